;; Generated from org/shapes.org by lein tangle: edit the chapter, not this file.
(ns cortex.shapes
  "The collision shape a segment's mesh is: the primitives it is made of
  (box, sphere, capsule, cylinder), each within a stated tolerance, or
  the seed's convex hull. Pure functions on plain data (a point is
  [x y z], a triangle [a b c], a shape a map; see the shapes chapter),
  and one that makes the engine's CollisionShape of such a map.

  Entry points: `triangles` (a Geometry's triangles in its own axes at
  world scale), `pieces` (the closed parts of a mesh), `fit` (a piece's
  primitive, or its hull), `judge` (every primitive tried on a piece,
  with its measures), `segment-shape` (a segment's shape),
  `seed-hull` (the seed's hull, point for point), `defaults` (the
  tolerances), `margin` and `collision-shape` (Bullet's shape of the
  data)."
  (:require [cortex.engine :as engine]
            [cortex.geometry :as geometry]
            [cortex.mass :as mass]
            [cortex.util :as util])
  (:import (com.jme3.bullet.collision.shapes BoxCollisionShape CapsuleCollisionShape
                                             CollisionShape CompoundCollisionShape
                                             CylinderCollisionShape HullCollisionShape
                                             SphereCollisionShape)
           (com.jme3.math Matrix3f Quaternion Vector3f)
           (com.jme3.scene Geometry Mesh$Mode VertexBuffer$Type)))

(set! *warn-on-reflection* true)

(defn- v+ [[a b c] [x y z]] [(+ (double a) (double x)) (+ (double b) (double y)) (+ (double c) (double z))])
(defn- v- [[a b c] [x y z]] [(- (double a) (double x)) (- (double b) (double y)) (- (double c) (double z))])
(defn- v* [k [x y z]] [(* (double k) (double x)) (* (double k) (double y)) (* (double k) (double z))])
(defn- dot ^double [[a b c] [x y z]]
  (+ (* (double a) (double x)) (* (double b) (double y)) (* (double c) (double z))))
(defn- cross [[a b c] [x y z]]
  (let [a (double a) b (double b) c (double c) x (double x) y (double y) z (double z)]
    [(- (* b z) (* c y)) (- (* c x) (* a z)) (- (* a y) (* b x))]))
