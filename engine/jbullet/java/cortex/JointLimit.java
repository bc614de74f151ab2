// Generated from org/engine.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.dynamics.RigidBody;
import com.bulletphysics.dynamics.constraintsolver.TypedConstraint;
import com.bulletphysics.dynamics.constraintsolver.TypedConstraintType;
import com.bulletphysics.linearmath.Transform;
import javax.vecmath.Matrix3f;
import javax.vecmath.Quat4f;
import javax.vecmath.Vector3f;

/**
 * A joint's limits as cortex's proprioception reads them (a hinge's twist angle about its axis; a
 * cone's twist about X and the Y and Z of its swing's rotation vector,
 * Blender's axes), solved as one-sided angular rows whose impulse only
 * pushes, speculatively: a row within `activation` of its limit lets
 * the joint approach only as fast as reaches the limit at the step's
 * end, and one past it is stopped where it is (`erp` of the error per
 * step is taken back, 0 unless set: see org/engine.org).
 * Frames are quaternions [x y z w] of the joint frame in each body
 * (as cortex.proprioception/rest-frames finds them). cortex adds one
 * beside each hinge and cone it builds on jBullet (cortex.engine/limit-rows!);
 * see org/engine.org and org/physics-trust.org.
 */
public class JointLimit extends TypedConstraint {
    final double[] fa, fb, axis;
    final boolean hinge;
    final double lo, hi, twist, swingY, swingZ;
    /** How much of a joint's overshoot its rows take back each step: 0,
     * so that a joint already past its limit is only stopped there (see
     * org/engine.org). */
    public float erp = 0f;
    public boolean speculative = true;
    public double activation = 0.3;
    /** The joint's pivot in each body's frame (its centre of mass and
     * principal axes), for `solveTail`'s point rows; null: none. */
    public Vector3f pivotA, pivotB;
    /** How much of the pivots' gap `solveTail`'s point rows close per step. */
    public float pointErp = 0.2f;

    final Vector3f[] dir = new Vector3f[6];
    final double[] k = new double[6], c = new double[6], acc = new double[6];
    int rows;
    public double v0, v1, v2;

    public JointLimit(RigidBody a, RigidBody b, double[] fa, double[] fb, double[] axis, double lo, double hi) {
        super(TypedConstraintType.HINGE_CONSTRAINT_TYPE, a, b);
        this.fa = fa; this.fb = fb; this.axis = axis; this.hinge = true;
        this.lo = lo; this.hi = hi; this.twist = 0; this.swingY = 0; this.swingZ = 0;
        for (int i = 0; i < 6; i++) dir[i] = new Vector3f();
    }

    public JointLimit(RigidBody a, RigidBody b, double[] fa, double[] fb, double twist, double swingY, double swingZ) {
        super(TypedConstraintType.D6_CONSTRAINT_TYPE, a, b);
        this.fa = fa; this.fb = fb; this.axis = null; this.hinge = false;
        this.lo = 0; this.hi = 0; this.twist = twist; this.swingY = swingY; this.swingZ = swingZ;
        for (int i = 0; i < 6; i++) dir[i] = new Vector3f();
    }

    static double[] mul(double[] p, double[] q) {
        return new double[] {
            p[3]*q[0] + p[0]*q[3] + p[1]*q[2] - p[2]*q[1],
            p[3]*q[1] - p[0]*q[2] + p[1]*q[3] + p[2]*q[0],
            p[3]*q[2] + p[0]*q[1] - p[1]*q[0] + p[2]*q[3],
            p[3]*q[3] - p[0]*q[0] - p[1]*q[1] - p[2]*q[2]};
    }
    static double[] conj(double[] q) { return new double[] {-q[0], -q[1], -q[2], q[3]}; }
    static double[] rotate(double[] q, double x, double y, double z) {
        double ux = q[0], uy = q[1], uz = q[2], w = q[3];
        double tx = 2 * (uy*z - uz*y), ty = 2 * (uz*x - ux*z), tz = 2 * (ux*y - uy*x);
        return new double[] {x + w*tx + uy*tz - uz*ty, y + w*ty + uz*tx - ux*tz, z + w*tz + ux*ty - uy*tx};
    }
    static double wrap(double a) {
        double t = a - 2 * Math.PI * Math.floor((a + Math.PI) / (2 * Math.PI));
        return t;
    }
    static double[] orientation(RigidBody b) {
        Quat4f q = b.getOrientation(new Quat4f());
        return new double[] {q.x, q.y, q.z, q.w};
    }

    void row(double C, double[] d, double sign) {
        if (C >= activation && speculative) return;
        if (C >= 0 && !speculative) return;
        Vector3f v = dir[rows];
        v.set((float) (sign * d[0]), (float) (sign * d[1]), (float) (sign * d[2]));
        double den = getRigidBodyA().computeAngularImpulseDenominator(v)
                   + getRigidBodyB().computeAngularImpulseDenominator(v);
        if (den < 1e-12) return;
        k[rows] = 1.0 / den;
        c[rows] = C;
        acc[rows] = 0;
        rows++;
    }

