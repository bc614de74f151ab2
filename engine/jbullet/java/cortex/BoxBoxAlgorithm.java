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
 * of the reference face and keeps the points below it, in the order
 * Bullet's detector gives them (at most four: beyond that the deepest,
 * then those a quarter turn apart round the centre); an edge
 * axis gives the closest points of the two edges. The boxes' full half
 * extents (with margin) are used, as Blender's, and the pair's manifold
 * keeps its points within Bullet 2.8's relative breaking threshold.
 */
public final class BoxBoxAlgorithm extends ManifoldAlgorithm {

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
            algo.start(ci, a, b, this);
            return algo;
        }

        @Override
        public void releaseCollisionAlgorithm(CollisionAlgorithm algo) {
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
        // the incident face: the one most opposed to nr, ties broken as
        // Bullet's detector breaks them
        double[] an = {Math.abs(dot(I[0], nr)), Math.abs(dot(I[1], nr)), Math.abs(dot(I[2], nr))};
        int f = an[1] > an[0] ? (an[1] > an[2] ? 1 : 2) : (an[0] > an[2] ? 0 : 2);
        double[] fc = axpy(ci, -Math.signum(dot(I[f], nr)) * hi[f], I[f]);
        // its corners in Bullet's order: its other two axes a1 < a2,
        // (-a1 -a2), (-a1 +a2), (+a1 +a2), (+a1 -a2)
        int a1 = f == 0 ? 1 : 0;
        int a2 = f == 2 ? 1 : 2;
        double[][] poly = {
            axpy(axpy(fc, -hi[a1], I[a1]), -hi[a2], I[a2]),
            axpy(axpy(fc, -hi[a1], I[a1]), hi[a2], I[a2]),
            axpy(axpy(fc, hi[a1], I[a1]), hi[a2], I[a2]),
            axpy(axpy(fc, hi[a1], I[a1]), -hi[a2], I[a2])};
        // clipped by the reference face's sides: its lower axis first, the
        // negative side first, as Bullet's detector clips them
        int r1 = k == 0 ? 1 : 0;
        int r2 = k == 2 ? 1 : 2;
        for (int s : new int[] {r1, r2}) {
            double c = dot(R[s], cr);
            poly = clip(poly, R[s], c, hr[s], -1);
            poly = clip(poly, R[s], c, hr[s], 1);
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
        // all of them when there are at most four, in the polygon's
        // order; else Bullet's choice: the deepest first, then those whose
        // angles round the polygon's centre are nearest a quarter turn apart
        int[] chosen = new int[Math.min(4, count)];
        if (count <= 4) {
            for (int c = 0; c < count; c++) {
                chosen[c] = c;
            }
        } else {
            int deepest = 0;
            for (int m = 1; m < count; m++) {
                if (deps[m] > deps[deepest]) {
                    deepest = m;
                }
            }
            double[] xy = new double[2 * count];
            for (int m = 0; m < count; m++) {
                xy[2 * m] = dot(R[r1], pts[m]) - dot(R[r1], cr);
                xy[2 * m + 1] = dot(R[r2], pts[m]) - dot(R[r2], cr);
            }
            chosen = cull(count, xy, 4, deepest);
        }
        for (int c : chosen) {
            double[] p = pts[c];
            // a point on B: the incident point itself when B is incident,
            // else the incident point lifted onto B's reference face
            double[] onB = refA ? p : axpy(p, deps[c], nr);
            add(out, normalOnB, onB, -deps[c]);
        }
    }

    /** `poly` clipped to side * (axis . p - centre) < half. */
    private static double[][] clip(double[][] poly, double[] axis, double centre, double half, int side) {
        java.util.ArrayList<double[]> outPts = new java.util.ArrayList<>();
        int n = poly.length;
        for (int m = 0; m < n; m++) {
            double[] p = poly[m];
            double[] q = poly[(m + 1) % n];
            double xp = dot(axis, p) - centre;
            double xq = dot(axis, q) - centre;
            boolean pin = side * xp < half;
            boolean qin = side * xq < half;
            if (pin) {
                outPts.add(p);
            }
            if (pin != qin) {
                double t = (side * half - xp) / (xq - xp);
                outPts.add(new double[] {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])});
            }
        }
        return outPts.toArray(new double[0][]);
    }

    /** Bullet's cullPoints2: `m` of the `n` points `p` (x, y pairs), `i0` first. */
    static int[] cull(int n, double[] p, int m, int i0) {
        double a = 0;
        double cx = 0;
        double cy = 0;
        if (n == 1) {
            cx = p[0];
            cy = p[1];
        } else if (n == 2) {
            cx = 0.5 * (p[0] + p[2]);
            cy = 0.5 * (p[1] + p[3]);
        } else {
            for (int i = 0; i < n - 1; i++) {
                double q = p[i * 2] * p[i * 2 + 3] - p[i * 2 + 2] * p[i * 2 + 1];
                a += q;
                cx += q * (p[i * 2] + p[i * 2 + 2]);
                cy += q * (p[i * 2 + 1] + p[i * 2 + 3]);
            }
            double q = p[n * 2 - 2] * p[1] - p[0] * p[n * 2 - 1];
            a = Math.abs(a + q) > 1.1920929E-7 ? 1.0 / (3.0 * (a + q)) : 1e18;
            cx = a * (cx + q * (p[n * 2 - 2] + p[0]));
            cy = a * (cy + q * (p[n * 2 - 1] + p[1]));
        }
        double[] angle = new double[n];
        for (int i = 0; i < n; i++) {
            angle[i] = Math.atan2(p[i * 2 + 1] - cy, p[i * 2] - cx);
        }
        boolean[] avail = new boolean[n];
        java.util.Arrays.fill(avail, true);
        avail[i0] = false;
        int[] ret = new int[m];
        ret[0] = i0;
        for (int j = 1; j < m; j++) {
            double want = j * (2 * Math.PI / m) + angle[i0];
            if (want > Math.PI) {
                want -= 2 * Math.PI;
            }
            double best = 1e9;
            ret[j] = i0;
            for (int i = 0; i < n; i++) {
                if (avail[i]) {
                    double diff = Math.abs(angle[i] - want);
                    if (diff > Math.PI) {
                        diff = 2 * Math.PI - diff;
                    }
                    if (diff < best) {
                        best = diff;
                        ret[j] = i;
                    }
                }
            }
            avail[ret[j]] = false;
        }
        return ret;
    }
}
