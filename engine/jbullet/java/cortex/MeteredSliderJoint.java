// Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.dynamics.RigidBody;
import com.bulletphysics.dynamics.constraintsolver.SliderConstraint;
import com.bulletphysics.linearmath.Transform;
import com.jme3.bullet.joints.SliderJoint;
import com.jme3.bullet.objects.PhysicsRigidBody;
import com.jme3.math.Matrix3f;
import com.jme3.math.Vector3f;

/**
 * jME's SliderJoint, whose applied impulse is what the joint gave its
 * bodies in the last physics step (see ImpulseMeter): jBullet's
 * SliderConstraint never writes it.
 */
public class MeteredSliderJoint extends SliderJoint {
    static final class Metered extends SliderConstraint {
        final ImpulseMeter meter;

        Metered(RigidBody a, RigidBody b, Transform fa, Transform fb, boolean useA) {
            super(a, b, fa, fb, useA);
            meter = new ImpulseMeter(a, b, fa.basis);
        }

        @Override
        public void buildJacobian() {
            meter.start();
            super.buildJacobian();
        }

        @Override
        public void solveConstraint(float timeStep) {
            meter.before();
            super.solveConstraint(timeStep);
            meter.after();
        }

        @Override
        public float getAppliedImpulse() {
            return meter.rowMax();
        }
    }

    public MeteredSliderJoint(PhysicsRigidBody nodeA, PhysicsRigidBody nodeB,
                              Vector3f pivotA, Vector3f pivotB,
                              Matrix3f rotA, Matrix3f rotB, boolean useLinearReferenceFrameA) {
        super(nodeA, nodeB, pivotA, pivotB, rotA, rotB, useLinearReferenceFrameA);
        constraint = new Metered(nodeA.getObjectId(), nodeB.getObjectId(),
                                 ImpulseMeter.frame(rotA, pivotA), ImpulseMeter.frame(rotB, pivotB),
                                 useLinearReferenceFrameA);
    }
}
