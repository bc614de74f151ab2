// Generated from org/shapes.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.BulletGlobals;
import com.bulletphysics.collision.broadphase.BroadphaseNativeType;
import com.bulletphysics.collision.broadphase.CollisionAlgorithm;
import com.bulletphysics.collision.broadphase.CollisionAlgorithmConstructionInfo;
import com.bulletphysics.collision.broadphase.DispatcherInfo;
import com.bulletphysics.collision.dispatch.CollisionAlgorithmCreateFunc;
import com.bulletphysics.collision.dispatch.CollisionDispatcher;
import com.bulletphysics.collision.dispatch.CollisionObject;
import com.bulletphysics.collision.dispatch.ManifoldResult;
import com.bulletphysics.collision.narrowphase.DiscreteCollisionDetectorInterface;
import com.bulletphysics.collision.narrowphase.GjkEpaPenetrationDepthSolver;
import com.bulletphysics.collision.narrowphase.GjkPairDetector;
import com.bulletphysics.collision.narrowphase.PersistentManifold;
import com.bulletphysics.collision.narrowphase.VoronoiSimplexSolver;
import com.bulletphysics.collision.shapes.CollisionShape;
import com.bulletphysics.collision.shapes.ConvexShape;
import com.bulletphysics.dynamics.constraintsolver.ContactSolverInfo;
import com.bulletphysics.linearmath.Transform;
import com.bulletphysics.util.ObjectArrayList;
import javax.vecmath.Vector3f;

/**
 * Two convex shapes, one of them thin, meet as they would if both were
 * made `UNIT / thickness` times bigger: jBullet's GJK and EPA work to
 * absolute tolerances meant for shapes about a unit in size (EPA to
 * 0.001, GJK's degenerate cases below 0.01, contact points merged within
 * 0.02), which at a hundredth of that size turn a box resting on a floor
 * over on contact normals 45 degrees off. A shape with no margin of its
 * own is given one inside its outer size (see `Scaled`). Two thicker
 * shapes without margins meet through it unscaled, for that margin
 * (EPA's normals under a resting body are as far off at any size);
 * other pairs keep jBullet's own algorithm. See org/shapes.org.
 */
public final class SmallConvexAlgorithm extends ManifoldAlgorithm {
    /** The thickness a pair's thinner shape is scaled to. */
    public static final float UNIT = 1f;
    /** The margin, at that size, of a shape that has none. */
    public static final float MARGIN = 0.04f;
    private final GjkPairDetector gjk = new GjkPairDetector();
    private float scale, margin;
    private Scaled scaledA, scaledB;

    /** The size of convex `shape` along each of its axes, read by its
     * supporting points (a hull's cached box can be stale). */
    static Vector3f extent(ConvexShape shape, Vector3f centre) {
        Vector3f p = new Vector3f();
        float[] h = new float[3], l = new float[3], c = new float[3];
        for (int i = 0; i < 3; i++) {
            float[] d = new float[3];
            d[i] = 1f;
            shape.localGetSupportingVertex(new Vector3f(d), p).get(c);
            h[i] = c[i];
            d[i] = -1f;
            shape.localGetSupportingVertex(new Vector3f(d), p).get(c);
            l[i] = c[i];
        }
        centre.set((h[0] + l[0]) / 2, (h[1] + l[1]) / 2, (h[2] + l[2]) / 2);
        return new Vector3f(h[0] - l[0], h[1] - l[1], h[2] - l[2]);
    }

    /** Whether convex `shape` has less margin of its own than `m` (a
     * sphere or a capsule is all margin). */
    static boolean bare(CollisionShape shape, float m) {
        BroadphaseNativeType type = shape.getShapeType();
        boolean round = type == BroadphaseNativeType.SPHERE_SHAPE_PROXYTYPE
            || type == BroadphaseNativeType.CAPSULE_SHAPE_PROXYTYPE;
        return !(round || shape.getMargin() >= m);
    }

    /** How thick convex `shape` counts as: its smallest extent along
     * its axes, or for a sheet (thinner than a tenth of its next
     * extent; a plane's polygon is not thick at all) a tenth of that
     * next extent, as cortex.geometry/sheet-thickness says. */
    public static float thickness(CollisionShape shape) {
        Vector3f e = extent((ConvexShape) shape, new Vector3f());
        float[] s = {e.x, e.y, e.z};
        java.util.Arrays.sort(s);
        return Math.max(s[0], 0.1f * s[1]);
    }

