// Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.collision.broadphase.Dispatcher;
import com.bulletphysics.collision.dispatch.CollisionObject;
import com.bulletphysics.collision.narrowphase.ManifoldPoint;
import com.bulletphysics.collision.narrowphase.PersistentManifold;
import com.bulletphysics.dynamics.RigidBody;
import com.bulletphysics.dynamics.constraintsolver.ConstraintSolver;
import com.bulletphysics.dynamics.constraintsolver.ContactSolverInfo;
import com.bulletphysics.dynamics.constraintsolver.TypedConstraint;
import com.bulletphysics.linearmath.IDebugDraw;
import com.bulletphysics.linearmath.TransformUtil;
import com.bulletphysics.util.ObjectArrayList;
import java.util.ArrayList;
import javax.vecmath.Matrix3f;
import javax.vecmath.Vector3f;

/**
 * jBullet's constraint solver with contacts as Bullet 2.8's sequential
 * impulse solver (Blender's) sets them up, written for cortex: every
 * point of a manifold is a contact row (a point still apart is held to
 * close no faster than its distance allows), its position error
 * corrected at the solver's erp, warm started with the solver's
 * factor; and each point has ONE friction row, along the sliding
 * direction of that step (any direction across the normal when it does
 * not slide), bounded by friction times the point's normal impulse and
 * starting from nothing. jBullet's own (Bullet 2.72's) gives every
 * point two friction rows whose directions are kept from the step the
 * point appeared, warm started. Joints
 * are solved as jBullet solves them (their own solveConstraint), first
 * in each iteration, then contacts, then friction, in a fixed order.
 * cortex's own worlds give each point a second friction row across the
 * first, and take back each step a share of what a point has slid while
 * it held (see org/engine.org).
 */
public final class BlenderContactSolver extends ConstraintSolver {
    private static final class Row {
        RigidBody a;
        RigidBody b;
        final Vector3f n = new Vector3f();
        final Vector3f ca = new Vector3f();
        final Vector3f cb = new Vector3f();
        final Vector3f angA = new Vector3f();
        final Vector3f angB = new Vector3f();
        final Vector3f linA = new Vector3f();
        final Vector3f linB = new Vector3f();
        float jacInv;
        float rhs;
        float jv0;
        float applied;
        float friction;
        ManifoldPoint cp;
        Row contact;
        boolean second;
        Slip slip;
    }

    /** What a contact point has slid across its normal while its friction
     * held, and where it was (on body B) the step before. */
    private static final class Slip {
        final Vector3f at = new Vector3f();
        final Vector3f slid = new Vector3f();
    }

    private final boolean twoFrictionRows;
    private final float slipErp;

    /** Bullet 2.8's solving, one friction row a point, as Blender has it. */
    public BlenderContactSolver() {
        this(false);
    }

    /** With `twoFrictionRows`, each point gets a second friction row,
     * across the first and the normal (cortex's own worlds; see
     * org/engine.org). */
    public BlenderContactSolver(boolean twoFrictionRows) {
        this(twoFrictionRows, 0f);
    }

    /** With two friction rows and a `slipErp` over 0, each step's
     * friction also takes back that share of what its point has slid
     * while the friction held (cortex's own worlds). */
    public BlenderContactSolver(boolean twoFrictionRows, float slipErp) {
        this.twoFrictionRows = twoFrictionRows;
        this.slipErp = twoFrictionRows ? slipErp : 0f;
    }

    private final ArrayList<Row> contacts = new ArrayList<>();
    private final ArrayList<Row> frictions = new ArrayList<>();
    private final Vector3f t1 = new Vector3f();
    private final Vector3f t2 = new Vector3f();
    private final Matrix3f m = new Matrix3f();

    private static RigidBody dynamic(CollisionObject o) {
        return RigidBody.upcast(o);
    }

    private float velocity(Row r) {
        float v = 0f;
        if (r.a != null) {
            v += r.n.dot(r.a.getLinearVelocity(t1)) + r.ca.dot(r.a.getAngularVelocity(t2));
        }
        if (r.b != null) {
            v -= r.n.dot(r.b.getLinearVelocity(t1)) + r.cb.dot(r.b.getAngularVelocity(t2));
        }
        return v;
    }

