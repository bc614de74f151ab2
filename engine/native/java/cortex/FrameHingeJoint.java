// Generated from org/engine.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.jme3.bullet.RotationOrder;
import com.jme3.bullet.joints.New6Dof;
import com.jme3.bullet.joints.motors.MotorParam;
import com.jme3.bullet.joints.motors.RotationMotor;
import com.jme3.bullet.objects.PhysicsRigidBody;
import com.jme3.math.Matrix3f;
import com.jme3.math.Vector3f;

/**
 * A hinge whose frame in each body is given whole, as Blender builds
 * its hinges: the axis is the frame's Z, and the angle is zero where
 * the two frames agree. Native Bullet: a New6Dof whose translations
 * and turns about X and Y are locked.
 */
public class FrameHingeJoint extends New6Dof {
    private static final int Z = 5;
    private final Matrix3f rotA;
    private final Matrix3f rotB;

    public FrameHingeJoint(PhysicsRigidBody nodeA, PhysicsRigidBody nodeB,
                           Vector3f pivotA, Vector3f pivotB,
                           Matrix3f rotA, Matrix3f rotB) {
        super(nodeA, nodeB, pivotA, pivotB, rotA, rotB, RotationOrder.XYZ);
        this.rotA = rotA.clone();
        this.rotB = rotB.clone();
        for (int i = 0; i < 5; i++) {
            set(MotorParam.LowerLimit, i, 0f);
            set(MotorParam.UpperLimit, i, 0f);
        }
        setLimit(1f, -1f);
        setFeedback(true);
    }

    /** Limit the hinge angle to [low, high] radians; low > high frees it. */
    public void setLimit(float low, float high) {
        set(MotorParam.LowerLimit, Z, low);
        set(MotorParam.UpperLimit, Z, high);
    }

    public float getLowerLimit() {
        return get(MotorParam.LowerLimit, Z);
    }

    public float getUpperLimit() {
        return get(MotorParam.UpperLimit, Z);
    }

    /** The angle between the two frames about the axis, in radians. */
    public float getHingeAngle() {
        return getAngles(new Vector3f()).z;
    }

    /** Drive the hinge at targetVelocity (rad/s) with at most maxImpulse per 1/60 s step. */
    public void enableMotor(boolean enable, float targetVelocity, float maxImpulse) {
        RotationMotor m = getRotationMotor(2);
        m.setMotorEnabled(enable);
        m.set(MotorParam.TargetVelocity, targetVelocity);
        m.set(MotorParam.MaxMotorForce, maxImpulse * 60f);
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