    /** Have every pair of convex shapes in `dispatcher` meet through
     * this algorithm when one of them is thinner than `size`, and
     * through the one jBullet gives them otherwise (two spheres keep
     * their own exact one); the first such pair sets `solver`'s slop
     * to 0. With `every`, two thicker shapes without margins of their
     * own meet through it too, unscaled. */
    public static void register(CollisionDispatcher dispatcher, float size, boolean every,
                                ContactSolverInfo solver) {
        BroadphaseNativeType[] types = BroadphaseNativeType.values();
        for (BroadphaseNativeType a : types) {
            for (BroadphaseNativeType b : types) {
                if (a.isConvex() && b.isConvex() && !(a == b && a == BroadphaseNativeType.SPHERE_SHAPE_PROXYTYPE)) {
                    CollisionAlgorithmCreateFunc own = dispatcher.getCollisionConfiguration().getCollisionAlgorithmCreateFunc(a, b);
                    dispatcher.registerCollisionCreateFunc(a.ordinal(), b.ordinal(),
                                                           new CreateFunc(own, size, every, solver));
                }
            }
        }
    }

    static final class CreateFunc extends CollisionAlgorithmCreateFunc {
        final CollisionAlgorithmCreateFunc own;
        final float size;
        final boolean every;
        final ContactSolverInfo solver;
        CreateFunc(CollisionAlgorithmCreateFunc own, float size, boolean every, ContactSolverInfo solver) {
            this.own = own;
            this.size = size;
            this.every = every;
            this.solver = solver;
        }

        @Override
        public CollisionAlgorithm createCollisionAlgorithm(CollisionAlgorithmConstructionInfo ci,
                                                           CollisionObject a, CollisionObject b) {
            float t = Math.min(thickness(a.getCollisionShape()), thickness(b.getCollisionShape()));
            boolean small = t < size;
            float m = MARGIN * Math.min(t / UNIT, 1f);
            if (!small && !(every && bare(a.getCollisionShape(), m) && bare(b.getCollisionShape(), m))) {
                return own.createCollisionAlgorithm(ci, a, b);
            }
            if (small && solver != null) {
                solver.linearSlop = 0f;
            }
            SmallConvexAlgorithm algo = new SmallConvexAlgorithm();
            algo.start(ci, a, b, this);
            algo.scale = small ? UNIT / Math.max(t, 1e-6f) : 1f;
            algo.margin = small ? MARGIN : m;
            algo.gjk.init(null, null, new VoronoiSimplexSolver(), new GjkEpaPenetrationDepthSolver());
            return algo;
        }

        @Override
        public void releaseCollisionAlgorithm(CollisionAlgorithm algo) {
        }
    }

    @Override
    public void processCollision(CollisionObject a, CollisionObject b, DispatcherInfo info, ManifoldResult out) {
        if (manifold == null) {
            return;
        }
        out.setPersistentManifold(manifold);
        final float k = scale;
        if (scaledA == null || scaledA.shape != a.getCollisionShape()) {
            scaledA = new Scaled((ConvexShape) a.getCollisionShape(), k, margin);
        }
        if (scaledB == null || scaledB.shape != b.getCollisionShape()) {
            scaledB = new Scaled((ConvexShape) b.getCollisionShape(), k, margin);
        }
        Scaled sa = scaledA, sb = scaledB;
        float saved = BulletGlobals.getContactBreakingThreshold();
        // the manifold keeps and merges points within the threshold the
        // pair would have at the bigger size (jBullet's is thread-local)
        BulletGlobals.setContactBreakingThreshold(saved / k);
        try {
            DiscreteCollisionDetectorInterface.ClosestPointInput in =
                new DiscreteCollisionDetectorInterface.ClosestPointInput();
            in.init();
            a.getWorldTransform(in.transformA);
            b.getWorldTransform(in.transformB);
            final Vector3f origin = new Vector3f(in.transformA.origin);
            in.transformA.origin.sub(origin);
            in.transformA.origin.scale(k);
            in.transformB.origin.sub(origin);
            in.transformB.origin.scale(k);
            float d = sa.getMargin() + sb.getMargin() + saved;
            in.maximumDistanceSquared = d * d;
            gjk.setMinkowskiA(sa);
            gjk.setMinkowskiB(sb);
            gjk.getClosestPoints(in, new DiscreteCollisionDetectorInterface.Result() {
                    @Override
                    public void setShapeIdentifiers(int p0, int i0, int p1, int i1) {
                    }

                    @Override
                    public void addContactPoint(Vector3f normal, Vector3f point, float depth) {
                        Vector3f p = new Vector3f(point);
                        p.scale(1f / k);
                        p.add(origin);
                        out.addContactPoint(normal, p, depth / k);
                    }
                }, null);
            if (ownManifold) {
                out.refreshContactPoints();
            }
        } finally {
            BulletGlobals.setContactBreakingThreshold(saved);
        }
    }