(defn- norm ^double [v] (Math/sqrt (dot v v)))
(defn- unit [v] (let [n (norm v)] (if (pos? n) (v* (/ 1.0 n) v) v)))
(defn- column [m k] (mapv #(nth % k) m))
(defn- columns->matrix [cols] (vec (for [i (range 3)] (mapv #(nth % i) cols))))

(defn- float-key
  "A point's identity as a Vector3f has it (Float.compare of each
  coordinate: -0.0 is not 0.0)."
  [[x y z]]
  [(Float/floatToIntBits (float x)) (Float/floatToIntBits (float y)) (Float/floatToIntBits (float z))])

(defn- distinct-floats
  "The points of `points`, rounded to floats (as doubles), without
  repeats by `float-key`, in order of first appearance."
  [points]
  (let [seen (java.util.HashSet.)]
    (persistent!
     (reduce (fn [out [x y z]]
               (let [p [(double (float x)) (double (float y)) (double (float z))]]
                 (if (.add seen (float-key p)) (conj! out p) out)))
             (transient []) points))))

(defn triangles
  "The triangles of `geom`'s mesh at its world scale, in its own axes,
  as a vector of [[x y z] [x y z] [x y z]] (doubles); none unless the
  mesh is made of triangles. Its metadata :points holds the mesh's
  distinct vertex positions, in buffer order, each coordinate the float
  the seed's hull is made of (as a double)."
  [^Geometry geom]
  (let [mesh (.getMesh geom)
        ^Vector3f scale (.getWorldScale geom)
        positions (.getFloatBuffer mesh VertexBuffer$Type/Position)
        index (.getIndexBuffer mesh)
        n-vertices (if positions (quot (.limit positions) 3) 0)
        vertex (fn [i] (let [i (int i)]
                         [(* (.x scale) (.get positions (* 3 i)))
                          (* (.y scale) (.get positions (+ 1 (* 3 i))))
                          (* (.z scale) (.get positions (+ 2 (* 3 i))))]))
        ;; each vertex made once, and shared by the triangles that use it
        vertices (mapv vertex (range n-vertices))
        corner (if index #(vertices (.get index (int %))) vertices)
        n-corners (if index (.size index) n-vertices)
        tris (if (and positions (= Mesh$Mode/Triangles (.getMode mesh)))
               (mapv (fn [t] (let [k (* 3 (long t))]
                               [(corner k) (corner (+ k 1)) (corner (+ k 2))]))
                     (range (quot n-corners 3)))
               [])]
    (with-meta tris {:points (distinct-floats vertices)})))

(defn- position-key [[x y z]] [(+ 0.0 (double x)) (+ 0.0 (double y)) (+ 0.0 (double z))])

(defn pieces
  "The connected pieces of `triangles` ([a b c] each): triangles that
  share a vertex position, directly or through others, are one piece.
  A vector of pieces (each a vector of triangles in their given order),
  in the order of each piece's first triangle."
  [triangles]
  (let [tris (vec triangles)
        n (count tris)
        parent (int-array (range n))
        find (fn ^long [^long i]
               (let [root (loop [r i] (let [p (aget parent r)] (if (== p r) r (recur p))))]
                 (loop [j i]                ; every index on the way now points at the root
                   (let [p (aget parent j)]
                     (when-not (== p j) (aset parent j (int root)) (recur p))))
                 root))
        union! (fn [^long a ^long b]
                 (let [ra (find a) rb (find b)]
                   (when-not (== ra rb)
                     (aset parent (max ra rb) (int (min ra rb))))))]
    (loop [i 0 seen (transient {})]
      (when (< i n)
        (recur (inc i)
               (reduce (fn [seen p]
                         (let [k (position-key p)]
                           (if-let [j (get seen k)]
                             (do (union! i j) seen)
                             (assoc! seen k i))))
                       seen (nth tris i)))))
    (let [groups (group-by #(find %) (range n))]
      (mapv (fn [root] (mapv tris (groups root))) (sort (keys groups))))))

(def defaults
  "How closely a piece must follow a primitive to become one, and the
  other options of `fit` and `segment-shape` (see the shapes chapter):
  every vertex within :tolerance of the primitive's surface, every point
  of every face within :face-tolerance, both as fractions of its radius
  (a box: its smallest half-extent); the volumes within
  :volume-tolerance of the primitive's; a segment of more than
  :max-pieces pieces is one hull; :shapes :hull asks for the seed's hull
  whatever the mesh."
  {:tolerance 0.02
   :face-tolerance 0.10
   :volume-tolerance 0.15
   :max-pieces 16
   :shapes :fit})

(def max-hull-points
  "The most points a hull keeps: the seed's limit (cortex.body)."
  100)

(defn- closed?
  "Is every edge of `piece` used once in each direction (a closed,
  consistently oriented surface)? Degenerate triangles are skipped."
  [piece]
  (let [edges (persistent!
               (reduce (fn [m [a b c]]
                         (let [a (position-key a) b (position-key b) c (position-key c)]
                           (if (or (= a b) (= b c) (= a c))
                             m
                             (reduce (fn [m e] (assoc! m e (inc (long (get m e 0)))))
                                     m [[a b] [b c] [c a]]))))
                       (transient {}) piece))]
    (boolean (and (seq edges)
                  (every? (fn [[[a b] k]] (and (== 1 (long k)) (== 1 (long (get edges [b a] 0)))))
                          edges)))))

(def ^:private identity-axes [[1.0 0.0 0.0] [0.0 1.0 0.0] [0.0 0.0 1.0]])

(defn- snap
  "`axis` (a unit vector) as exactly +-x, y or z when it is within 1e-6
  of one, else as it is."
  [axis]
  (let [i (apply max-key #(Math/abs (double (nth axis %))) [0 1 2])
        s (if (neg? (double (nth axis i))) -1.0 1.0)
        exact (assoc [0.0 0.0 0.0] i s)]
    (if (< (norm (v- axis exact)) 1e-6) exact axis)))

(defn- frame
  "A right-handed frame (three unit column vectors) whose first axis is
  along `u` and second in the plane of `u` and `v`."
  [u v]
  (let [u (unit u)
        w (unit (cross u v))
        v (cross w u)]
    (mapv snap [u v w])))

(def ^:private max-cluster-triangles
  "Pieces of more triangles than this are not searched for flat faces
  (their principal axes still are)."
  4000)

(defn- face-clusters
  "The flat regions of `piece`: triangles grouped by outward normal
  (within 1e-6 of a cosine), as {:normal n :area a}, biggest first."
  [piece]
  (when (<= (count piece) max-cluster-triangles)
    (->> piece
         (reduce (fn [clusters [a b c]]
                   (let [n (cross (v- b a) (v- c a))
                         l (norm n)]
                     (if (<= l 0.0)
                       clusters
                       (let [u (v* (/ 1.0 l) n)
                             i (first (keep-indexed (fn [i {m :normal}]
                                                      (when (> (dot u m) (- 1.0 1e-6)) i))
                                                    clusters))]
                         (if i
                           (update-in clusters [i :area] + (* 0.5 l))
                           (conj clusters {:normal u :area (* 0.5 l)}))))))
                 [])
         (sort-by (comp - :area)))))

(defn- frames
  "The frames (vectors of three unit column vectors) a primitive is
  sought in for `piece`, whose inertia tensor is `inertia`."
  [piece inertia]
  (let [principal (:axes (mass/principal inertia))
        clusters (face-clusters piece)
        [u] (map :normal clusters)
        v (when u (first (filter #(< (Math/abs (dot u %)) 1e-3) (map :normal clusters))))]
    (distinct
     (cond-> [identity-axes
              (frame (column principal 0) (column principal 1))]
       v (conj (frame u v))))))

(defn- extent
  "[lowest highest] of the points `ps` along `axis`."
  [ps axis]
  (let [ts (map #(dot % axis) ps)]
    [(apply min ts) (apply max ts)]))

(defn- along
  "`axes` turned so that the column `k` comes second: [x a z], a right-
  handed frame along the axis a."
  [axes k]
  (let [a (nth axes k)
        x (nth axes (mod (inc k) 3))]
    [x a (cross x a)]))

(defn- round-fit
  "The line of a cylinder or capsule of `points` along axis `k` of
  `axes`, the piece's centre of volume being `g`: {:axes :centre :radius
  :length}, length the piece's extent along the line."
  [points g axes k]
  (let [[x a z :as axes] (along axes k)
        [lo hi] (extent points a)
        centre (v+ (v- g (v* (dot g a) a)) (v* (* 0.5 (+ lo hi)) a))
        radius (apply max (map (fn [p] (let [d (v- p centre)] (norm (v- d (v* (dot d a) a)))))
                               points))]
    {:axes axes :centre centre :radius radius :length (- hi lo)}))

(defn- candidates
  "The primitives tried on a piece with distinct vertices `points`,
  centre of volume `g`, in the frames `fs`: sphere first, then boxes,
  cylinders and capsules in each frame."
  [points g fs]
  (concat
   [{:type :sphere :axes identity-axes :centre g
     :radius (apply max (map #(norm (v- % g)) points))}]
   (for [axes fs
         :let [ranges (mapv #(extent points %) axes)]]
     {:type :box :axes axes
      :centre (reduce v+ (map (fn [axis [lo hi]] (v* (* 0.5 (+ lo hi)) axis)) axes ranges))
      :half-extents (mapv (fn [[lo hi]] (* 0.5 (- hi lo))) ranges)})
   (for [axes fs k [0 1 2]]
     (let [{:keys [length radius] :as line} (round-fit points g axes k)]
       (assoc line :type :cylinder :half-height (* 0.5 length))))
   (for [axes fs k [0 1 2]
         :let [{:keys [length radius] :as line} (round-fit points g axes k)
               height (- length (* 2.0 radius))]
         :when (pos? height)]
     (assoc line :type :capsule :height height))))

(defn- local
  "Point `p` in the frame of primitive `c`."
  [{:keys [axes centre]} p]
  (let [d (v- p centre)] (mapv #(dot d %) axes)))

(defn- surface-distance
  "The signed distance from `p` (in the frame of primitive `c`) to its
  surface: positive outside, negative inside."
  ^double [c [x y z]]
  (let [x (double x) y (double y) z (double z)]
    (case (:type c)
      :sphere (- (Math/sqrt (+ (* x x) (* y y) (* z z))) (double (:radius c)))
      :box (let [[hx hy hz] (:half-extents c)
                 qx (- (Math/abs x) (double hx))
                 qy (- (Math/abs y) (double hy))
                 qz (- (Math/abs z) (double hz))]
             (+ (norm [(max qx 0.0) (max qy 0.0) (max qz 0.0)])
                (min (max qx (max qy qz)) 0.0)))
      :cylinder (let [dr (- (Math/sqrt (+ (* x x) (* z z))) (double (:radius c)))
                      dy (- (Math/abs y) (double (:half-height c)))]
                  (+ (min (max dr dy) 0.0)
                     (Math/sqrt (+ (Math/pow (max dr 0.0) 2) (Math/pow (max dy 0.0) 2)))))
      :capsule (let [h (* 0.5 (double (:height c)))
                     t (max (- h) (min h y))]
                 (- (norm [x (- y t) z]) (double (:radius c)))))))

(defn- volume
  "The volume of primitive `c`."
  ^double [c]
  (let [r (double (or (:radius c) 0.0))]
    (case (:type c)
      :sphere (* (/ 4.0 3.0) Math/PI r r r)
      :box (* 8.0 (reduce * (map double (:half-extents c))))
      :cylinder (* Math/PI r r 2.0 (double (:half-height c)))
      :capsule (+ (* Math/PI r r (double (:height c))) (* (/ 4.0 3.0) Math/PI r r r)))))

(defn- size
  "The length a primitive's deviations are measured against: its radius,
  or a box's smallest half-extent."
  ^double [c]
  (double (if (= :box (:type c)) (apply min (:half-extents c)) (:radius c))))

(def ^:private face-samples
  "Barycentric weights of the points sampled on each face: a grid of
  fifteen, corners and edges' quarters included."
  (vec (for [i (range 5) j (range (- 5 i))]
         [(/ (- 4.0 i j) 4.0) (/ i 4.0) (/ j 4.0)])))

(defn- measure
  "Candidate `c` with its measures: :vertex-deviation and
  :face-deviation (the farthest vertex, and sampled face point, from its
  surface, as fractions of its `size`), :volume-difference (|V - Vc| /
  Vc, V the piece's `vol`) and :fits? under `opts`. The face deviation
  is measured only when the others pass."
  [c points piece vol {:keys [tolerance face-tolerance volume-tolerance]}]
  (let [s (size c)]
    (if-not (and (pos? s) (pos? (volume c)))
      (assoc c :fits? false)
      (let [deviation (fn [ps] (/ (reduce max 0.0 (map #(Math/abs (surface-distance c (local c %))) ps)) s))
            vd (deviation points)
            dv (/ (Math/abs (- (double vol) (volume c))) (volume c))
            c (assoc c :vertex-deviation vd :volume-difference dv)]
        (if (and (<= vd (double tolerance)) (<= dv (double volume-tolerance)))
          (let [fd (deviation (for [[a b t] piece [wa wb wt] face-samples]
                                (v+ (v+ (v* wa a) (v* wb b)) (v* wt t))))]
            (assoc c :face-deviation fd :fits? (<= fd (double face-tolerance))))
          (assoc c :fits? false))))))

(defn- quaternion
  "The rotation [x y z w] whose matrix has the columns `axes` (a proper
  rotation)."
  [axes]
  (let [[[m00 m01 m02] [m10 m11 m12] [m20 m21 m22]] (columns->matrix axes)
        m00 (double m00) m01 (double m01) m02 (double m02)
        m10 (double m10) m11 (double m11) m12 (double m12)
        m20 (double m20) m21 (double m21) m22 (double m22)
        trace (+ m00 m11 m22)
        [x y z w] (cond
                    (pos? trace)
                    (let [s (/ 0.5 (Math/sqrt (+ trace 1.0)))]
                      [(* (- m21 m12) s) (* (- m02 m20) s) (* (- m10 m01) s) (/ 0.25 s)])
                    (and (> m00 m11) (> m00 m22))
                    (let [s (* 2.0 (Math/sqrt (- (+ 1.0 m00) m11 m22)))]
                      [(* 0.25 s) (/ (+ m01 m10) s) (/ (+ m02 m20) s) (/ (- m21 m12) s)])
                    (> m11 m22)
                    (let [s (* 2.0 (Math/sqrt (- (+ 1.0 m11) m00 m22)))]
                      [(/ (+ m01 m10) s) (* 0.25 s) (/ (+ m12 m21) s) (/ (- m02 m20) s)])
                    :else
                    (let [s (* 2.0 (Math/sqrt (- (+ 1.0 m22) m00 m11)))]
                      [(/ (+ m02 m20) s) (/ (+ m12 m21) s) (* 0.25 s) (/ (- m10 m01) s)]))
        [x y z w] (if (neg? (double w)) (mapv - [x y z w]) [x y z w])]
    [x y z w]))

(defn- segment-axis
  "The segment axis (0, 1 or 2) `axis` is exactly (+ or -), or nil."
  [axis]
  (first (filter #(== 1.0 (Math/abs (double (nth axis %)))) [0 1 2])))

(defn- primitive
  "The data of fitted candidate `c` (see the chapter): a box, sphere,
  cylinder or capsule, with :position and :rotation only when it is not
  at the segment's origin or not along its axes."
  [{:keys [type axes centre radius half-extents half-height height] :as c}]
  (let [big (double (case type
                      :box (apply max half-extents)
                      :cylinder (max (double radius) (double half-height))
                      :capsule (+ (double radius) (* 0.5 (double height)))
                      radius))
        centred? (<= (norm centre) (* 1e-6 big))
        turn (fn [shape aligned?]
               (cond-> shape
                 (not centred?) (assoc :position (vec centre))
                 (not aligned?) (assoc :rotation (quaternion axes))))]
    (case type
      :sphere (turn {:type :sphere :radius radius} true)
      :box (let [slots (map segment-axis axes)]
             (if (every? some? slots)
               (turn {:type :box
                      :half-extents (reduce (fn [h [slot e]] (assoc h slot e))
                                            [0.0 0.0 0.0] (map vector slots half-extents))}
                     true)
               (turn {:type :box :half-extents (vec half-extents)} false)))
      (let [i (segment-axis (second axes))
            axis (or i 1)
            shape (case type
                    :cylinder {:type :cylinder :axis axis
                               :half-extents (assoc [radius radius radius] axis half-height)}
                    :capsule {:type :capsule :radius radius :height height :axis axis})]
        (turn shape (some? i))))))

(defn- corner-points
  "The distinct corners of `triangles`, in order, as floats (doubles)."
  [triangles]
  (distinct-floats (apply concat triangles)))

(defn- sphere-directions
  "cortex.body's `sphere-directions`, as floats held in doubles."
  [n]
  (let [golden (* Math/PI (- 3 (Math/sqrt 5)))]
    (vec (for [i (range n)
               :let [y (- 1 (/ (* 2 (+ i 0.5)) n))
                     r (Math/sqrt (- 1 (* y y)))
                     a (* golden i)]]
           [(double (float (* r (Math/cos a)))) (double (float y))
            (double (float (* r (Math/sin a))))]))))

(defn- float-dot
  "Vector3f.dot of two points of floats (held in doubles), in float
  arithmetic: (x*a + y*b) + z*c, each step rounded to a float."
  ^double [[x y z] [a b c]]
  (let [xa (float (* (double x) (double a)))
        yb (float (* (double y) (double b)))
        zc (float (* (double z) (double c)))]
    (double (float (+ (double (float (+ xa yb))) zc)))))

(defn- simplify-hull
  "cortex.body's `simplify-hull` on points of floats held in doubles:
  at most `limit` of `points`, the farthest out in each of `limit`
  directions, distinct as Vector3fs are."
  [points limit]
  (if (<= (count points) limit)
    (vec points)
    (distinct-floats
     (for [d (sphere-directions limit)]
       (apply max-key #(float-dot d %) points)))))

(defn- hull-data
  "The hull of `points` (floats held in doubles), as the seed simplifies one."
  [points]
  {:type :hull :points (simplify-hull (distinct-floats points) max-hull-points)})

(defn seed-hull
  "The seed's hull of a segment whose triangles are `triangles`:
  {:type :hull :points ...}, the points those of cortex.body's hull
  (the mesh's positions as the metadata :points of `triangles` holds
  them, or the triangles' corners), in the same order, each coordinate
  the same float (as a double)."
  [triangles]
  (hull-data (or (:points (meta triangles)) (corner-points triangles))))

(defn- assess
  "What fitting `piece` starts from: {:points (its distinct vertices)
  :volume :candidates (unmeasured)}, or nil when it is not closed or
  encloses no volume."
  [piece]
  (when-let [props (when (closed? piece) (mass/mesh-properties piece 1.0))]
    (let [points (distinct (map position-key (apply concat piece)))]
      {:points points :volume (:volume props)
       :candidates (candidates points (:centre props) (frames piece (:inertia props)))})))

(defn judge
  "Every primitive tried on `piece` (triangles), with its measures (see
  the chapter): a seq of maps of :type, its sizes in its own frame
  (:axes, columns, and :centre), :vertex-deviation, :volume-difference,
  :face-deviation and :fits?. None when the piece is not closed or
  encloses no volume."
  ([piece] (judge piece {}))
  ([piece opts]
   (let [opts (merge defaults opts)
         {:keys [points volume candidates]} (assess piece)]
     (for [c candidates] (measure c points piece volume opts)))))

(defn- settle
  "Fitted `c` moved to the segment's origin when it is within a
  thousandth of its size of it and still fits there (a noisy mesh's
  centre wanders by its noise), else `c`."
  [c points piece volume opts]
  (let [off (norm (:centre c))]
    (if (and (pos? off) (<= off (* 1e-3 (size c))))
      (let [moved (measure (assoc c :centre [0.0 0.0 0.0]) points piece volume opts)]
        (if (:fits? moved) moved c))
      c)))

(defn fit
  "The shape `piece` (closed triangles, see `pieces`) is, under `opts`
  (merged into `defaults`): a box, sphere, cylinder or capsule (with
  :position and :rotation when it is not centred on, or not aligned
  with, the segment's origin and axes), or {:type :hull :points ...}
  when it is none of them within the tolerances."
  ([piece] (fit piece {}))
  ([piece opts]
   (let [opts (merge defaults opts)
         {:keys [points volume candidates]} (assess piece)
         best (first (for [t [:sphere :box :cylinder :capsule]
                           :let [fits (filter :fits? (for [c candidates :when (= t (:type c))]
                                                       (measure c points piece volume opts)))]
                           :when (seq fits)]
                       (apply min-key :face-deviation fits)))]
     (if best
       (primitive (settle best points piece volume opts))
       (hull-data (corner-points piece))))))

(defn- child
  "A compound's child for `shape` (which may carry :position and
  :rotation)."
  [shape]
  {:shape (dissoc shape :position :rotation)
   :position (or (:position shape) [0.0 0.0 0.0])
   :rotation (or (:rotation shape) [0.0 0.0 0.0 1.0])})

(defn segment-shape
  "The shape (data, see the shapes chapter) of a segment whose mesh is
  `triangles` (in its own axes at world scale, as `triangles` gives
  them): its one piece's shape (`fit`), or {:type :compound :children
  [...]} of its pieces', or the seed's hull (`seed-hull`) when no piece
  is a primitive, when it has more than :max-pieces pieces, or when
  `opts` has {:shapes :hull}. `opts` is merged into `defaults`."
  ([triangles] (segment-shape triangles {}))
  ([triangles opts]
   (let [opts (merge defaults opts)
         ps (when (= :fit (:shapes opts)) (pieces triangles))]
     (if (or (empty? ps) (> (count ps) (long (:max-pieces opts))))
       (seed-hull triangles)
       (let [shapes (mapv #(fit % opts) ps)]
         (cond
           (every? #(= :hull (:type %)) shapes) (seed-hull triangles)
           (and (= 1 (count shapes)) (not (:position (first shapes))) (not (:rotation (first shapes))))
           (first shapes)
           :else {:type :compound :children (mapv child shapes)}))))))

(defn margin
  "The collision margin cortex gives `shape` (data) on the running
  engine, unless the data carries its own :margin: a hull the engine's
  hull margin, or half a percent of its thickness if that is less and
  the hull is thinner than cortex.engine/thin (but not flat); a box or cylinder the
  smaller of the hull margin and a tenth of its smallest half-extent
  (inside its outer size, on both engines); a sphere or capsule its
  radius (Bullet's own rule); a compound none of its own (0.0)."
  ^double [shape]
  (double
   (or (:margin shape)
       (case (:type shape)
         :hull (let [t (geometry/points-thickness (:points shape))]
                 ;; a flat hull (a plane's mesh) is not a small body, and
                 ;; native Bullet refuses a margin of 0
                 (if (< 0.0 t (double engine/thin))
                   (min (engine/hull-margin) (* 0.005 t))
                   (engine/hull-margin)))
         (:box :cylinder) (min (engine/hull-margin) (* 0.1 (double (apply min (:half-extents shape)))))
         (:sphere :capsule) (:radius shape)
         :compound 0.0))))

(def prism-sides
  "The sides of the prism a small cylinder becomes on native Bullet."
  16)

(defn prism-points
  "The corners of a prism of `sides` sides (`prism-sides` if not given)
  round the axis of the cylinder `shape`, drawn in by `m`: [[x y z] ...]."
  ([shape m] (prism-points shape m prism-sides))
  ([{:keys [half-extents axis]} m sides]
   (let [k (long (or axis 1))
         [i j] (remove #{k} [0 1 2])
         r (- (double (nth half-extents i)) m)
         h (- (double (nth half-extents k)) m)]
     (for [n (range sides)
           end [-1.0 1.0]
           :let [t (/ (* 2 Math/PI n) sides)]]
       (-> [0.0 0.0 0.0]
           (assoc k (* end h))
           (assoc i (* r (Math/cos t)))
           (assoc j (* r (Math/sin t))))))))

(defn- vec3 ^Vector3f [[x y z]] (Vector3f. (float x) (float y) (float z)))

(defn- matrix
  "The rotation matrix of quaternion [x y z w]."
  ^Matrix3f [[x y z w]]
  (.toRotationMatrix (Quaternion. (float x) (float y) (float z) (float w))))

(defn- make-shape
  "Bullet's shape of `shape` (data), made on the calling thread."
  ^CollisionShape [shape]
  (if (or (:position shape) (:rotation shape))
    (make-shape {:type :compound :children [(child shape)]})
    (case (:type shape)
      :hull (doto (HullCollisionShape. (float-array (mapcat identity (:points shape))))
              (.setMargin (float (margin shape))))
      :box (if (= :native engine/name)
             ;; native Bullet's box contacts fail the physics-trust drops:
             ;; there a box is the hull of its corners (see above)
             ;; its corners drawn in by the margin, which Bullet adds
             ;; back around a hull: the outside is the box's, as Bullet's
             ;; box shape keeps it
             (let [m (margin shape)
                   [x y z] (map #(- (double %) m) (:half-extents shape))]
               (doto (HullCollisionShape.
                      (float-array (for [sx [-1.0 1.0] sy [-1.0 1.0] sz [-1.0 1.0]
                                         c [(* sx x) (* sy y) (* sz z)]]
                                     c)))
                 (.setMargin (float m))))
             (doto (BoxCollisionShape. (vec3 (:half-extents shape)))
               (.setMargin (float (margin shape)))))
      :cylinder (let [m (margin shape)]
                  (if (and (= :native engine/name)
                           (< (* 2.0 (double (apply min (:half-extents shape)))) (double engine/thin)))
                    ;; a small cylinder on native Bullet: a prism's hull (see above)
                    (doto (HullCollisionShape. (float-array (mapcat identity (prism-points shape m))))
                      (.setMargin (float m)))
                    (doto (CylinderCollisionShape. (vec3 (:half-extents shape)) (int (:axis shape 1)))
                      (.setMargin (float m)))))
      :sphere (SphereCollisionShape. (float (:radius shape)))
      :capsule (let [c (CapsuleCollisionShape. (float (:radius shape)) (float (:height shape))
                                               (int (:axis shape 1)))]
                 ;; jBullet's capsule keeps jME's 0.04 unless told (see above);
                 ;; native Bullet's is its radius, and Minie refuses to change it
                 (when (= :jbullet engine/name) (.setMargin c (float (margin shape))))
                 c)
      :compound (let [c (CompoundCollisionShape.)]
                  (doseq [{:keys [shape position rotation]} (:children shape)]
                    (.addChildShape c (make-shape shape) (vec3 (or position [0 0 0]))
                                    (matrix (or rotation [0 0 0 1]))))
                  c))))

(defn collision-shape
  "The engine's CollisionShape for `shape` (data, see the shapes
  chapter), in the segment's frame, with the margins of `margin`; a
  primitive carrying :position or :rotation is made a compound's only
  child. Made under cortex.util/locked-shape, as every shape cortex
  makes is."
  ^CollisionShape [shape]
  (util/locked-shape #(make-shape shape)))
