// Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.dynamics.RigidBody;
import com.bulletphysics.dynamics.constraintsolver.Generic6DofConstraint;
import com.bulletphysics.linearmath.Transform;
import com.jme3.bullet.joints.SixDofJoint;
import com.jme3.bullet.joints.motors.RotationalLimitMotor;
import com.jme3.bullet.joints.motors.TranslationalLimitMotor;
import com.jme3.bullet.objects.PhysicsRigidBody;
import com.jme3.bullet.util.Converter;
import com.jme3.math.Matrix3f;
import com.jme3.math.Vector3f;

/**
 * jME's SixDofJoint, whose applied impulse (getAppliedImpulse) is what
 * the joint gave its bodies in the last physics step, measured by an
 * ImpulseMeter: jBullet's own Generic6DofConstraint never writes it.
 * Everything else is jME's SixDofJoint.
 */
public class MeteredSixDofJoint extends SixDofJoint {
    private final RotationalLimitMotor[] motors = new RotationalLimitMotor[3];
    private final TranslationalLimitMotor linearMotor;

    static final class Metered extends Generic6DofConstraint {
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

    public MeteredSixDofJoint(PhysicsRigidBody nodeA, PhysicsRigidBody nodeB,
                              Vector3f pivotA, Vector3f pivotB,
                              Matrix3f rotA, Matrix3f rotB, boolean useLinearReferenceFrameA) {
        super(nodeA, nodeB, pivotA, pivotB, rotA, rotB, useLinearReferenceFrameA);
        Metered c = new Metered(nodeA.getObjectId(), nodeB.getObjectId(),
                                ImpulseMeter.frame(rotA, pivotA), ImpulseMeter.frame(rotB, pivotB),
                                useLinearReferenceFrameA);
        constraint = c;
        for (int i = 0; i < 3; i++) {
            motors[i] = new RotationalLimitMotor(c.getRotationalLimitMotor(i));
        }
        linearMotor = new TranslationalLimitMotor(c.getTranslationalLimitMotor());
    }

    @Override
    public RotationalLimitMotor getRotationalLimitMotor(int index) {
        return motors[index];
    }

    @Override
    public TranslationalLimitMotor getTranslationalLimitMotor() {
        return linearMotor;
    }

    /** The step's impulse (world axes), summed over the solver's iterations. */
    public Vector3f getStepImpulse() {
        return Converter.convert(((Metered) constraint).meter.getImpulse(new javax.vecmath.Vector3f()));
    }
}
