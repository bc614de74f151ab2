// Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.bulletphysics.collision.broadphase.BroadphaseNativeType;
import com.bulletphysics.collision.broadphase.CollisionAlgorithm;
import com.bulletphysics.collision.broadphase.CollisionAlgorithmConstructionInfo;
import com.bulletphysics.collision.broadphase.DispatcherInfo;
import com.bulletphysics.collision.dispatch.CollisionAlgorithmCreateFunc;
import com.bulletphysics.collision.dispatch.CollisionDispatcher;
import com.bulletphysics.collision.dispatch.CollisionObject;
import com.bulletphysics.collision.dispatch.ManifoldResult;
import com.bulletphysics.collision.narrowphase.PersistentManifold;
import com.bulletphysics.collision.shapes.BoxShape;
import com.bulletphysics.linearmath.Transform;
import com.bulletphysics.util.ObjectArrayList;
import javax.vecmath.Vector3f;

/**
 * Contacts between two boxes found at once, as the Bullet in Blender
 * finds them (its btBoxBoxCollisionAlgorithm), for jBullet, whose GJK
 * finds one point a step. The separating-axis test over the 15 axes of
 * two boxes (three face normals of each, nine edge-edge crosses) picks
 * the axis of least penetration, preferring a face axis unless an edge
 * axis is 5% better; no contact when any axis separates them. A face
 * axis clips the other box's face most opposed to it against the sides
 * of the reference face and keeps the points below it (at most four:
 * the deepest, then each next the farthest from those kept); an edge
 * axis gives the closest points of the two edges. The boxes' full half
 * extents (with margin) are used, as Blender's, and the pair's manifold
 * keeps its points within Bullet 2.8's relative breaking threshold.
 */
public final class BoxBoxAlgorithm extends CollisionAlgorithm {
    private PersistentManifold manifold;
    private boolean ownManifold;

    /** Make two boxes meet through this algorithm in `dispatcher`. */
    public static void register(CollisionDispatcher dispatcher) {
        int box = BroadphaseNativeType.BOX_SHAPE_PROXYTYPE.ordinal();
        dispatcher.registerCollisionCreateFunc(box, box, new CreateFunc());
    }

    static final class CreateFunc extends CollisionAlgorithmCreateFunc {
        @Override
        public CollisionAlgorithm createCollisionAlgorithm(CollisionAlgorithmConstructionInfo ci,
                                                           CollisionObject a, CollisionObject b) {
            BoxBoxAlgorithm algo = new BoxBoxAlgorithm();
            algo.init(ci);
            algo.manifold = ci.manifold;
            if (algo.manifold == null && ci.dispatcher1.needsCollision(a, b)) {
                algo.manifold = ci.dispatcher1.getNewManifold(a, b);
                algo.ownManifold = true;
            }
            algo.internalSetCreateFunc(this);
            return algo;
        }

        @Override
        public void releaseCollisionAlgorithm(CollisionAlgorithm algo) {
        }
    }

    @Override
    public void destroy() {
        if (ownManifold && manifold != null) {
            dispatcher.releaseManifold(manifold);
        }
        manifold = null;
        ownManifold = false;
    }

    @Override
    public float calculateTimeOfImpact(CollisionObject a, CollisionObject b, DispatcherInfo info,
                                       ManifoldResult out) {
        return 1f;
    }

    @Override
    public void getAllContactManifolds(ObjectArrayList<PersistentManifold> out) {
        if (manifold != null && ownManifold) {
            out.add(manifold);
        }
    }

    private static double[] vec(Vector3f v) {
        return new double[] {v.x, v.y, v.z};
    }

    private static double dot(double[] a, double[] b) {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    }

