// Generated from org/engine.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.jme3.bullet.PhysicsSpace;
import com.jme3.bullet.PhysicsTickListener;
import com.jme3.bullet.RotationOrder;
import com.jme3.bullet.joints.New6Dof;
import com.jme3.bullet.joints.motors.MotorParam;
import com.jme3.bullet.joints.motors.RotationMotor;
import com.jme3.bullet.objects.PhysicsRigidBody;
import com.jme3.math.Matrix3f;
import com.jme3.math.Vector3f;

/**
 * The Physics tab's 6-DOF joint on native Bullet: a New6Dof (Bullet's
 * btGeneric6DofSpring2Constraint, whose rows hold a locked axis from
 * the first step) with jME's SixDofJoint methods that cortex calls,
 * reporting its applied impulse (native Bullet writes it). An axis is
 * locked when its lower limit equals its upper one, free when the
 * lower is above the upper; angles are Euler XYZ in the joint's frame.
 */
public class MeteredSixDofJoint extends New6Dof implements PhysicsTickListener {
    /**
     * How much the Physics tab widens a locked angle on each side
     * (radians): none, New6Dof locks an angle whose limits are equal.
     */
    public static final double ANGLE_LOCK_MARGIN = 0.0;

    private AngularMotor[] motors = new AngularMotor[3];
    /** The limits asked for: linear X, Y, Z then angular X, Y, Z. */
    private final float[] lower = new float[6];
    private final float[] upper = new float[6];
    /** Whether each axis's range limit is in the solver now. */
    private final boolean[] engaged = new boolean[6];
    private final Vector3f angles = new Vector3f();
    private final Vector3f originA = new Vector3f();
    private final Vector3f originB = new Vector3f();
    private final Matrix3f basisA = new Matrix3f();

    public MeteredSixDofJoint(PhysicsRigidBody nodeA, PhysicsRigidBody nodeB,
                              Vector3f pivotA, Vector3f pivotB,
                              Matrix3f rotA, Matrix3f rotB, boolean useLinearReferenceFrameA) {
        super(nodeA, nodeB, pivotA, pivotB, rotA, rotB, RotationOrder.XYZ);
        for (int i = 0; i < 3; i++) {
            motors[i] = new AngularMotor(getRotationMotor(i));
        }
        setFeedback(true);
    }

    public void setLinearLowerLimit(Vector3f v) {
        setLimits(lower, 0, v);
    }

    public void setLinearUpperLimit(Vector3f v) {
        setLimits(upper, 0, v);
    }

    public void setAngularLowerLimit(Vector3f v) {
        setLimits(lower, 3, v);
    }

    public void setAngularUpperLimit(Vector3f v) {
        setLimits(upper, 3, v);
    }

    public Vector3f getLinearLowerLimit(Vector3f out) {
        return out.set(lower[0], lower[1], lower[2]);
    }

    public Vector3f getLinearUpperLimit(Vector3f out) {
        return out.set(upper[0], upper[1], upper[2]);
    }

    public Vector3f getAngularLowerLimit(Vector3f out) {
        return out.set(lower[3], lower[4], lower[5]);
    }

    public Vector3f getAngularUpperLimit(Vector3f out) {
        return out.set(upper[3], upper[4], upper[5]);
    }

    private void setLimits(float[] limits, int first, Vector3f v) {
        for (int i = 0; i < 3; i++) {
            limits[first + i] = v.get(i);
            engage(first + i, true);
        }
    }

    /**
     * Put axis `dof`'s limits in the solver (a range limit makes rows),
     * or, for a range limit, take them out (the axis turns free).
     */
    private void engage(int dof, boolean on) {
        engaged[dof] = on;
        float lo = on ? lower[dof] : upper[dof];
        float hi = on ? upper[dof] : lower[dof];
        set(MotorParam.LowerLimit, dof, lo);
        set(MotorParam.UpperLimit, dof, hi);
    }

