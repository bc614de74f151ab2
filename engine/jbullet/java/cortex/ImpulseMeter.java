// Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.dynamics.RigidBody;
import com.bulletphysics.linearmath.Transform;
import javax.vecmath.Matrix3f;
import javax.vecmath.Vector3f;

/**
 * How hard a constraint pulls in one physics step, as Bullet's breaking
 * thresholds measure it. jBullet's solver writes each body's velocity
 * back before it calls a constraint's solveConstraint and reads it
 * after, so the change of a body's linear velocity across that call,
 * times its mass, is the impulse the constraint gave it in that
 * iteration. The meter adds those up from buildJacobian (the start of
 * a step) on, and reports the largest component of the sum along the
 * axes of the constraint's frame in body A: Bullet breaks a constraint
 * when one row's impulse reaches the threshold, and a 6-DOF
 * constraint's linear rows are those axes. Angular rows are not
 * measured.
 */
public final class ImpulseMeter {
    private final RigidBody a;
    private final RigidBody b;
    private final Matrix3f basisInA;
    private final Vector3f sum = new Vector3f();
    private final Vector3f before = new Vector3f();
    private final Vector3f tmp = new Vector3f();
    private final Transform t = new Transform();

    /**
     * A jME joint frame (rotation and pivot in a body's frame) as the
     * jBullet Transform its constraints take: the one conversion every
     * metered joint needs.
     */
    public static Transform frame(com.jme3.math.Matrix3f rotation, com.jme3.math.Vector3f pivot) {
        Transform t = new Transform(com.jme3.bullet.util.Converter.convert(rotation));
        com.jme3.bullet.util.Converter.convert(pivot, t.origin);
        return t;
    }

    public ImpulseMeter(RigidBody a, RigidBody b, Matrix3f basisInA) {
        this.a = a;
        this.b = b;
        this.basisInA = new Matrix3f(basisInA);
    }

    private RigidBody measured() {
        return (b != null && b.getInvMass() > 0f) ? b : a;
    }

    /** A new step: forget the last one. */
    public void start() {
        sum.set(0f, 0f, 0f);
    }

    /** Just before the constraint is solved once. */
    public void before() {
        measured().getLinearVelocity(before);
    }

    /** Just after: add what the constraint gave the measured body. */
    public void after() {
        RigidBody r = measured();
        float inv = r.getInvMass();
        if (inv > 0f) {
            r.getLinearVelocity(tmp);
            tmp.sub(before);
            tmp.scale(1f / inv);
            sum.add(tmp);
        }
    }

    /** The impulse of the step so far, summed over iterations (world axes). */
    public Vector3f getImpulse(Vector3f out) {
        out.set(sum);
        return out;
    }

    /** The largest magnitude of the step's impulse along the frame's axes. */
    public float rowMax() {
        a.getCenterOfMassTransform(t);
        Matrix3f m = new Matrix3f(t.basis);
        m.mul(basisInA);
        float best = 0f;
        Vector3f col = new Vector3f();
        for (int i = 0; i < 3; i++) {
            m.getColumn(i, col);
            best = Math.max(best, Math.abs(col.dot(sum)));
        }
        return best;
    }
}
