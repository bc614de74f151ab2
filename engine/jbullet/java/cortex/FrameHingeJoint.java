// Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.dynamics.constraintsolver.HingeConstraint;
import com.bulletphysics.linearmath.Transform;
import com.jme3.bullet.joints.PhysicsJoint;
import com.jme3.bullet.objects.PhysicsRigidBody;
import com.jme3.math.Matrix3f;
import com.jme3.math.Vector3f;

/**
 * A hinge whose frame in each body is given whole, as Bullet's
 * btHingeConstraint(rbA, rbB, frameInA, frameInB) takes it and as
 * Blender builds its hinges: the axis is the frame's Z, and the angle
 * is zero where the two frames agree. jME's HingeJoint takes only an
 * axis per body and guesses the rest of the frame, which moves the
 * zero of the limits.
 */
public class FrameHingeJoint extends PhysicsJoint {
    private final Matrix3f rotA;
    private final Matrix3f rotB;

    public FrameHingeJoint(PhysicsRigidBody nodeA, PhysicsRigidBody nodeB,
                           Vector3f pivotA, Vector3f pivotB,
                           Matrix3f rotA, Matrix3f rotB) {
        super(nodeA, nodeB, pivotA, pivotB);
        this.rotA = rotA.clone();
        this.rotB = rotB.clone();
        constraint = new Metered(nodeA.getObjectId(), nodeB.getObjectId(),
                                 ImpulseMeter.frame(rotA, pivotA), ImpulseMeter.frame(rotB, pivotB));
    }

    /** jBullet's hinge, with an ImpulseMeter for its applied impulse. */
    static final class Metered extends HingeConstraint {
        final ImpulseMeter meter;

        Metered(com.bulletphysics.dynamics.RigidBody a, com.bulletphysics.dynamics.RigidBody b,
                Transform fa, Transform fb) {
            super(a, b, fa, fb);
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

    private HingeConstraint hinge() {
        return (HingeConstraint) constraint;
    }

    /** Limit the hinge angle to [low, high] radians; low > high frees it. */
    public void setLimit(float low, float high) {
        hinge().setLimit(low, high);
    }

    public float getLowerLimit() {
        return hinge().getLowerLimit();
    }

    public float getUpperLimit() {
        return hinge().getUpperLimit();
    }

    /** The angle between the two frames about the axis, in radians. */
    public float getHingeAngle() {
        return hinge().getHingeAngle();
    }

    /** Drive the hinge at targetVelocity (rad/s) with at most maxImpulse. */
    public void enableMotor(boolean enable, float targetVelocity, float maxImpulse) {
        hinge().enableAngularMotor(enable, targetVelocity, maxImpulse);
    }

    /** The hinge's frame in body A's frame. */
    public Matrix3f getRotA() {
        return rotA.clone();
    }

    /** The hinge's frame in body B's frame. */
    public Matrix3f getRotB() {
        return rotB.clone();
    }
}
