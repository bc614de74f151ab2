// Generated from org/engine.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.collision.broadphase.BroadphaseNativeType;
import com.bulletphysics.collision.broadphase.CollisionAlgorithm;
import com.bulletphysics.collision.broadphase.CollisionAlgorithmConstructionInfo;
import com.bulletphysics.collision.dispatch.CollisionAlgorithmCreateFunc;
import com.bulletphysics.collision.dispatch.CollisionDispatcher;
import com.bulletphysics.collision.dispatch.CollisionObject;
import com.bulletphysics.dynamics.constraintsolver.ContactSolverInfo;

/**
 * A box against a static box (the floor), neither thinner than `size`,
 * meets through BoxBoxAlgorithm, which finds all the points of their
 * contact at once; any other pair of boxes meets as
 * SmallConvexAlgorithm has it. See org/engine.org.
 */
public final class FloorBoxes extends CollisionAlgorithmCreateFunc {
    private final CollisionAlgorithmCreateFunc boxes = new BoxBoxAlgorithm.CreateFunc();
    private final CollisionAlgorithmCreateFunc others;
    private final float size;

    private FloorBoxes(CollisionAlgorithmCreateFunc others, float size) {
        this.others = others;
        this.size = size;
    }

    /** Have two boxes in `dispatcher` meet so; `size` and `solver` as
     * SmallConvexAlgorithm.register takes them (every pair). */
    public static void register(CollisionDispatcher dispatcher, float size, ContactSolverInfo solver) {
        BroadphaseNativeType box = BroadphaseNativeType.BOX_SHAPE_PROXYTYPE;
        CollisionAlgorithmCreateFunc own = dispatcher.getCollisionConfiguration().getCollisionAlgorithmCreateFunc(box, box);
        dispatcher.registerCollisionCreateFunc(box.ordinal(), box.ordinal(),
            new FloorBoxes(new SmallConvexAlgorithm.CreateFunc(own, size, true, solver), size));
    }

    @Override
    public CollisionAlgorithm createCollisionAlgorithm(CollisionAlgorithmConstructionInfo ci,
                                                       CollisionObject a, CollisionObject b) {
        boolean floor = a.isStaticObject() || b.isStaticObject();
        boolean thick = Math.min(SmallConvexAlgorithm.thickness(a.getCollisionShape()),
                                 SmallConvexAlgorithm.thickness(b.getCollisionShape())) >= size;
        return (floor && thick ? boxes : others).createCollisionAlgorithm(ci, a, b);
    }

    @Override
    public void releaseCollisionAlgorithm(CollisionAlgorithm algo) {
    }
}
