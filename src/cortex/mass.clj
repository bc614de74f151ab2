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

(defn- outer [[a b c :as u]] (mapv #(mapv (fn [x] (* % x)) u) [a b c]))

(defn- m+ [& ms] (apply mapv (fn [& rows] (apply mapv + rows)) ms))

(defn- m* [k m] (mapv (fn [row] (mapv #(* k %) row)) m))

(defn- trace [m] (+ (get-in m [0 0]) (get-in m [1 1]) (get-in m [2 2])))

(def ^:private identity3 [[1.0 0.0 0.0] [0.0 1.0 0.0] [0.0 0.0 1.0]])

(defn- moments
  "[volume first-moment second-moment] of the solid the `triangles`
  ([a b c] each) enclose, signed by their orientation."
  [triangles]
  (reduce (fn [[vol first second] [a b c]]
            (let [v (/ (dot a (cross b c)) 6.0)
                  s (mapv + a b c)]
              [(+ vol v)
               (mapv + first (mapv #(* (/ v 4.0) %) s))
               (m+ second (m* (/ v 20.0) (m+ (outer a) (outer b) (outer c) (outer s))))]))
          [0.0 [0.0 0.0 0.0] [[0.0 0.0 0.0] [0.0 0.0 0.0] [0.0 0.0 0.0]]]
          triangles))

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