    /** `shape` made `k` times bigger, as GJK and EPA read it; a shape
     * with no margin of its own is drawn in by `MARGIN` (at the bigger
     * size) along each axis of its box and given that margin back round
     * it, so that two such shapes at rest are apart by their margins
     * (GJK's case) rather than touching (EPA's). */
    static final class Scaled extends ConvexShape {
        final ConvexShape shape;
        final float k, margin;
        final boolean drawn;
        final Vector3f centre = new Vector3f(), shrink = new Vector3f(1f, 1f, 1f), pad = new Vector3f();
        Scaled(ConvexShape shape, float k, float given) {
            this.shape = shape;
            this.k = k;
            drawn = bare(shape, given / k);
            if (!drawn) {
                margin = shape.getMargin() * k;
            } else {
                Vector3f hi = extent(shape, centre);
                float m = given / k;
                // an axis thinner than the margin's two sides (a plane's
                // polygon) is not drawn in past its middle, and its core is
                // given a thickness of one margin, so that EPA has a solid
                shrink.set(Math.max(0f, 1f - 2f * m / hi.x), Math.max(0f, 1f - 2f * m / hi.y),
                           Math.max(0f, 1f - 2f * m / hi.z));
                pad.set(hi.x < 2f * m ? m / 2 : 0f, hi.y < 2f * m ? m / 2 : 0f, hi.z < 2f * m ? m / 2 : 0f);
                margin = given;
            }
        }

        private Vector3f core(Vector3f dir, Vector3f out) {
            if (!drawn) {
                shape.localGetSupportingVertexWithoutMargin(dir, out);
            } else {
                Vector3f d = new Vector3f(dir.x * shrink.x, dir.y * shrink.y, dir.z * shrink.z);
                shape.localGetSupportingVertex(d, out);
                out.sub(centre);
                out.set(out.x * shrink.x, out.y * shrink.y, out.z * shrink.z);
                out.add(centre);
                out.x += dir.x < 0f ? -pad.x : pad.x;
                out.y += dir.y < 0f ? -pad.y : pad.y;
                out.z += dir.z < 0f ? -pad.z : pad.z;
            }
            out.scale(k);
            return out;
        }

        @Override
        public Vector3f localGetSupportingVertexWithoutMargin(Vector3f dir, Vector3f out) {
            return core(dir, out);
        }

        @Override
        public Vector3f localGetSupportingVertex(Vector3f dir, Vector3f out) {
            core(dir, out);
            float l = dir.length();
            if (l > 0f) {
                out.scaleAdd(margin / l, dir, out);
            }
            return out;
        }

        @Override
        public void batchedUnitVectorGetSupportingVertexWithoutMargin(Vector3f[] dirs, Vector3f[] outs, int n) {
            for (int i = 0; i < n; i++) {
                core(dirs[i], outs[i]);
            }
        }

        @Override
        public void getAabb(Transform t, Vector3f lo, Vector3f hi) {
            Transform u = new Transform(t);
            u.origin.scale(1f / k);
            shape.getAabb(u, lo, hi);
            lo.scale(k);
            hi.scale(k);
        }

        @Override public void getAabbSlow(Transform t, Vector3f lo, Vector3f hi) { getAabb(t, lo, hi); }
        @Override public float getMargin() { return margin; }
        @Override public void setMargin(float m) { throw new UnsupportedOperationException(); }
        @Override public void setLocalScaling(Vector3f s) { throw new UnsupportedOperationException(); }
        @Override public Vector3f getLocalScaling(Vector3f out) { return shape.getLocalScaling(out); }
        @Override public int getNumPreferredPenetrationDirections() { return 0; }
        @Override public void getPreferredPenetrationDirection(int i, Vector3f out) { throw new UnsupportedOperationException(); }
        @Override public BroadphaseNativeType getShapeType() { return shape.getShapeType(); }
        @Override public void calculateLocalInertia(float mass, Vector3f out) { throw new UnsupportedOperationException(); }
        @Override public String getName() { return "Scaled " + shape.getName(); }
    }
}