    private void setup(Row r, RigidBody a, RigidBody b, Vector3f n, Vector3f relA, Vector3f relB) {
        r.a = a;
        r.b = b;
        r.n.set(n);
        r.ca.cross(relA, n);
        r.cb.cross(relB, n);
        float denom = 0f;
        if (a != null) {
            a.getInvInertiaTensorWorld(m).transform(r.ca, r.angA);
            r.linA.scale(a.getInvMass(), n);
            denom += a.getInvMass() + r.ca.dot(r.angA);
        }
        if (b != null) {
            b.getInvInertiaTensorWorld(m).transform(r.cb, r.angB);
            r.linB.scale(b.getInvMass(), n);
            denom += b.getInvMass() + r.cb.dot(r.angB);
        }
        r.jacInv = denom > 0f ? 1f / denom : 0f;
        r.jv0 = velocity(r);
    }

    /** A friction row of `contact` along `dir`, bounded by that point's
     * friction, asking for no sliding along it; added to the rows. */
    private Row friction(Row contact, RigidBody a, RigidBody b, Vector3f dir, Vector3f relA, Vector3f relB) {
        Row f = new Row();
        f.cp = contact.cp;
        f.contact = contact;
        f.friction = contact.cp.combinedFriction;
        setup(f, a, b, dir, relA, relB);
        f.rhs = -f.jv0 * f.jacInv;
        frictions.add(f);
        return f;
    }

    private void apply(Row r, float p) {
        if (r.a != null) {
            r.a.internalApplyImpulse(r.linA, r.angA, p);
        }
        if (r.b != null) {
            r.b.internalApplyImpulse(r.linB, r.angB, -p);
        }
    }

    private void resolve(Row r, float lo, float hi) {
        float delta = r.rhs - (velocity(r) - r.jv0) * r.jacInv;
        float sum = r.applied + delta;
        if (sum < lo) {
            delta = lo - r.applied;
            r.applied = lo;
        } else if (sum > hi) {
            delta = hi - r.applied;
            r.applied = hi;
        } else {
            r.applied = sum;
        }
        apply(r, delta);
    }

    @Override
    public float solveGroup(ObjectArrayList<CollisionObject> bodies, int numBodies,
                            ObjectArrayList<PersistentManifold> manifolds, int manifoldOffset, int numManifolds,
                            ObjectArrayList<TypedConstraint> constraints, int constraintOffset, int numConstraints,
                            ContactSolverInfo info, IDebugDraw debug, Dispatcher dispatcher) {
        float dt = info.timeStep;
        contacts.clear();
        frictions.clear();
        Vector3f pa = new Vector3f();
        Vector3f pb = new Vector3f();
        Vector3f relA = new Vector3f();
        Vector3f relB = new Vector3f();
        Vector3f va = new Vector3f();
        Vector3f vb = new Vector3f();
        Vector3f vel = new Vector3f();
        Vector3f dir1 = new Vector3f();
        Vector3f dir2 = new Vector3f();
        com.bulletphysics.linearmath.Transform tr = new com.bulletphysics.linearmath.Transform();
        for (int i = 0; i < numManifolds; i++) {
            PersistentManifold man = manifolds.getQuick(manifoldOffset + i);
            CollisionObject o0 = (CollisionObject) man.getBody0();
            CollisionObject o1 = (CollisionObject) man.getBody1();
            RigidBody a = dynamic(o0);
            RigidBody b = dynamic(o1);
            if ((a == null || a.getInvMass() == 0f) && (b == null || b.getInvMass() == 0f)) {
                continue;
            }
            for (int j = 0; j < man.getNumContacts(); j++) {
                ManifoldPoint cp = man.getContactPoint(j);
                cp.getPositionWorldOnA(pa);
                cp.getPositionWorldOnB(pb);
                relA.sub(pa, o0.getWorldTransform(tr).origin);
                relB.sub(pb, o1.getWorldTransform(tr).origin);
                Row c = new Row();
                c.cp = cp;
                setup(c, a, b, cp.normalWorldOnB, relA, relB);
                float relVel = c.jv0;
                float restitution = -relVel * cp.combinedRestitution;
                if (restitution <= 0f) {
                    restitution = 0f;
                }
                float penetration = cp.getDistance() + info.linearSlop;
                float velocityError = restitution - relVel;
                float positionalError = 0f;
                if (penetration > 0f) {
                    velocityError -= penetration / dt;
                } else {
                    positionalError = -penetration * info.erp / dt;
                }
                c.rhs = (positionalError + velocityError) * c.jacInv;
                contacts.add(c);

                // a friction row along the sliding velocity, or across the normal;
                // with two rows, a second across both
                if (a != null) {
                    a.getVelocityInLocalPoint(relA, va);
                } else {
                    va.set(0f, 0f, 0f);
                }
                if (b != null) {
                    b.getVelocityInLocalPoint(relB, vb);
                } else {
                    vb.set(0f, 0f, 0f);
                }
                vel.sub(va, vb);
                float rv = cp.normalWorldOnB.dot(vel);
                dir1.scaleAdd(-rv, cp.normalWorldOnB, vel);
                float lat = dir1.lengthSquared();
                if (lat > 1.1920929E-7f) {
                    dir1.scale(1f / (float) Math.sqrt(lat));
                } else {
                    TransformUtil.planeSpace1(cp.normalWorldOnB, dir1, dir2);
                }
                if (slipErp > 0f) {
                    c.slip = slipOf(cp, man, pb);
                }
                anchored(friction(c, a, b, dir1, relA, relB), dt);
                if (twoFrictionRows) {
                    dir2.cross(cp.normalWorldOnB, dir1);
                    anchored(friction(c, a, b, dir2, relA, relB), dt).second = true;
                }
            }
        }

        // warm starting, from the velocities every row was set up with
        boolean warm = (info.solverMode & com.bulletphysics.dynamics.constraintsolver.SolverMode.SOLVER_USE_WARMSTARTING) != 0;
        for (Row c : contacts) {
            c.applied = warm ? c.cp.appliedImpulse * info.warmstartingFactor : 0f;
            apply(c, c.applied);
        }
        // friction rows start from nothing: their direction is new each step
        for (Row f : frictions) {
            f.applied = 0f;
        }
        for (int j = 0; j < numConstraints; j++) {
            constraints.getQuick(constraintOffset + j).buildJacobian();
        }
        for (int it = 0; it < info.numIterations; it++) {
            for (int j = 0; j < numConstraints; j++) {
                constraints.getQuick(constraintOffset + j).solveConstraint(dt);
            }
            for (Row c : contacts) {
                resolve(c, 0f, 1e10f);
            }
            for (Row f : frictions) {
                float total = f.contact.applied;
                if (total > 0f) {
                    resolve(f, -f.friction * total, f.friction * total);
                }
            }
        }
        for (Row c : contacts) {
            c.cp.appliedImpulse = c.applied;
        }
        if (slipErp > 0f) {
            keepSlips(dt);
        }
        for (Row f : frictions) {
            if (f.second) {
                f.cp.appliedImpulseLateral2 = f.applied;
            } else {
                f.cp.appliedImpulseLateral1 = f.applied;
                f.cp.appliedImpulseLateral2 = 0f;
            }
        }
        return 0f;
    }

