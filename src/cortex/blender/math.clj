;; Generated from org/blender-scene.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender.math
  "The little linear algebra the reader needs, on plain Clojure data:
  a 3x3 or 4x4 matrix is a vector of rows (row-major, column vectors
  multiply on the right, as in Blender's own formulas).

  Entry points: `mat-mul`, `mat-vec`, `from-blender`, `euler->mat3`,
  `quat->mat3`, `y-up`, `to-y-up`, `det3`.")

(set! *warn-on-reflection* true)

(defn identity-matrix
  "The n by n identity."
  [n]
  (mapv (fn [r] (mapv (fn [c] (if (= r c) 1.0 0.0)) (range n))) (range n)))

(defn mat-mul
  "The product of matrices `a` and `b` (vectors of rows)."
  [a b]
  (let [k (count b)
        m (count (first b))]
    (mapv (fn [row]
            (mapv (fn [j]
                    (loop [t 0 acc 0.0]
                      (if (< t k)
                        (recur (inc t) (+ acc (* (double (nth row t))
                                                 (double (nth (nth b t) j)))))
                        acc)))
                  (range m)))
          a)))

(defn mat-vec
  "Matrix `m` times column vector `v`."
  [m v]
  (mapv (fn [row]
          (loop [t 0 acc 0.0]
            (if (< t (count v))
              (recur (inc t) (+ acc (* (double (nth row t)) (double (nth v t)))))
              acc)))
        m))

(defn transpose
  "The transpose of `m`."
  [m]
  (apply mapv vector m))

(defn mat3->mat4
  "Put 3x3 `m` in the top left of a 4x4 with translation `t`."
  [m [tx ty tz]]
  [(conj (vec (m 0)) (double tx))
   (conj (vec (m 1)) (double ty))
   (conj (vec (m 2)) (double tz))
   [0.0 0.0 0.0 1.0]])

(defn mat4->mat3
  "The rotation-and-scale part of a 4x4."
  [m]
  (mapv #(subvec (vec %) 0 3) (subvec (vec m) 0 3)))

(defn translation
  "The translation column of a 4x4."
  [m]
  (mapv #(nth % 3) (subvec (vec m) 0 3)))

(defn from-blender
  "A Blender `float[4][4]` as stored (`m[column][row]`) as rows."
  [m]
  (mapv (fn [r] (mapv (fn [c] (double (get-in m [c r] (if (= r c) 1.0 0.0))))
                      (range 4)))
        (range 4)))

(defn- rx [a] (let [c (Math/cos a) s (Math/sin a)] [[1.0 0.0 0.0] [0.0 c (- s)] [0.0 s c]]))
(defn- ry [a] (let [c (Math/cos a) s (Math/sin a)] [[c 0.0 s] [0.0 1.0 0.0] [(- s) 0.0 c]]))
(defn- rz [a] (let [c (Math/cos a) s (Math/sin a)] [[c (- s) 0.0] [s c 0.0] [0.0 0.0 1.0]]))

(def euler-orders
  "Blender's rotation modes 1..6 and the axes they turn about, first
  axis first: mode 1 is XYZ (X, then Y, then Z)."
  {1 [0 1 2], 2 [0 2 1], 3 [1 0 2], 4 [1 2 0], 5 [2 0 1], 6 [2 1 0]})

(defn euler->mat3
  "Rotation matrix of Euler angles `e` (radians, [x y z]) in rotation
  mode `mode` (1..6; anything else is XYZ). The first axis turns
  first, so XYZ is Rz * Ry * Rx."
  [e mode]
  (let [order (euler-orders mode [0 1 2])
        elem (fn [axis] ([rx ry rz] axis))
        ms (map (fn [axis] ((elem axis) (double (nth e axis 0.0)))) order)]
    (reduce (fn [acc m] (mat-mul m acc)) (identity-matrix 3) ms)))

(defn quat->mat3
  "Rotation matrix of quaternion [w x y z], normalised first; a zero
  quaternion is no rotation, as in Blender's normalize_qt."
  [[w x y z]]
  (let [w (double w) x (double x) y (double y) z (double z)
        len (Math/sqrt (+ (* w w) (* x x) (* y y) (* z z)))]
    (if (< len 1e-30)
      (identity-matrix 3)
      (let [w (/ w len) x (/ x len) y (/ y len) z (/ z len)]
        [[(- 1 (* 2 (+ (* y y) (* z z)))) (* 2 (- (* x y) (* w z))) (* 2 (+ (* x z) (* w y)))]
         [(* 2 (+ (* x y) (* w z))) (- 1 (* 2 (+ (* x x) (* z z)))) (* 2 (- (* y z) (* w x)))]
         [(* 2 (- (* x z) (* w y))) (* 2 (+ (* y z) (* w x))) (- 1 (* 2 (+ (* x x) (* y y))))]]))))

(defn axis-angle->mat3
  "Rotation by `angle` radians about `axis` (normalised first; a zero
  axis is no rotation, as in Blender's axis_angle_to_mat3)."
  [axis angle]
  (let [[x y z] (map double axis)
        len (Math/sqrt (+ (* x x) (* y y) (* z z)))]
    (if (< len 1e-30)
      (identity-matrix 3)
      (let [x (/ x len) y (/ y len) z (/ z len)
            c (Math/cos angle) s (Math/sin angle) t (- 1 c)]
        [[(+ c (* t x x)) (- (* t x y) (* s z)) (+ (* t x z) (* s y))]
         [(+ (* t x y) (* s z)) (+ c (* t y y)) (- (* t y z) (* s x))]
         [(- (* t x z) (* s y)) (+ (* t y z) (* s x)) (+ c (* t z z))]]))))

(defn scale->mat3
  "Diagonal matrix of scale [sx sy sz]."
  [[sx sy sz]]
  [[(double sx) 0.0 0.0] [0.0 (double sy) 0.0] [0.0 0.0 (double sz)]])

(def y-up
  "Blender's Z-up basis to jME's Y-up: (x, y, z) -> (x, z, -y). A
  proper rotation, so it keeps the winding of faces."
  [[1.0 0.0 0.0] [0.0 0.0 1.0] [0.0 -1.0 0.0]])

(defn to-y-up
  "A Blender 4x4 (or 3x3) as it reads in jME's basis: C M C^-1. C only
  permutes axes and flips one, so (C M C^-1)[i][j] is s_i s_j M[p_i][p_j]
  with p = (0 2 1 3) and s = (1 1 -1 1)."
  [m]
  (let [p [0 2 1 3] s [1.0 1.0 -1.0 1.0]
        n (count m)]
    (mapv (fn [i] (mapv (fn [j] (* (double (s i)) (double (s j))
                                   (double (get-in m [(p i) (p j)]))))
                        (range n)))
          (range n))))

(defn det3
  "Determinant of a 3x3."
  [[[a b c] [d e f] [g h i]]]
  (- (+ (* a (- (* e i) (* f h))) (* c (- (* d h) (* e g))))
     (* b (- (* d i) (* f g)))))

(defn affine-inverse
  "The inverse of 4x4 affine matrix `m` (its 3x3 by cofactors over its
  determinant), or nil when the 3x3 is singular."
  [m]
  (let [[[a b c] [d e f] [g h i]] (mat4->mat3 m)
        det (double (det3 [[a b c] [d e f] [g h i]]))]
    (when-not (< (Math/abs det) 1e-12)
      (let [inv (mapv (fn [row] (mapv #(/ (double %) det) row))
                      [[(- (* e i) (* f h)) (- (* c h) (* b i)) (- (* b f) (* c e))]
                       [(- (* f g) (* d i)) (- (* a i) (* c g)) (- (* c d) (* a f))]
                       [(- (* d h) (* e g)) (- (* b g) (* a h)) (- (* a e) (* b d))]])]
        (mat3->mat4 inv (mapv - (mat-vec inv (translation m))))))))

(defn- norm [v] (Math/sqrt (reduce + (map * v v))))

(defn- sub [a b] (mapv - a b))

(defn- scale-v [v k] (mapv #(* % k) v))

(defn- dot [a b] (reduce + (map * a b)))

(defn decompose
  "Split the 3x3 part of `m` into a rotation (3x3) and scale [sx sy sz]
  such that rotation * diag(scale) is `m` whenever `m` has no shear.
  Scales are column lengths; a mirroring matrix gets its last scale
  negated; the rotation's columns are made orthonormal (Gram-Schmidt),
  so a sheared `m` gives the nearest such pair and the caller must
  look after the rest (see `residual`)."
  [m]
  (let [a (mat4->mat3 (if (= 4 (count m)) m (mat3->mat4 m [0 0 0])))
        cols (transpose a)
        s (mapv norm cols)
        flip? (neg? (det3 a))
        s (if flip? (update s 2 -) s)
        safe (fn [v k] (if (< (Math/abs (double k)) 1e-12) v (scale-v v (/ 1.0 k))))
        [c0 c1 c2] (map safe cols s)
        e0 (let [n (norm c0)] (if (< n 1e-12) [1.0 0.0 0.0] (scale-v c0 (/ 1.0 n))))
        c1 (sub c1 (scale-v e0 (dot e0 c1)))
        e1 (let [n (norm c1)]
             (if (< n 1e-12)
               (let [t (if (< (Math/abs (double (e0 0))) 0.9) [1.0 0.0 0.0] [0.0 1.0 0.0])
                     t (sub t (scale-v e0 (dot e0 t)))]
                 (scale-v t (/ 1.0 (norm t))))
               (scale-v c1 (/ 1.0 n))))
        e2 [(- (* (e0 1) (e1 2)) (* (e0 2) (e1 1)))
            (- (* (e0 2) (e1 0)) (* (e0 0) (e1 2)))
            (- (* (e0 0) (e1 1)) (* (e0 1) (e1 0)))]]
    {:rotation (transpose [e0 e1 e2]) :scale s}))

(defn residual
  "The 3x3 that remains of `m3` once rotation `r` and scale `s` are
  taken out: diag(s)^-1 r^T m3. The identity when r * diag(s) = m3."
  [m3 r s]
  (let [inv-s (mapv #(if (< (Math/abs (double %)) 1e-12) 0.0 (/ 1.0 %)) s)]
    (mat-mul (mapv (fn [row k] (mapv #(* k %) row)) (transpose r) inv-s) m3)))

(defn near-identity?
  "Is 3x3 `m` the identity within `eps`?"
  [m eps]
  (every? true? (for [r (range 3) c (range 3)]
                  (< (Math/abs (- (double (get-in m [r c])) (if (= r c) 1.0 0.0))) eps))))
