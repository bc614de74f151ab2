// Generated from org/shapes.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.collision.broadphase.CollisionAlgorithm;
import com.bulletphysics.collision.broadphase.CollisionAlgorithmConstructionInfo;
import com.bulletphysics.collision.broadphase.DispatcherInfo;
import com.bulletphysics.collision.dispatch.CollisionAlgorithmCreateFunc;
import com.bulletphysics.collision.dispatch.CollisionObject;
import com.bulletphysics.collision.dispatch.ManifoldResult;
import com.bulletphysics.collision.narrowphase.PersistentManifold;
import com.bulletphysics.util.ObjectArrayList;

/**
 * A jBullet collision algorithm that keeps a pair's contacts in a
 * manifold: the dispatcher's, or one of its own, released with it. It
 * has no time of impact. See org/shapes.org.
 */
public abstract class ManifoldAlgorithm extends CollisionAlgorithm {
    protected PersistentManifold manifold;
    protected boolean ownManifold;

    /** Set up from `ci` for bodies `a` and `b`, made by `from`. */
    protected void start(CollisionAlgorithmConstructionInfo ci, CollisionObject a,
                         CollisionObject b, CollisionAlgorithmCreateFunc from) {
        init(ci);
        manifold = ci.manifold;
        if (manifold == null && ci.dispatcher1.needsCollision(a, b)) {
            manifold = ci.dispatcher1.getNewManifold(a, b);
            ownManifold = true;
        }
        internalSetCreateFunc(from);
    }

    @Override
    public void destroy() {
        if (ownManifold && manifold != null) {
            dispatcher.releaseManifold(manifold);
        }
        manifold = null;
        ownManifold = false;
    }

    @Override
    public float calculateTimeOfImpact(CollisionObject a, CollisionObject b, DispatcherInfo info,
                                       ManifoldResult out) {
        return 1f;
    }

    @Override
    public void getAllContactManifolds(ObjectArrayList<PersistentManifold> out) {
        if (manifold != null && ownManifold) {
            out.add(manifold);
        }
    }
}
