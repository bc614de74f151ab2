// Generated from org/engine.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.dynamics.RigidBody;
import com.bulletphysics.dynamics.constraintsolver.TypedConstraint;
import com.bulletphysics.dynamics.constraintsolver.TypedConstraintType;
import javax.vecmath.Vector3f;

/**
 * The springs of a spring joint on jBullet: each of the joint's three
 * angles (the rotation vector from the joint's frame in body A to its
 * frame in body B, in A's frame) is a soft row that the solver's passes
 * drive towards 0, as a spring and damper would over the step (see
 * org/engine.org).
 */
public class JointSpring extends TypedConstraint {
    final double[] fa, fb;
    final double stiffness, damping;
    private boolean pending;
    private final Vector3f[] axis = {new Vector3f(), new Vector3f(), new Vector3f()};
    private final double[] bias = new double[3], den = new double[3], acc = new double[3];
    private double gamma;
    private final Vector3f wa = new Vector3f(), wb = new Vector3f(), push = new Vector3f();

    /** Springs between `a` and `b` whose joint frames are `fa`, `fb`
     * (quaternions [x y z w] in each body's frame). */
    public JointSpring(RigidBody a, RigidBody b, double[] fa, double[] fb, double stiffness, double damping) {
        super(TypedConstraintType.D6_CONSTRAINT_TYPE, a, b);
        this.fa = fa; this.fb = fb; this.stiffness = stiffness; this.damping = damping;
    }

    @Override
    public void buildJacobian() {
        pending = true;
    }

    /** The step's rows: each angle, its axis in the world, the speed its
     * spring asks for, and the softness of a spring over `dt`. */
    private void setUp(double dt) {
        RigidBody a = getRigidBodyA(), b = getRigidBodyB();
        double[] qa = JointLimit.mul(JointLimit.orientation(a), fa);
        double[] q = JointLimit.mul(JointLimit.conj(qa), JointLimit.mul(JointLimit.orientation(b), fb));
        if (q[3] < 0) q = new double[] {-q[0], -q[1], -q[2], -q[3]};
        double s = Math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        double f = s < 1e-9 ? 2.0 : 2.0 * Math.atan2(s, q[3]) / s;
        double soft = damping + dt * stiffness;
        gamma = soft > 0 ? 1.0 / (dt * soft) : Double.POSITIVE_INFINITY;
        for (int i = 0; i < 3; i++) {
            double[] d = JointLimit.rotate(qa, i == 0 ? 1 : 0, i == 1 ? 1 : 0, i == 2 ? 1 : 0);
            axis[i].set((float) d[0], (float) d[1], (float) d[2]);
            den[i] = a.computeAngularImpulseDenominator(axis[i]) + b.computeAngularImpulseDenominator(axis[i]);
            bias[i] = soft > 0 ? stiffness * f * q[i] / soft : 0.0;
            acc[i] = 0.0;
        }
    }

    @Override
    public void solveConstraint(float timeStep) {
        if (pending) {
            setUp(timeStep);
            pending = false;
        }
        if (Double.isInfinite(gamma)) return;
        RigidBody a = getRigidBodyA(), b = getRigidBodyB();
        for (int i = 0; i < 3; i++) {
            Vector3f n = axis[i];
            a.getAngularVelocity(wa);
            b.getAngularVelocity(wb);
            double v = n.x * (wb.x - wa.x) + n.y * (wb.y - wa.y) + n.z * (wb.z - wa.z);
            double d = -(v + bias[i] + gamma * acc[i]) / (den[i] + gamma);
            acc[i] += d;
            push.scale((float) d, n);
            b.applyTorqueImpulse(push);
            push.negate();
            a.applyTorqueImpulse(push);
        }
    }
}