    private static double[] cross(double[] a, double[] b) {
        return new double[] {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    }

    private static double[] axpy(double[] p, double s, double[] v) {
        return new double[] {p[0] + s * v[0], p[1] + s * v[1], p[2] + s * v[2]};
    }

    private static double[][] axes(Transform t) {
        double[][] a = new double[3][3];
        for (int i = 0; i < 3; i++) {
            for (int r = 0; r < 3; r++) {
                a[i][r] = t.basis.getElement(r, i);
            }
        }
        return a;
    }

    private static double radius(double[][] axes, double[] h, double[] l) {
        return h[0] * Math.abs(dot(axes[0], l)) + h[1] * Math.abs(dot(axes[1], l)) + h[2] * Math.abs(dot(axes[2], l));
    }

    @Override
    public void processCollision(CollisionObject a, CollisionObject b, DispatcherInfo info, ManifoldResult out) {
        if (manifold == null) {
            return;
        }
        out.setPersistentManifold(manifold);
        Transform ta = a.getWorldTransform(new Transform());
        Transform tb = b.getWorldTransform(new Transform());
        double[] ha = vec(((BoxShape) a.getCollisionShape()).getHalfExtentsWithMargin(new Vector3f()));
        double[] hb = vec(((BoxShape) b.getCollisionShape()).getHalfExtentsWithMargin(new Vector3f()));
        float saved = com.bulletphysics.BulletGlobals.getContactBreakingThreshold();
        // Bullet 2.8's manifolds keep points within a threshold relative to
        // the smaller shape (CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD, on
        // by default): its bounding sphere's radius times the global 0.02.
        // jBullet's global one is thread-local: it is set for this pair and
        // restored.
        com.bulletphysics.BulletGlobals.setContactBreakingThreshold(
            saved * Math.min(a.getCollisionShape().getAngularMotionDisc(), b.getCollisionShape().getAngularMotionDisc()));
        try {
            contacts(axes(ta), vec(ta.origin), ha, axes(tb), vec(tb.origin), hb, out);
            if (ownManifold) {
                out.refreshContactPoints();
            }
        } finally {
            com.bulletphysics.BulletGlobals.setContactBreakingThreshold(saved);
        }
    }

    private static void add(ManifoldResult out, double[] normalOnB, double[] pointOnB, double depth) {
        out.addContactPoint(new Vector3f((float) normalOnB[0], (float) normalOnB[1], (float) normalOnB[2]),
                            new Vector3f((float) pointOnB[0], (float) pointOnB[1], (float) pointOnB[2]),
                            (float) depth);
    }

    /** The contacts of box A (axes, centre, half extents) with box B, into `out`. */
    static void contacts(double[][] A, double[] ca, double[] ha, double[][] B, double[] cb, double[] hb,
                         ManifoldResult out) {
        double[] d = {cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2]};
        double best = -Double.MAX_VALUE;
        double[] normal = null;
        int code = -1;
        for (int k = 0; k < 6; k++) {
            double[] l = k < 3 ? A[k] : B[k - 3];
            double s = Math.abs(dot(d, l)) - (radius(A, ha, l) + radius(B, hb, l));
            if (s > 0) {
                return;
            }
            if (s > best) {
                best = s;
                normal = l;
                code = k;
            }
        }
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++) {
                double[] l = cross(A[i], B[j]);
                double len = Math.sqrt(dot(l, l));
                if (len < 1e-5) {
                    continue;
                }
                l = new double[] {l[0] / len, l[1] / len, l[2] / len};
                double s = Math.abs(dot(d, l)) - (radius(A, ha, l) + radius(B, hb, l));
                if (s > 0) {
                    return;
                }
                if (s * 1.05 > best) {
                    best = s;
                    normal = l;
                    code = 6 + 3 * i + j;
                }
            }
        }
        // n: from A towards B
        double[] n = dot(d, normal) < 0 ? new double[] {-normal[0], -normal[1], -normal[2]} : normal;
        double[] normalOnB = {-n[0], -n[1], -n[2]};
        if (code >= 6) {
            int i = (code - 6) / 3;
            int j = (code - 6) % 3;
            double[] ea = ca.clone();
            for (int k = 0; k < 3; k++) {
                if (k != i) {
                    ea = axpy(ea, Math.signum(dot(A[k], n)) * ha[k], A[k]);
                }
            }
            double[] eb = cb.clone();
            for (int k = 0; k < 3; k++) {
                if (k != j) {
                    eb = axpy(eb, -Math.signum(dot(B[k], n)) * hb[k], B[k]);
                }
            }
            double[] w = {ea[0] - eb[0], ea[1] - eb[1], ea[2] - eb[2]};
            double ab = dot(A[i], B[j]);
            double den = 1 - ab * ab;
            double t = 0;
            double u = 0;
            if (den > 1e-12) {
                double p = dot(A[i], w);
                double q = dot(B[j], w);
                t = (ab * q - p) / den;
                u = (q - ab * p) / den;
            }
            t = Math.max(-ha[i], Math.min(ha[i], t));
            u = Math.max(-hb[j], Math.min(hb[j], u));
            add(out, normalOnB, axpy(eb, u, B[j]), best);
            return;
        }

        boolean refA = code < 3;
        double[][] R = refA ? A : B;
        double[][] I = refA ? B : A;
        double[] cr = refA ? ca : cb;
        double[] ci = refA ? cb : ca;
        double[] hr = refA ? ha : hb;
        double[] hi = refA ? hb : ha;
        int k = refA ? code : code - 3;
        // the reference face's outward normal, towards the incident box
        double[] nr = refA ? n : normalOnB;
        double front = dot(nr, cr) + hr[k];
        // the incident face: the one most opposed to nr
        int f = 0;
        double most = -1;
        for (int m = 0; m < 3; m++) {
            double v = Math.abs(dot(I[m], nr));
            if (v > most) {
                most = v;
                f = m;
            }
        }
        double[] fc = axpy(ci, -Math.signum(dot(I[f], nr)) * hi[f], I[f]);
        int u1 = (f + 1) % 3;
        int u2 = (f + 2) % 3;
        double[][] poly = {
            axpy(axpy(fc, hi[u1], I[u1]), hi[u2], I[u2]),
            axpy(axpy(fc, -hi[u1], I[u1]), hi[u2], I[u2]),
            axpy(axpy(fc, -hi[u1], I[u1]), -hi[u2], I[u2]),
            axpy(axpy(fc, hi[u1], I[u1]), -hi[u2], I[u2])};
        for (int m = 1; m <= 2; m++) {
            int s = (k + m) % 3;
            double c = dot(R[s], cr);
            poly = clip(poly, R[s], c + hr[s], 1);
            poly = clip(poly, R[s], c - hr[s], -1);
        }

        int count = 0;
        double[][] pts = new double[poly.length][];
        double[] deps = new double[poly.length];
        for (double[] p : poly) {
            double dep = front - dot(nr, p);
            if (dep >= 0) {
                pts[count] = p;
                deps[count] = dep;
                count++;
            }
        }
        boolean[] kept = new boolean[count];
        int[] chosen = new int[Math.min(4, count)];
        for (int c = 0; c < chosen.length; c++) {
            int pick = -1;
            double score = -1;
            for (int m = 0; m < count; m++) {
                if (kept[m]) {
                    continue;
                }
                double sc;
                if (c == 0) {
                    sc = deps[m];
                } else {
                    sc = Double.MAX_VALUE;
                    for (int q = 0; q < c; q++) {
                        double[] e = pts[chosen[q]];
                        double[] v = {pts[m][0] - e[0], pts[m][1] - e[1], pts[m][2] - e[2]};
                        sc = Math.min(sc, dot(v, v));
                    }
                }
                if (sc > score) {
                    score = sc;
                    pick = m;
                }
            }
            kept[pick] = true;
            chosen[c] = pick;
        }
        for (int c : chosen) {
            double[] p = pts[c];
            // a point on B: the incident point itself when B is incident,
            // else the incident point lifted onto B's reference face
            double[] onB = refA ? p : axpy(p, deps[c], nr);
            add(out, normalOnB, onB, -deps[c]);
        }
    }

    /** The polygon `poly` clipped to side*(axis . p) <= side*offset. */
    private static double[][] clip(double[][] poly, double[] axis, double offset, int side) {
        java.util.ArrayList<double[]> outPts = new java.util.ArrayList<>();
        int n = poly.length;
        for (int m = 0; m < n; m++) {
            double[] p = poly[m];
            double[] q = poly[(m + 1) % n];
            double dp = side * (dot(axis, p) - offset);
            double dq = side * (dot(axis, q) - offset);
            if (dp <= 0) {
                outPts.add(p);
            }
            if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
                double t = dp / (dp - dq);
                outPts.add(new double[] {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])});
            }
        }
        return outPts.toArray(new double[0][]);
    }
}
