;; Generated from org/mass.org by lein tangle: edit the chapter, not this file.
(ns cortex.mass
  "Mass properties of a closed triangle mesh of uniform density: its
  volume, centre of mass and inertia tensor, and the tensor's principal
  moments and axes. Plain numbers in, plain numbers out: a point is
  [x y z], a matrix a vector of three rows.

  Entry points: `mesh-properties` (triangles and a mass to volume,
  centre, inertia about the centre), `principal` (moments and axes of
  an inertia tensor)."
  )

(set! *warn-on-reflection* true)

(defn- dot [[a b c] [x y z]] (+ (* a x) (* b y) (* c z)))

(defn- cross [[a b c] [x y z]]
  [(- (* b z) (* c y)) (- (* c x) (* a z)) (- (* a y) (* b x))])

(defn- outer [[a b c]]
  [[(* a a) (* a b) (* a c)] [(* b a) (* b b) (* b c)] [(* c a) (* c b) (* c c)]])

(defn- m+ [[[a b c] [d e f] [g h i]] [[p q r] [s t u] [v w x]]]
  [[(+ a p) (+ b q) (+ c r)] [(+ d s) (+ e t) (+ f u)] [(+ g v) (+ h w) (+ i x)]])

(defn- m* [k m] (mapv (fn [[x y z]] [(* k x) (* k y) (* k z)]) m))

(defn- trace [m] (+ (get-in m [0 0]) (get-in m [1 1]) (get-in m [2 2])))

(def ^:private identity3 [[1.0 0.0 0.0] [0.0 1.0 0.0] [0.0 0.0 1.0]])

(defn- add!
  "Add `x` to element `i` of `acc`."
  [^doubles acc ^long i ^double x]
  (aset acc i (+ (aget acc i) x)))

(defn- moments
  "[volume first-moment second-moment] of the solid the `triangles`
  ([a b c] each) enclose, signed by their orientation. The sums above,
  in primitive doubles, each term added in the order the formulas
  write it; the second moment is symmetric, so six of its nine
  entries are summed."
  [triangles]
  (let [acc (double-array 10)] ; volume, first x y z, second xx xy xz yy yz zz
    (doseq [[[ax ay az] [bx by bz] [cx cy cz]] triangles]
      (let [ax (double ax) ay (double ay) az (double az)
            bx (double bx) by (double by) bz (double bz)
            cx (double cx) cy (double cy) cz (double cz)
            v (/ (+ (* ax (- (* by cz) (* bz cy)))
                    (* ay (- (* bz cx) (* bx cz)))
                    (* az (- (* bx cy) (* by cx))))
                 6.0)
            sx (+ ax bx cx) sy (+ ay by cy) sz (+ az bz cz)
            f (/ v 4.0)
            q (/ v 20.0)]
        (add! acc 0 v)
        (add! acc 1 (* f sx)) (add! acc 2 (* f sy)) (add! acc 3 (* f sz))
        (add! acc 4 (* q (+ (* ax ax) (* bx bx) (* cx cx) (* sx sx))))
        (add! acc 5 (* q (+ (* ax ay) (* bx by) (* cx cy) (* sx sy))))
        (add! acc 6 (* q (+ (* ax az) (* bx bz) (* cx cz) (* sx sz))))
        (add! acc 7 (* q (+ (* ay ay) (* by by) (* cy cy) (* sy sy))))
        (add! acc 8 (* q (+ (* ay az) (* by bz) (* cy cz) (* sy sz))))
        (add! acc 9 (* q (+ (* az az) (* bz bz) (* cz cz) (* sz sz))))))
    (let [[v x y z xx xy xz yy yz zz] (vec acc)]
      [v [x y z] [[xx xy xz] [xy yy yz] [xz yz zz]]])))

(defn mesh-properties
  "The mass properties of the closed mesh `triangles` ([a b c] each, a
  point being [x y z]) filled with `mass` at uniform density:
  {:volume V :centre [x y z] :inertia I}, I the inertia tensor about the
  centre, in the mesh's axes. Triangles may all face in or all face out.
  Nil when they enclose no volume (an open or flat mesh)."
  [triangles mass]
  (let [[vol first second] (moments triangles)
        sign (if (neg? vol) -1.0 1.0)
        vol (* sign vol)]
    (when (> vol 1e-12)
      (let [centre (mapv #(/ (* sign %) vol) first)
            about-centre (m+ (m* sign second) (m* (- vol) (outer centre)))
            density (/ (double mass) vol)]
        {:volume vol
         :centre centre
         :inertia (m* density (m+ (m* (trace about-centre) identity3)
                                  (m* -1.0 about-centre)))}))))

(defn- rotate
  "One Jacobi rotation of symmetric `a` (and accumulated axes `v`) that
  zeroes a[p][q]."
  [[a v] [p q]]
  (let [apq (get-in a [p q])]
    (if (< (Math/abs (double apq)) 1e-300)
      [a v]
      (let [theta (/ (- (get-in a [q q]) (get-in a [p p])) (* 2.0 apq))
            t (/ (Math/signum theta) (+ (Math/abs theta) (Math/sqrt (+ 1.0 (* theta theta)))))
            t (if (zero? theta) 1.0 t)
            c (/ 1.0 (Math/sqrt (+ 1.0 (* t t))))
            s (* t c)
            turn (fn [m]
                   (-> m
                       (assoc-in [p p] c) (assoc-in [q q] c)
                       (assoc-in [p q] s) (assoc-in [q p] (- s))))
            j (turn identity3)
            jt (apply mapv vector j)
            mul (fn [x y] (mapv (fn [row] (mapv (fn [col] (dot row col)) (apply mapv vector y))) x))]
        [(mul jt (mul a j)) (mul v j)]))))

(defn principal
  "The principal moments and axes of the symmetric tensor `inertia`:
  {:moments [i1 i2 i3] :axes R}, R a rotation whose columns are the
  axes (so inertia = R diag(moments) R^T), a proper rotation
  (determinant 1)."
  [inertia]
  (let [[a v] (reduce rotate [inertia identity3]
                      (take (* 3 12) (cycle [[0 1] [0 2] [1 2]])))
        axes (if (neg? (dot (cross (mapv first v) (mapv second v)) (mapv #(nth % 2) v)))
               (mapv #(update % 2 -) v)
               v)]
    {:moments [(get-in a [0 0]) (get-in a [1 1]) (get-in a [2 2])]
     :axes axes}))