    private java.util.IdentityHashMap<ManifoldPoint, Slip> slips = new java.util.IdentityHashMap<>();
    private java.util.IdentityHashMap<ManifoldPoint, Slip> nextSlips = new java.util.IdentityHashMap<>();

    /** The slip of point `cp` of manifold `man`, at `pb` on body B: the
     * step before's while the point is within the breaking threshold of
     * where it was, else none; laid across the normal. */
    private Slip slipOf(ManifoldPoint cp, PersistentManifold man, Vector3f pb) {
        Slip s = slips.get(cp);
        float near = man.getContactBreakingThreshold();
        if (s != null) {
            t1.sub(pb, s.at);
        }
        if (s == null || t1.lengthSquared() > near * near) {
            s = new Slip();
        }
        s.at.set(pb);
        s.slid.scaleAdd(-cp.normalWorldOnB.dot(s.slid), cp.normalWorldOnB, s.slid);
        nextSlips.put(cp, s);
        return s;
    }

    /** Friction row `f`, asked to take back slipErp of its point's slip
     * along its direction in a step of `dt`. */
    private Row anchored(Row f, float dt) {
        Slip s = f.contact.slip;
        if (s != null) {
            f.rhs -= slipErp * f.n.dot(s.slid) / dt * f.jacInv;
        }
        return f;
    }

    /** After the iterations: a point that slid or let go forgets its
     * slip; one that held adds its velocity across the normal times
     * `dt`, row by row (the two rows span the plane). */
    private void keepSlips(float dt) {
        for (Row f : frictions) {
            Row c = f.contact;
            if (c.slip != null && (c.applied <= 0f || Math.abs(f.applied) >= 0.999f * f.friction * c.applied)) {
                c.slip.slid.set(0f, 0f, 0f);
                c.slip = null;
            }
        }
        for (Row f : frictions) {
            if (f.contact.slip != null) {
                f.contact.slip.slid.scaleAdd(velocity(f) * dt, f.n, f.contact.slip.slid);
            }
        }
    }

    @Override
    public void allSolved(ContactSolverInfo info, IDebugDraw debug) {
        java.util.IdentityHashMap<ManifoldPoint, Slip> solved = slips;
        slips = nextSlips;
        nextSlips = solved;
        nextSlips.clear();
    }

    @Override
    public void reset() {
    }
}