    /**
     * Before a substep: a range limit is in the solver only while its
     * axis is beyond it, as Bullet 2.8's btGeneric6DofConstraint (what
     * Blender's GENERIC and MOTOR are) makes a limit's row. The
     * spring-2 constraint makes rows for a range limit the axis is
     * inside too, slowing the approach to it (0.2 of the distance a
     * substep); locked and free axes are left as they are.
     */
    private void engageRangeLimits() {
        boolean any = false;
        for (int dof = 0; dof < 6; dof++) {
            any |= lower[dof] < upper[dof];
        }
        if (!any) {
            return;
        }
        getAngles(angles);
        calculatedOriginA(originA);
        calculatedOriginB(originB).subtractLocal(originA);
        calculatedBasisA(basisA);
        for (int dof = 0; dof < 6; dof++) {
            if (lower[dof] < upper[dof]) {
                float x = dof < 3 ? basisA.getColumn(dof).dot(originB) : angles.get(dof - 3);
                boolean beyond = x < lower[dof] || x > upper[dof];
                if (beyond != engaged[dof]) {
                    engage(dof, beyond);
                }
            }
        }
    }

    /** The motor about axis `index` (0 X, 1 Y, 2 Z of the joint's frame). */
    public AngularMotor getRotationalLimitMotor(int index) {
        return motors[index];
    }

    /** Native Bullet clamps and breaks the constraint itself at `threshold`. */
    public void setBreakingThreshold(float threshold) {
        setBreakingImpulseThreshold(threshold);
    }

    /** In a space, the motors learn each substep's length before it. */
    @Override
    public void setPhysicsSpace(PhysicsSpace space) {
        PhysicsSpace old = getPhysicsSpace();
        if (old != null && old != space) {
            old.removeTickListener(this);
        }
        super.setPhysicsSpace(space);
        if (space != null && space != old) {
            space.addTickListener(this);
        }
    }

    @Override
    public void cloneFields(com.jme3.util.clone.Cloner cloner, Object original) {
        super.cloneFields(cloner, original);
        AngularMotor[] old = motors;
        motors = new AngularMotor[3];
        for (int i = 0; i < 3; i++) {
            motors[i] = new AngularMotor(getRotationMotor(i));
            motors[i].maxImpulse = old[i].maxImpulse;
            motors[i].step = old[i].step;
        }
    }

    @Override
    public void prePhysicsTick(PhysicsSpace space, float timeStep) {
        engageRangeLimits();
        for (AngularMotor m : motors) {
            m.step(timeStep);
        }
    }

    @Override
    public void physicsTick(PhysicsSpace space, float timeStep) {
    }

    /**
     * A motor about one axis, set as jBullet's RotationalLimitMotor is:
     * its largest "force" is the largest impulse in one substep, which
     * the spring-2 constraint takes as a force over the substep.
     */
    public static final class AngularMotor {
        final RotationMotor motor;
        private float maxImpulse;
        private float step = 1f / 60f;

        AngularMotor(RotationMotor motor) {
            this.motor = motor;
            maxImpulse = motor.get(MotorParam.MaxMotorForce) * step;
        }

        void step(float seconds) {
            if (seconds > 0f && seconds != step) {
                step = seconds;
                motor.set(MotorParam.MaxMotorForce, maxImpulse / step);
            }
        }

        public boolean isEnableMotor() {
            return motor.isMotorEnabled();
        }

        public void setEnableMotor(boolean enable) {
            motor.setMotorEnabled(enable);
        }

        public float getTargetVelocity() {
            return motor.get(MotorParam.TargetVelocity);
        }

        public void setTargetVelocity(float velocity) {
            motor.set(MotorParam.TargetVelocity, velocity);
        }

        /** The largest impulse the motor gives in one substep. */
        public float getMaxMotorForce() {
            return maxImpulse;
        }

        public void setMaxMotorForce(float impulse) {
            maxImpulse = impulse;
            motor.set(MotorParam.MaxMotorForce, impulse / step);
        }
    }
}
