// Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.dynamics.RigidBody;
import com.bulletphysics.dynamics.constraintsolver.Generic6DofConstraint;
import com.bulletphysics.linearmath.Transform;
import com.bulletphysics.linearmath.VectorUtil;
import com.jme3.bullet.joints.SixDofJoint;
import com.jme3.bullet.joints.motors.RotationalLimitMotor;
import com.jme3.bullet.joints.motors.TranslationalLimitMotor;
import com.jme3.bullet.objects.PhysicsRigidBody;
import com.jme3.bullet.util.Converter;
import com.jme3.math.Matrix3f;
import com.jme3.math.Vector3f;

/**
 * jME's SixDofJoint, solved as Bullet 2.8's btGeneric6DofConstraint
 * (the one Blender's FIXED, POINT and GENERIC constraints are) solves
 * its rows, and whose applied impulse (getAppliedImpulse) is what
 * Bullet 2.8 compares with a breaking threshold: the largest impulse of
 * one row in the last physics step. jBullet's own Generic6DofConstraint
 * (Bullet 2.72's) softens every row (a limit gets half the impulse it
 * needs in an iteration, a locked axis 0.7 of it), corrects errors at
 * other rates (0.5 for limits, 0.35 for locked axes, where Bullet 2.8
 * uses the world's 0.2), lets a limit pull as well as push, and never
 * writes its applied impulse; and its angular axes are not unit
 * vectors (the Y axis is as long as the Y angle's cosine), which makes
 * its limits pull back harder. Here the rows are Bullet 2.8's: angular
 * rows first, then linear, each along a unit axis; each row's impulse
 * makes the relative velocity along its axis what the error correction
 * wants (ERP 0.2); a
 * limit only pushes; a locked axis holds both ways; and when a breaking
 * threshold is set, no row's impulse in a step exceeds it, as Bullet 2.8
 * clamps a breakable constraint's rows. Motors are jBullet's.
 */
public class MeteredSixDofJoint extends SixDofJoint {
    /**
     * How much the Physics tab widens a locked angle on each side
     * (radians): jBullet frees an angle whose limits are equal.
     */
    public static final double ANGLE_LOCK_MARGIN = 1e-4;

    /**
     * The error reduction of Bullet 2.8's constraint rows: the solver's
     * btContactSolverInfo.m_erp, 0.2, which Blender never changes.
     */
    public static final float ERP = 0.2f;

    /**
     * How far (radians) a locked angle may start from its lock and still
     * be taken to start on it. Blender's two frames of a constraint are
     * one matrix, and an angle it locks at the start pose starts exactly
     * on the lock, held by no row until it moves; cortex's frames, made
     * through jME's float rotations, start it up to 1e-7 off, and a row
     * holding that from the first step turned addon-ragdoll's left arm
     * 0.03 rad/s from Blender's in it. So such an angle is locked at the
     * angle it starts at.
     */
    public static final float LOCK_NOISE = 1e-6f;

    private final RotationalLimitMotor[] motors = new RotationalLimitMotor[3];
    private final TranslationalLimitMotor linearMotor;

    static final class Metered extends Generic6DofConstraint {
        final ImpulseMeter meter;
        float threshold = Float.POSITIVE_INFINITY;
        private final javax.vecmath.Vector3f axis = new javax.vecmath.Vector3f();
        private final javax.vecmath.Vector3f va = new javax.vecmath.Vector3f();
        private final javax.vecmath.Vector3f vb = new javax.vecmath.Vector3f();
        private final javax.vecmath.Vector3f ra = new javax.vecmath.Vector3f();
        private final javax.vecmath.Vector3f rb = new javax.vecmath.Vector3f();
        private final javax.vecmath.Vector3f tmp = new javax.vecmath.Vector3f();
        private final javax.vecmath.Vector3f ta = new javax.vecmath.Vector3f();
        private final javax.vecmath.Vector3f tb = new javax.vecmath.Vector3f();
        private final javax.vecmath.Matrix3f inertia = new javax.vecmath.Matrix3f();
        private final float[] lockAt = new float[3];
        private boolean lockSet;

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
            this.timeStep = timeStep;
            for (int i = 0; i < 3; i++) {
                angularRow(i, timeStep);
            }
            for (int i = 0; i < 3; i++) {
                linearRow(i, timeStep);
            }
            meter.after();
        }

