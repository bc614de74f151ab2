// Generated from org/engine.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.collision.dispatch.CollisionObject;
import com.bulletphysics.collision.narrowphase.PersistentManifold;
import com.bulletphysics.dynamics.RigidBody;
import com.bulletphysics.dynamics.constraintsolver.ContactSolverInfo;
import com.bulletphysics.dynamics.constraintsolver.SequentialImpulseConstraintSolver;
import com.bulletphysics.dynamics.constraintsolver.SolverBody;
import com.bulletphysics.dynamics.constraintsolver.TypedConstraint;
import com.bulletphysics.linearmath.IDebugDraw;
import com.bulletphysics.util.ObjectArrayList;
import java.lang.reflect.Field;

/**
 * jBullet's sequential-impulse solver, which after its own iterations
 * solves cortex's limit rows (JointLimit) `passes` more times, so that
 * they have the last word over contacts; see org/engine.org.
 */
public class LimitSolver extends SequentialImpulseConstraintSolver {
    private static final Field SOLVER_BODIES;
    static {
        try {
            SOLVER_BODIES = SequentialImpulseConstraintSolver.class.getDeclaredField("tmpSolverBodyPool");
            SOLVER_BODIES.setAccessible(true);
        } catch (NoSuchFieldException e) {
            throw new ExceptionInInitializerError(e);
        }
    }

    /** How many times the limit rows are solved after the iterations. */
    public final int passes;
    /** Whether those passes hold the joints' pivots together too. */
    public final boolean points;
    private final ObjectArrayList<SolverBody> solverBodies;

    @SuppressWarnings("unchecked")
    public LimitSolver(int passes, boolean points) {
        this.passes = passes;
        this.points = points;
        try {
            solverBodies = (ObjectArrayList<SolverBody>) SOLVER_BODIES.get(this);
        } catch (IllegalAccessException e) {
            throw new IllegalStateException(e);
        }
    }

    private void sync(RigidBody b, boolean toBody) {
        if (b.getIslandTag() >= 0 && b.getCompanionId() >= 0) {
            SolverBody s = solverBodies.getQuick(b.getCompanionId());
            if (toBody) s.writebackVelocity(); else s.readVelocity();
        }
    }

    @Override
    public float solveGroupCacheFriendlyIterations(ObjectArrayList<CollisionObject> bodies, int numBodies,
            ObjectArrayList<PersistentManifold> manifolds, int manifoldOffset, int numManifolds,
            ObjectArrayList<TypedConstraint> constraints, int constraintsOffset, int numConstraints,
            ContactSolverInfo info, IDebugDraw debugDrawer) {
        float r = super.solveGroupCacheFriendlyIterations(bodies, numBodies, manifolds, manifoldOffset, numManifolds,
                constraints, constraintsOffset, numConstraints, info, debugDrawer);
        for (int p = 0; p < passes; p++) {
            for (int j = 0; j < numConstraints; j++) {
                TypedConstraint c = constraints.getQuick(constraintsOffset + j);
                if (!(c instanceof JointLimit)) continue;
                RigidBody a = c.getRigidBodyA(), b = c.getRigidBodyB();
                sync(a, true);
                sync(b, true);
                ((JointLimit) c).solveTail(info.timeStep, points);
                sync(a, false);
                sync(b, false);
            }
        }
        return r;
    }
}