    @Override
    public void buildJacobian() {
        rows = 0;
        double[] wa = mul(orientation(getRigidBodyA()), fa);
        double[] wb = mul(orientation(getRigidBodyB()), fb);
        double[] q = mul(conj(wa), wb);
        if (hinge) {
            double v = wrap(2 * Math.atan2(q[0]*axis[0] + q[1]*axis[1] + q[2]*axis[2], q[3]));
            double[] a = rotate(wa, axis[0], axis[1], axis[2]);
            v0 = v;
            row(v - lo, a, 1);
            row(hi - v, a, -1);
        } else {
            // Blender's axes: x, -z, y
            double x = q[0], y = -q[2], z = q[1], w = q[3];
            if (w < 0) { x = -x; y = -y; z = -z; w = -w; }
            double t = 2 * Math.atan2(x, w);
            double[] s = mul(new double[] {x, y, z, w}, new double[] {-Math.sin(t / 2), 0, 0, Math.cos(t / 2)});
            if (s[3] < 0) { s[0] = -s[0]; s[1] = -s[1]; s[2] = -s[2]; s[3] = -s[3]; }
            double n = Math.sqrt(s[0]*s[0] + s[1]*s[1] + s[2]*s[2]);
            double kk = n < 1e-12 ? 2.0 : 2 * Math.atan2(n, s[3]) / n;
            double sy = kk * s[1], sz = kk * s[2];
            t = wrap(t);
            v0 = t; v1 = sy; v2 = sz;
            double[] ax = rotate(wb, 1, 0, 0);
            double[] ay = rotate(wa, 0, 0, -1);
            double[] az = rotate(wa, 0, 1, 0);
            row(twist - t, ax, -1);
            row(t + twist, ax, 1);
            row(swingY - sy, ay, -1);
            row(sy + swingY, ay, 1);
            row(swingZ - sz, az, -1);
            row(sz + swingZ, az, 1);
        }
    }

    /**
     * What cortex.LimitSolver solves after the solver's iterations: the
     * joint's pivots held together (a ball joint's three rows, solved
     * as one block, closing `pointErp` of their gap per step) when
     * `pivotA` is set, then the limit rows.
     */
    public void solveTail(float timeStep, boolean points) {
        solveConstraint(timeStep);
        if (points && pivotA != null && pushing()) solvePoint(timeStep);
    }

    /** Whether any of the limit rows pushes in this step. */
    boolean pushing() {
        for (int i = 0; i < rows; i++) if (acc[i] > 0) return true;
        return false;
    }

    static void addCrossTerm(Matrix3f k, Matrix3f inv, Vector3f r) {
        // k += [r]x^T inv [r]x
        Matrix3f s = new Matrix3f(0, -r.z, r.y, r.z, 0, -r.x, -r.y, r.x, 0);
        Matrix3f st = new Matrix3f(s);
        st.transpose();
        st.mul(inv);
        st.mul(s);
        k.add(st);
    }

    void solvePoint(float timeStep) {
        RigidBody a = getRigidBodyA(), b = getRigidBodyB();
        Transform ta = a.getCenterOfMassTransform(new Transform());
        Transform tb = b.getCenterOfMassTransform(new Transform());
        Vector3f ra = new Vector3f(pivotA), rb = new Vector3f(pivotB);
        ta.basis.transform(ra);
        tb.basis.transform(rb);
        Vector3f gap = new Vector3f(tb.origin);
        gap.add(rb);
        gap.sub(ta.origin);
        gap.sub(ra);
        Vector3f va = new Vector3f(), vb = new Vector3f(), w = new Vector3f();
        a.getLinearVelocity(va);
        w.cross(a.getAngularVelocity(new Vector3f()), ra);
        va.add(w);
        b.getLinearVelocity(vb);
        w.cross(b.getAngularVelocity(new Vector3f()), rb);
        vb.add(w);
        // the change of relative pivot velocity wanted: to -erp gap / dt
        Vector3f rhs = new Vector3f(gap);
        rhs.scale(-pointErp / timeStep);
        rhs.sub(vb);
        rhs.add(va);
        Matrix3f k = new Matrix3f();
        float m = a.getInvMass() + b.getInvMass();
        k.setIdentity();
        k.mul(m);
        addCrossTerm(k, a.getInvInertiaTensorWorld(new Matrix3f()), ra);
        addCrossTerm(k, b.getInvInertiaTensorWorld(new Matrix3f()), rb);
        if (Math.abs(k.determinant()) < 1e-12f) return;
        k.invert();
        k.transform(rhs);
        b.applyImpulse(rhs, rb);
        rhs.negate();
        a.applyImpulse(rhs, ra);
    }

    @Override
    public void solveConstraint(float timeStep) {
        if (rows == 0) return;
        RigidBody a = getRigidBodyA(), b = getRigidBodyB();
        Vector3f wa = a.getAngularVelocity(new Vector3f());
        Vector3f wb = b.getAngularVelocity(new Vector3f());
        Vector3f imp = new Vector3f();
        for (int i = 0; i < rows; i++) {
            Vector3f d = dir[i];
            if (i > 0) { a.getAngularVelocity(wa); b.getAngularVelocity(wb); }
            double vel = d.x * (wb.x - wa.x) + d.y * (wb.y - wa.y) + d.z * (wb.z - wa.z);
            double C = c[i];
            double target = (C >= 0 ? -C : -erp * C) / timeStep;
            double lambda = k[i] * (target - vel);
            double next = Math.max(0.0, acc[i] + lambda);
            double delta = next - acc[i];
            acc[i] = next;
            if (delta != 0) {
                imp.scale((float) delta, d);
                b.applyTorqueImpulse(imp);
                imp.negate();
                a.applyTorqueImpulse(imp);
            }
        }
    }
}