        private static float clamp(float x, float lo, float hi) {
            return x < lo ? lo : (x > hi ? hi : x);
        }

        /**
         * Angle i: a motor as jBullet drives it, or a limit as Bullet 2.8
         * holds it, along the unit axis (jBullet's axes are not): a range
         * limit only pushes, a locked angle is held both ways.
         */
        private void angularRow(int i, float dt) {
            com.bulletphysics.dynamics.constraintsolver.RotationalLimitMotor m = angularLimits[i];
            // a locked angle (limits equal, widened by ANGLE_LOCK_MARGIN) is
            // held whenever it is off the lock, by however little, as Bullet
            // 2.8 holds an angle whose limits are equal; the widened range
            // alone would leave it free within ANGLE_LOCK_MARGIN
            boolean locked = !m.enableMotor && m.loLimit <= m.hiLimit
                && m.hiLimit - m.loLimit <= 3 * ANGLE_LOCK_MARGIN;
            if (!lockSet) {
                // where each locked angle is held: its lock, or the angle
                // it starts at when that lies within float noise of it
                for (int k = 0; k < 3; k++) {
                    com.bulletphysics.dynamics.constraintsolver.RotationalLimitMotor l = angularLimits[k];
                    float centre = 0.5f * (l.loLimit + l.hiLimit);
                    float start = getAngle(k);
                    lockAt[k] = Math.abs(start - centre) < LOCK_NOISE ? start : centre;
                }
                lockSet = true;
            }
            float off = getAngle(i) - lockAt[i];
            if (locked ? off == 0f : !m.needApplyTorques()) {
                return;
            }
            getAxis(i, axis);
            if (!locked && m.currentLimit == 0) {
                m.solveAngularLimits(dt, axis, 1f / jacAng[i].getDiagonal(), rbA, rbB);
                return;
            }
            axis.normalize();
            float inv = 1f / (angularMass(rbA, axis) + angularMass(rbB, axis));
            rbA.getAngularVelocity(va);
            rbB.getAngularVelocity(vb);
            va.sub(vb);
            float error = m.currentLimitError;
            float lo = -threshold;
            float hi = threshold;
            if (locked) {
                // held both ways, towards the lock itself
                error = off;
            } else if (m.currentLimit == 1) {
                lo = 0f;
            } else {
                hi = 0f;
            }
            float target = -ERP * error / dt;
            float old = m.accumulatedImpulse;
            float sum = clamp(old + (target - axis.dot(va)) * inv, lo, hi);
            m.accumulatedImpulse = sum;
            tmp.scale(sum - old, axis);
            rbA.applyTorqueImpulse(tmp);
            tmp.negate();
            rbB.applyTorqueImpulse(tmp);
        }

        /**
         * Is angle j held by a limit in this substep, as Bullet 2.8 counts
         * it: beyond a range limit, or locked (an angle whose limits are
         * equal, here widened by ANGLE_LOCK_MARGIN) and off its lock?
         */
        private boolean angleHeld(int j) {
            com.bulletphysics.dynamics.constraintsolver.RotationalLimitMotor m = angularLimits[j];
            if (!m.enableMotor && m.loLimit <= m.hiLimit && m.hiLimit - m.loLimit <= 3 * ANGLE_LOCK_MARGIN) {
                return getAngle(j) != lockAt[j];
            }
            return m.currentLimit != 0;
        }

        /** (I^-1 t) . t of body `body`, world axes. */
        private float angularMass(RigidBody body, javax.vecmath.Vector3f t) {
            body.getInvInertiaTensorWorld(inertia);
            inertia.transform(t, tmp);
            return tmp.dot(t);
        }

        /**
         * Axis i: locked, limited or free, as Bullet 2.8 holds it, with the
         * frame offset it uses by default (m_useOffsetForConstraintFrame):
         * each body is pushed at its own frame's origin (the part of the
         * lever along the axis, which the offset moves by the mass ratio,
         * turns nothing), and when one body is static and the two angles
         * about the other axes are both held, the row turns neither body:
         * it pushes the moving one's centre of mass only.
         */
        private void linearRow(int i, float dt) {
            com.bulletphysics.dynamics.constraintsolver.TranslationalLimitMotor l = linearLimits;
            if (!l.isLimited(i)) {
                return;
            }
            (useLinearReferenceFrameA ? calculatedTransformA : calculatedTransformB).basis.getColumn(i, axis);
            tmp.sub(calculatedTransformB.origin, calculatedTransformA.origin);
            float depth = tmp.dot(axis);
            float min = VectorUtil.getCoord(l.lowerLimit, i);
            float max = VectorUtil.getCoord(l.upperLimit, i);
            float lo = -threshold;
            float hi = threshold;
            if (min < max) {
                if (depth > max) {
                    depth -= max;
                    lo = 0f;
                } else if (depth < min) {
                    depth -= min;
                    hi = 0f;
                } else {
                    return;
                }
            } else {
                depth -= min;
            }
            float imA = rbA.getInvMass();
            float imB = rbB.getInvMass();
            float factA = imA + imB > 0f ? imB / (imA + imB) : 0.5f;
            float factB = 1f - factA;
            boolean rotAllowed = !(angleHeld((i + 1) % 3) && angleHeld((i + 2) % 3));
            boolean turnScaled = (imA < 1.1920929E-7f || imB < 1.1920929E-7f) && !rotAllowed;
            ra.sub(calculatedTransformA.origin, rbA.getCenterOfMassPosition(tmp));
            rb.sub(calculatedTransformB.origin, rbB.getCenterOfMassPosition(tmp));
            ta.cross(ra, axis);
            tb.cross(rb, axis);
            if (turnScaled) {
                ta.scale(factA);
                tb.scale(factB);
            }
            float inv = 1f / (imA + imB + angularMass(rbA, ta) + angularMass(rbB, tb));
            rbA.getLinearVelocity(va);
            rbB.getLinearVelocity(vb);
            float vel = axis.dot(va) - axis.dot(vb);
            rbA.getAngularVelocity(va);
            rbB.getAngularVelocity(vb);
            vel += ta.dot(va) - tb.dot(vb);
            float old = VectorUtil.getCoord(l.accumulatedImpulse, i);
            float sum = clamp(old + (ERP * depth / dt - vel) * inv, lo, hi);
            VectorUtil.setCoord(l.accumulatedImpulse, i, sum);
            float p = sum - old;
            tmp.scale(p, axis);
            rbA.applyCentralImpulse(tmp);
            tmp.negate();
            rbB.applyCentralImpulse(tmp);
            tmp.scale(p, ta);
            rbA.applyTorqueImpulse(tmp);
            tmp.scale(-p, tb);
            rbB.applyTorqueImpulse(tmp);
        }

        /** The largest impulse of one row (linear or angular) in the step. */
        @Override
        public float getAppliedImpulse() {
            float best = 0f;
            for (int i = 0; i < 3; i++) {
                best = Math.max(best, Math.abs(VectorUtil.getCoord(linearLimits.accumulatedImpulse, i)));
                best = Math.max(best, Math.abs(angularLimits[i].accumulatedImpulse));
            }
            return best;
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

    /**
     * Break at `threshold`: no row's impulse in a step exceeds it, as
     * Bullet 2.8 clamps the rows of a breakable constraint (the caller
     * removes the joint when getAppliedImpulse reaches it).
     */
    public void setBreakingThreshold(float threshold) {
        ((Metered) constraint).threshold = threshold;
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
