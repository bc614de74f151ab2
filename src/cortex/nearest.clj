;; Generated from org/body.org by lein tangle: edit the chapter, not this file.
(ns cortex.nearest
  "Which segments a joint (or an eye) is nearest to, measured, and the
  doubts and warnings that follow from where joints and segments are.
  Reads only the scene graph: no Bullet object is needed or made.

  Entry points: `joints` (the joint markers), `segment-index`,
  `index-of`, `nearest-segments`, `targets-near`, `joint-targets`,
  `tolerance`, `segment-sides`, `sheet?`, `joint-reach`, `fmt-length`, `joint-doubts`,
  `duplicate-doubts`, `naming-doubts`, `overlap-warnings`,
  `limit-warnings`."
  (:require [clojure.string :as str]
            [cortex.geometry :as geometry]
            [cortex.projection :as projection]
            [cortex.segment :as segment :refer [segments segment-name]]
            [cortex.sense :as sense]
            [cortex.util :as util])
  (:import (com.jme3.bounding BoundingBox)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.collision CollisionResults)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Node Spatial)))

(set! *warn-on-reflection* true)

(def ^{:doc "The children of the creature's \"joints\" node: one empty
  per joint."
       :arglists '([creature])}
  joints
  (sense/sense-nodes "joints"))

(defn physical?
  [^Spatial s]
  (some? (.getControl s RigidBodyControl)))

(defn- corners
  "The lowest and highest corners, [x y z] each, of `geom`'s world bound."
  [^Geometry geom]
  (let [b (.getWorldBound geom)
        c (.getCenter b)
        [ex ey ez] (if (instance? BoundingBox b)
                     [(.getXExtent ^BoundingBox b) (.getYExtent ^BoundingBox b)
                      (.getZExtent ^BoundingBox b)]
                     (repeat 3 (.getRadius ^com.jme3.bounding.BoundingSphere b)))]
    [[(- (.x c) ex) (- (.y c) ey) (- (.z c) ez)]
     [(+ (.x c) ex) (+ (.y c) ey) (+ (.z c) ez)]]))

(def ^:private max-cells-per-segment
  "A segment whose bound covers more grid cells than this is checked
  for every joint instead of being put in the grid."
  64)

(defn- cell-of
  "The number of the cell that coordinate `x` falls in along its axis."
  ^long [^double cell x]
  (long (Math/floor (/ (double x) cell))))

(defn- cell-range
  "The grid cells, as [i j k], that the box from `lo` to `hi` covers:
  a vector, made with no lazy sequence (a joint's search asks for a few
  hundred of these)."
  [cell lo hi]
  (let [cell (double cell)
        [i0 j0 k0] (mapv #(cell-of cell %) lo)
        [i1 j1 k1] (mapv #(cell-of cell %) hi)
        up (fn [from to f out] (reduce f out (range from (inc (long to)))))]
    (persistent!
     (up i0 i1 (fn [out i]
                 (up j0 j1 (fn [out j]
                             (up k0 k1 (fn [out k] (conj! out [i j k])) out))
                     out))
         (transient [])))))

(defn- cell-count
  "How many cells the box from `lo` to `hi` covers, counted in doubles:
  a box far out or huge (a damaged file's) covers more than a long
  holds."
  ^double [cell [lx ly lz] [hx hy hz]]
  (let [cell (double cell)
        across (fn ^double [l h] (inc (- (Math/floor (/ (double h) cell))
                                         (Math/floor (/ (double l) cell)))))]
    (* (* (* 1.0 (across lx hx)) (across ly hy)) (across lz hz))))

(defn- gridded?
  "Whether the box from `lo` to `hi` goes in the grid: it covers at most
  `most` cells, numbered by whole numbers that a long holds (a box
  a hundred thousand billion cells out, or with no finite corners, is
  kept aside and checked every time instead)."
  [cell lo hi most]
  (and (<= (cell-count cell lo hi) (double most))
       (every? #(< (Math/abs (Math/floor (/ (double %) cell))) 1e14) (concat lo hi))))

(defn index-of
  "The segments `geoms` indexed by where they are: each one's world
  bounds, and a grid of cells the size of a typical segment listing the
  segments that reach into each cell. The joint search asks the index
  for the segments near a point instead of testing every segment of the
  creature, which keeps building a body of n segments close to linear
  in n."
  [geoms]
  (let [items (vec (for [g geoms]
                     (let [[lo hi] (corners g)] {:geom g :lo lo :hi hi})))
        sizes (sort (for [{:keys [lo hi]} items] (apply max (map - hi lo))))
        cell (max 1e-9 (if (seq sizes) (nth sizes (quot (count sizes) 2)) 1.0))
        {big false small true} (group-by #(let [{:keys [lo hi]} (items %)]
                                            (gridded? cell lo hi max-cells-per-segment))
                                         (range (count items)))
        grid (persistent!
              (reduce (fn [grid i]
                        (let [{:keys [lo hi]} (items i)]
                          (reduce #(assoc! %1 %2 (conj (get %1 %2 []) i))
                                  grid (cell-range cell lo hi))))
                      (transient {}) small))]
    {:items items :cell cell :grid grid :big (vec big)
     :lo (if (seq items) (apply map min (map :lo items)) [0 0 0])
     :hi (if (seq items) (apply map max (map :hi items)) [0 0 0])}))

(defn segment-index
  "The physical segments of `parts` indexed (see `index-of`)."
  [^Node parts]
  (index-of (filter physical? (segments parts))))

(defn- overlaps?
  [[l0 l1 l2] [h0 h1 h2] [m0 m1 m2] [n0 n1 n2]]
  (and (<= l0 n0) (<= m0 h0) (<= l1 n1) (<= m1 h1) (<= l2 n2) (<= m2 h2)))

(defn- nearby
  "The items of `index` whose bounds meet the box from `lo` to `hi`."
  [{:keys [items cell grid big]} lo hi]
  (let [candidates (if-not (gridded? cell lo hi (count items))
                     (range (count items))
                     ;; each once, in order: a set sorted as it is filled
                     (let [in (java.util.TreeSet. ^java.util.Collection big)]
                       (doseq [c (cell-range cell lo hi)]
                         (when-let [is (grid c)] (.addAll in ^java.util.Collection is)))
                       in))]
    (for [i candidates
          :let [item (items i)]
          :when (overlaps? lo hi (:lo item) (:hi item))]
      item)))

(defn- touching
  "The physical segments in `index` whose triangles meet a cube of
  half-width `radius` centred on `center`."
  [index ^Vector3f center radius]
  (let [c [(.x center) (.y center) (.z center)]
        cube (BoundingBox. center (float radius) (float radius) (float radius))]
    (for [{:keys [^Geometry geom]} (nearby index (mapv #(- % radius) c) (mapv #(+ % radius) c))
          :when (pos? (.collideWith geom cube (CollisionResults.)))]
      geom)))

(defn- reach
  "How far from `center` the furthest corner of the indexed segments'
  bounds is: once the cube is that big it holds everything there is."
  [{:keys [lo hi]} ^Vector3f center]
  (let [c [(.x center) (.y center) (.z center)]]
    (Math/sqrt (reduce + (map #(let [d (max (Math/abs (double (- %1 %2))) (Math/abs (double (- %1 %3))))] (* d d))
                              c lo hi)))))

(defn- joint-frame-position
  "Where `target` sits as seen from `joint`: its offset in the joint's
  own frame, in Blender's axes."
  ^Vector3f [^Spatial joint ^Spatial target]
  (util/jme-to-blender
   (.mult (.inverse (.getWorldRotation joint))
          (.subtract (.getWorldTranslation target) (.getWorldTranslation joint)))))

(defn- touches?
  [^Geometry geom ^Vector3f center r]
  (pos? (.collideWith geom (BoundingBox. center (float r) (float r) (float r))
                      (CollisionResults.))))

(defn- reach-of
  "The half-width of the smallest cube centred on `center` that touches
  `geom`'s triangles, to a millionth of itself (or after 40 halvings),
  knowing that one of half-width `hi` does."
  [geom center hi]
  (loop [lo 0.0 hi (double hi) i 0]
    (if (or (= i 40) (<= (- hi lo) (* 1e-6 hi)))
      hi
      (let [mid (/ (+ lo hi) 2)]
        (if (touches? geom center mid)
          (recur lo mid (inc i))
          (recur mid hi (inc i)))))))

(defn nearest-segments
  "The physical segments of `index` (see `segment-index`) nearest to
  `joint`, as maps of :geom, :name (see `segment-name`) and :distance
  (the half-width of the smallest cube centred on the joint that touches
  the segment), nearest first, ties by name: the two nearest and every
  other segment within `window` of the second. When even a cube holding
  the whole creature finds fewer than two, an error names the joint.
  With `need` and `what` (an eye, say, needs one segment), the `need`
  nearest and every other within `window` of the last of them, the
  error naming the marker as a `what`."
  ([index joint window] (nearest-segments index joint window 2 "joint"))
  ([index ^Spatial joint window need what]
   (let [need (long need)
         center (.getWorldTranslation joint)
         limit (* 2 (max 0.01 (reach index center)))
         r (loop [r 0.01]
             (let [found (touching index center r)]
               (cond (>= (count found) need) r
                     (> r limit)
                     (throw (ex-info (str what " " (pr-str (.getName joint))
                                          ": found " (count found)
                                          " segment(s) near it"
                                          (when (seq found)
                                            (str " (" (str/join ", " (sort (map segment-name found))) ")"))
                                          ", a " what " needs " (if (= 2 need) "two" need))
                                     {(keyword what) (.getName joint)
                                      :found (map segment-name found)}))
                     :else (recur (* 2 r)))))
         outer (+ r (double window))
         measured (sort-by (juxt :distance :name)
                           (for [g (touching index center outer)]
                             {:geom g :name (segment-name g)
                              :distance (reach-of g center outer)}))
         dn (double (:distance (nth measured (dec need))))]
     (vec (take-while #(<= (double (:distance %)) (+ dn (double window))) measured)))))

(defn ordered-pair
  "The two segments `geoms` in the order the joint's frame gives them."
  [^Spatial joint geoms]
  (sort-by #(.dot (Vector3f. 1 1 1) (joint-frame-position joint %)) geoms))

(defn targets-near
  "The two physical segments in `index` (see `segment-index`) closest
  to `joint`, ordered as `joint-targets` says."
  [index ^Spatial joint]
  (ordered-pair joint (map :geom (take 2 (nearest-segments index joint 0.0)))))

(defn joint-targets
  "The two physical segments of `parts` closest to `joint`, found by
  growing a cube around the joint from 0.01 by doubling until it touches
  two of them, then measuring how near each is. They are ordered by
  where they lie in the joint's frame (in Blender's axes): the one with
  the smaller x + y + z first. Call after `physical!`. When even a cube
  holding the whole creature finds fewer than two, the error names the
  joint. Doubts about the pair are `joints!`'s business."
  [^Node parts ^Spatial joint]
  (.updateGeometricState parts)
  (targets-near (segment-index parts) joint))

(defn- world-triangles
  "The triangles of segment `geom` in world space, each corner drawn
  towards the world point `c` ([x y z]) by the factor `k` (1 leaves
  them where they are): a vector of double arrays
  [ax ay az bx by bz cx cy cz]."
  [^Geometry geom c k]
  (let [mesh (.getMesh geom)
        k (double k)
        a (Vector3f.) b (Vector3f.) d (Vector3f.)]
    (vec (for [i (range (.getTriangleCount mesh))]
           (do (.getTriangle mesh (int i) a b d)
               (let [out (double-array 9)]
                 (doseq [[j ^Vector3f v] [[0 a] [3 b] [6 d]]
                         :let [w (.localToWorld geom v nil)]]
                   (aset out j (+ (double (c 0)) (* k (- (.x w) (double (c 0))))))
                   (aset out (+ j 1) (+ (double (c 1)) (* k (- (.y w) (double (c 1))))))
                   (aset out (+ j 2) (+ (double (c 2)) (* k (- (.z w) (double (c 2)))))))
                 out))))))

(defn- hit
  "Where, as a multiple of (dx dy dz) from (px py pz), the line meets
  triangle `t`, or -1 when it misses it or runs along its plane."
  [^doubles t px py pz dx dy dz]
  (let [px (double px) py (double py) pz (double pz) dx (double dx) dy (double dy) dz (double dz)
        ax (aget t 0) ay (aget t 1) az (aget t 2)
        e1x (- (aget t 3) ax) e1y (- (aget t 4) ay) e1z (- (aget t 5) az)
        e2x (- (aget t 6) ax) e2y (- (aget t 7) ay) e2z (- (aget t 8) az)
        hx (- (* dy e2z) (* dz e2y)) hy (- (* dz e2x) (* dx e2z)) hz (- (* dx e2y) (* dy e2x))
        det (+ (* e1x hx) (* e1y hy) (* e1z hz))
        scale (* (Math/sqrt (+ (* dx dx) (* dy dy) (* dz dz)))
                 (Math/sqrt (+ (* e1x e1x) (* e1y e1y) (* e1z e1z)))
                 (Math/sqrt (+ (* e2x e2x) (* e2y e2y) (* e2z e2z))))]
    (if (<= (Math/abs det) (* 1e-12 scale))
      -1.0
      (let [f (/ 1.0 det)
            sx (- px ax) sy (- py ay) sz (- pz az)
            u (* f (+ (* sx hx) (* sy hy) (* sz hz)))
            qx (- (* sy e1z) (* sz e1y)) qy (- (* sz e1x) (* sx e1z)) qz (- (* sx e1y) (* sy e1x))
            v (* f (+ (* dx qx) (* dy qy) (* dz qz)))]
        (if (or (< u 0.0) (> u 1.0) (< v 0.0) (> (+ u v) 1.0))
          -1.0
          (* f (+ (* e2x qx) (* e2y qy) (* e2z qz))))))))

(defn- edges-cross?
  "Whether an edge of triangle `s` passes through triangle `t`."
  [^doubles s ^doubles t]
  (some (fn [[i j]]
          (let [i (long i) j (long j)
                x (aget s i) y (aget s (inc i)) z (aget s (+ i 2))
                r (hit t x y z (- (aget s j) x) (- (aget s (inc j)) y) (- (aget s (+ j 2)) z))]
            (<= 0.0 (double r) 1.0)))
        [[0 3] [3 6] [6 0]]))

(defn- winding
  "How many times the triangles `ts` wind around point (px py pz): the
  solid angles they make at the point, summed, over 4 pi (Van Oosterom
  and Strackee's formula). About 1 inside a closed piece (-1 if it is
  turned inside out), 0 outside, 1/2 on its surface; pieces that
  overlap add up."
  [ts px py pz]
  (let [px (double px) py (double py) pz (double pz)]
    (/ (reduce + 0.0
               (for [^doubles t ts]
                 (let [ax (- (aget t 0) px) ay (- (aget t 1) py) az (- (aget t 2) pz)
                       bx (- (aget t 3) px) by (- (aget t 4) py) bz (- (aget t 5) pz)
                       cx (- (aget t 6) px) cy (- (aget t 7) py) cz (- (aget t 8) pz)
                       la (Math/sqrt (+ (* ax ax) (* ay ay) (* az az)))
                       lb (Math/sqrt (+ (* bx bx) (* by by) (* bz bz)))
                       lc (Math/sqrt (+ (* cx cx) (* cy cy) (* cz cz)))
                       det (+ (* ax (- (* by cz) (* bz cy))) (* ay (- (* bz cx) (* bx cz)))
                              (* az (- (* bx cy) (* by cx))))
                       den (+ (* la lb lc) (* lc (+ (* ax bx) (* ay by) (* az bz)))
                              (* lb (+ (* ax cx) (* ay cy) (* az cz)))
                              (* la (+ (* bx cx) (* by cy) (* bz cz))))]
                   (* 2.0 (Math/atan2 det den)))))
       (* 4.0 Math/PI))))

(defn- point-inside?
  "Whether point (px py pz) lies inside the closed surface, or the
  closed pieces, of triangles `ts`."
  [ts px py pz]
  (> (Math/abs (double (winding ts px py pz))) 0.5))

(defn- inside?
  "Whether the first corner of triangle `s` lies inside the closed
  surface `ts`."
  [^doubles s ts]
  (point-inside? ts (aget s 0) (aget s 1) (aget s 2)))

(defn- within
  "The triangles of `ts` whose bounds meet the box from `lo` to `hi`."
  [ts lo hi]
  (filter (fn [^doubles t]
            (every? (fn [k] (let [k (long k)
                                  l (min (aget t k) (aget t (+ k 3)) (aget t (+ k 6)))
                                  h (max (aget t k) (aget t (+ k 3)) (aget t (+ k 6)))]
                              (and (<= l (double (nth hi k))) (<= (double (nth lo k)) h))))
                    [0 1 2]))
          ts))

(defn- point-triangle-d2
  "The squared distance from point (px py pz) to triangle `t`."
  [^doubles t px py pz]
  (let [px (double px) py (double py) pz (double pz)
        ax (aget t 0) ay (aget t 1) az (aget t 2)
        abx (- (aget t 3) ax) aby (- (aget t 4) ay) abz (- (aget t 5) az)
        acx (- (aget t 6) ax) acy (- (aget t 7) ay) acz (- (aget t 8) az)
        apx (- px ax) apy (- py ay) apz (- pz az)
        d1 (+ (* abx apx) (* aby apy) (* abz apz))
        d2 (+ (* acx apx) (* acy apy) (* acz apz))
        d3 (- d1 (+ (* abx abx) (* aby aby) (* abz abz)))
        d4 (- d2 (+ (* acx abx) (* acy aby) (* acz abz)))
        d5 (- d1 (+ (* abx acx) (* aby acy) (* abz acz)))
        d6 (- d2 (+ (* acx acx) (* acy acy) (* acz acz)))
        vc (- (* d1 d4) (* d3 d2)) vb (- (* d5 d2) (* d1 d6)) va (- (* d3 d6) (* d5 d4))
        ;; the nearest point is a + v (b - a) + w (c - a)
        [v w] (cond (and (<= d1 0.0) (<= d2 0.0)) [0.0 0.0]
                    (and (>= d3 0.0) (<= d4 d3)) [1.0 0.0]
                    (and (<= vc 0.0) (>= d1 0.0) (<= d3 0.0)) [(/ d1 (- d1 d3)) 0.0]
                    (and (>= d6 0.0) (<= d5 d6)) [0.0 1.0]
                    (and (<= vb 0.0) (>= d2 0.0) (<= d6 0.0)) [0.0 (/ d2 (- d2 d6))]
                    (and (<= va 0.0) (>= (- d4 d3) 0.0) (>= (- d5 d6) 0.0))
                    (let [u (/ (- d4 d3) (+ (- d4 d3) (- d5 d6)))] [(- 1.0 u) u])
                    (pos? (+ va vb vc)) (let [s (/ 1.0 (+ va vb vc))] [(* vb s) (* vc s)])
                    ;; no area: its edges, measured apart, say how near it is
                    :else [0.0 0.0])
        v (double v) w (double w)
        qx (- apx (* v abx) (* w acx)) qy (- apy (* v aby) (* w acy)) qz (- apz (* v abz) (* w acz))]
    (+ (* qx qx) (* qy qy) (* qz qz))))

(defn- edges-d2
  "The squared distance between the edge of triangle `s` from corner
  offset `i` to `j` and that of `t` from `k` to `l`."
  [^doubles s i j ^doubles t k l]
  (let [i (long i) j (long j) k (long k) l (long l)
        ux (- (aget s j) (aget s i)) uy (- (aget s (inc j)) (aget s (inc i))) uz (- (aget s (+ j 2)) (aget s (+ i 2)))
        vx (- (aget t l) (aget t k)) vy (- (aget t (inc l)) (aget t (inc k))) vz (- (aget t (+ l 2)) (aget t (+ k 2)))
        rx (- (aget s i) (aget t k)) ry (- (aget s (inc i)) (aget t (inc k))) rz (- (aget s (+ i 2)) (aget t (+ k 2)))
        a (+ (* ux ux) (* uy uy) (* uz uz)) e (+ (* vx vx) (* vy vy) (* vz vz))
        b (+ (* ux vx) (* uy vy) (* uz vz)) c (+ (* ux rx) (* uy ry) (* uz rz))
        f (+ (* vx rx) (* vy ry) (* vz rz))
        clamp (fn ^double [^double x] (max 0.0 (min 1.0 x)))
        [p q] (cond (and (zero? a) (zero? e)) [0.0 0.0]
                    (zero? a) [0.0 (clamp (/ f e))]
                    (zero? e) [(clamp (/ (- c) a)) 0.0]
                    :else (let [den (- (* a e) (* b b))
                                p (if (pos? den) (clamp (/ (- (* b f) (* c e)) den)) 0.0)
                                q (/ (+ (* b p) f) e)]
                            (cond (neg? q) [(clamp (/ (- c) a)) 0.0]
                                  (> q 1.0) [(clamp (/ (- b c) a)) 1.0]
                                  :else [p q])))
        p (double p) q (double q)
        dx (- (+ rx (* p ux)) (* q vx)) dy (- (+ ry (* p uy)) (* q vy)) dz (- (+ rz (* p uz)) (* q vz))]
    (+ (* dx dx) (* dy dy) (* dz dz))))

(defn- triangles-d2
  "The squared distance between triangles `s` and `t`: 0 when they
  cross."
  [^doubles s ^doubles t]
  (if (or (edges-cross? s t) (edges-cross? t s))
    0.0
    (let [edges [[0 3] [3 6] [6 0]]]
      (reduce min (concat (for [i [0 3 6]] (point-triangle-d2 t (aget s i) (aget s (+ i 1)) (aget s (+ i 2))))
                          (for [i [0 3 6]] (point-triangle-d2 s (aget t i) (aget t (+ i 1)) (aget t (+ i 2))))
                          (for [[i j] edges [k l] edges] (edges-d2 s i j t k l)))))))

(defn- gap
  "How near triangles `ta` and `tb` come, 0 where two cross, looking
  only at those that meet the box from `lo` to `hi`; infinite when
  either has none there."
  [ta tb lo hi]
  (let [na (vec (within ta lo hi)) nb (vec (within tb lo hi))]
    (if (or (empty? na) (empty? nb))
      Double/POSITIVE_INFINITY
      (Math/sqrt (double (reduce min (for [s na t nb] (triangles-d2 s t))))))))

(defn tolerance
  "The indexed creature's ambiguity window: a third segment within this
  of a joint's second nearest (or, for an eye, a second within this of
  its nearest) makes the pair doubtful. A tenth of the median segment
  size."
  [index]
  (* 0.1 (double (:cell index))))

(defn segment-sides
  "The sides of `geom`'s mesh bounds in its own axes, at its world
  scale, shortest first: how thick, wide and long the segment is,
  however it is turned."
  [^Geometry geom]
  (let [b (.getBound (.getMesh geom))
        ^Vector3f s (.getWorldScale geom)
        [ex ey ez] (if (instance? BoundingBox b)
                     [(.getXExtent ^BoundingBox b) (.getYExtent ^BoundingBox b)
                      (.getZExtent ^BoundingBox b)]
                     (repeat 3 (.getRadius ^com.jme3.bounding.BoundingSphere b)))]
    (vec (sort (map #(* 2.0 (Math/abs (double %1)) (double %2)) [(.x s) (.y s) (.z s)] [ex ey ez])))))

(defn sheet?
  "Whether segment `geom` is a sheet: its thinnest side under a tenth of
  its next (a plane's mesh, a fin, a leaf, a paper-thin foot), so that it
  counts as thicker than it is (cortex.geometry/sheet-thickness)."
  [geom]
  (let [sides (segment-sides geom)]
    (> (geometry/sheet-thickness sides) (double (first sides)))))

(defn joint-reach
  "How far a joint empty may lie from segment `geom` and still be at it
  (a far joint's rule): half how thick it counts as, which is its
  thinnest side or, for a sheet, a tenth of its width
  (cortex.geometry/sheet-thickness)."
  ^double [geom]
  (* 0.5 (geometry/sheet-thickness (segment-sides geom))))

(defn fmt-length
  "`x`, a length, as text: three decimals, or more for a small one, so
  that a creature a hundredth of the size reads three figures too."
  [x]
  (let [x (double x)
        places (if (or (zero? x) (not (Double/isFinite x)))
                 3
                 (max 3 (- 2 (long (Math/floor (Math/log10 (Math/abs x)))))))]
    (format (str "%." places "f") x)))

(def ^:private fmt fmt-length)

(defn- distances-text
  [measured]
  (str/join ", " (for [{:keys [name distance]} measured]
                   (str name " " (fmt distance)))))

(defn- at-most?
  "Whether length `d` is no more than `limit`, to a ten-thousandth of
  it: a distance is measured to a millionth of itself, on meshes of
  floats, so one at the limit may read a little over it."
  [d limit]
  (<= (double d) (* 1.0001 (double limit))))

(defn- contains-point?
  "Whether point `p` ([x y z]) lies inside the segment whose world
  triangles are `ts`."
  [p ts]
  (let [[px py pz] p]
    (point-inside? ts px py pz)))

(defn- reach-from-inside
  "How segment `x` (a measured map) stands from point `p` inside segment
  `y`, `triangles` giving a segment's world triangles: {:inside (y's
  name) :depth (p to y's surface) :gap (how near x and y come around p)
  :near? (whether x comes within `allowed` of y's surface there, and p
  is no farther from x than its depth, that gap and `allowed`
  together)}."
  [p x y allowed triangles]
  (let [dx (double (:distance x)) dy (double (:distance y)) allowed (double allowed)
        ;; nearer than y's own surface, x reaches into y: they overlap there
        g (if (<= dx dy)
            0.0
            (let [r (* 1.001 dx)]
              (gap (triangles x) (triangles y) (mapv #(- (double %) r) p) (mapv #(+ (double %) r) p))))]
    {:inside (:name y) :depth dy :gap g
     :near? (and (at-most? g allowed) (at-most? dx (+ dy g allowed)))}))

(defn- reach-text
  "What the reach of each of segments `names` is, in words, with its
  figure: half its thinnest side, or a twentieth of a sheet's width."
  [names allowed sheets]
  (let [plain (remove sheets names)]
    (str/join " and "
              (concat (when (seq plain)
                        [(str "half the thinnest side of "
                              (str/join " and of " (for [n plain] (str n " (" (fmt (allowed n)) ")"))))])
                      (for [n (filter sheets names)]
                        (str "a twentieth of the width of " n ", a sheet (" (fmt (allowed n)) ")"))))))

(defn- far-message
  [joint-name a b outside allowed sheets {:keys [inside depth gap]}]
  (if inside
    (let [{:keys [name distance]} (first outside)]
      (str "joint " (pr-str joint-name) " lies " (fmt depth) " inside " inside " and "
           (fmt distance) " from " name ", more than its depth"
           (when (Double/isFinite gap) (str ", the gap between the two (" (fmt gap) ")"))
           " and " (reach-text [name] allowed sheets) " together,"
           " so it is not where the two meet; move the empty into the gap where they meet"))
    (str "joint " (pr-str joint-name) " is " (fmt (:distance a)) " from " (:name a) " and "
         (fmt (:distance b)) " from " (:name b) ", more than "
         (reach-text (map :name outside) allowed sheets)
         ": it lies outside the two it joins; move the empty into the gap where the two meet")))

(defn joint-doubts
  "The doubts about joint empty `joint-name` given its `measured` nearest
  segments (see `nearest-segments`) and the creature's `tolerance` (the
  ambiguity window): maps of :kind (:ambiguous-joint or :far-joint),
  :joint, :segments, :distances, :tolerance, for a far joint :allowed
  (each segment's `joint-reach`) and, when `point` (the empty's
  [x y z]) lies inside one of the two, :inside (how the other stands
  from that one's surface: see the chapter), and a :message saying what
  to change.
  With `given?` the tolerance is the window itself (body!'s
  :tolerance); without, the default's, a third within it is a rival
  only if half as far again as the second at most, or within a quarter
  of the window of it."
  ([joint-name measured tolerance] (joint-doubts joint-name measured tolerance false nil))
  ([joint-name measured tolerance given?] (joint-doubts joint-name measured tolerance given? nil))
  ([joint-name measured tolerance given? point]
   (let [[a b & more] measured
         d2 (double (:distance b))
         rivals (if given?
                  more
                  (filter #(let [d (double (:distance %))]
                             (or (<= d (* 1.5 d2)) (<= (- d d2) (* 0.25 (double tolerance)))))
                          more))
         near (into [a b] rivals)
         allowed (into {} (for [{:keys [name geom]} [a b]] [name (joint-reach geom)]))
         sheets (set (for [{:keys [name geom]} [a b] :when (sheet? geom)] name))
         beyond (remove #(at-most? (:distance %) (allowed (:name %))) [a b])
         ;; never far from a segment it lies inside; judged from that one's surface
         ;; each segment's triangles worked out once, and only if asked
         triangles (memoize #(world-triangles (:geom %) [0.0 0.0 0.0] 1.0))
         holders (when (and point (seq beyond)) (filterv #(contains-point? point (triangles %)) [a b]))
         left (remove (set holders) beyond)
         from (when (and (seq holders) (seq left))
                (reach-from-inside point (first left) (first holders) (allowed (:name (first left)))
                                   triangles))
         outside (if (:near? from) [] left)
         base {:joint joint-name :tolerance tolerance
               :distances (into {} (map (juxt :name :distance)) measured)}]
     (cond-> []
       (seq rivals)
       (conj (assoc base :kind :ambiguous-joint
                    :segments (mapv :name near)
                    :message (str "joint " (pr-str joint-name) " is about equally near "
                                  (count near) " segments (" (distances-text near)
                                  "; the tolerance is " (fmt tolerance) "), so which two it joins"
                                  " cannot be told; move the empty into the gap between the two"
                                  " it should join, with every other segment farther away")))
       (seq outside)
       (conj (cond-> (assoc base :kind :far-joint
                            :segments [(:name a) (:name b)]
                            :allowed allowed
                            :message (far-message joint-name a b outside allowed sheets from))
               from (assoc :inside from)))))))

(defn duplicate-doubts
  "A doubt for each pair of segments that more than one joint joins,
  given `pairs`: [joint-name [segment-name segment-name]] in order."
  [pairs]
  (for [[pair names] (group-by (comp set second) pairs)
        :when (> (count names) 1)
        :let [joints (mapv first names)]]
    {:kind :duplicate-joint :joints joints :segments (vec (sort pair))
     :message (str "joints " (str/join ", " (map pr-str (butlast joints))) " and "
                   (pr-str (last joints)) (if (= 2 (count joints)) " both join " " all join ")
                   (str/join " and " (sort pair))
                   "; delete one, or move it into the gap it belongs to"
                   " (turns about two or three axes at one place are one :cone joint)")}))

(defn- like-joints?
  [^String name]
  (let [n (-> name str/lower-case str/trim (str/replace #"\.\d+$" ""))]
    (<= (long (util/edit-distance n "joints")) 1)))

(defn naming-doubts
  "Doubts and warnings about how `creature` names its joints: a node
  named nearly, but not exactly, \"joints\" when none is; objects with a
  `joint` property that are not under the joints node."
  [^Node creature]
  (let [marker-parent (.getChild creature "joints")
        near (when-not marker-parent
               (first (filter #(like-joints? (.getName ^Spatial %))
                              (rest (util/node-seq creature)))))]
    (concat
     (when near
       [{:kind :misnamed-joints :object (.getName ^Spatial near)
         :message (str "there is no node named \"joints\", but there is "
                       (pr-str (.getName ^Spatial near))
                       "; rename it to joints (exactly, in lower case) so that cortex"
                       " finds the joints under it")}])
     (for [^Spatial s (rest (util/node-seq creature))
           :when (some? (.getUserData s "joint"))
           :let [p (.getParent s)]
           :when (not (or (and marker-parent (identical? p marker-parent))
                          (and near (identical? p near))))]
       {:kind :stray-joint :object (.getName s) :warning? true
        :message (str "object " (pr-str (.getName s)) " has a joint property but is not"
                      " under the joints node, so it joins nothing; parent it to joints"
                      " or remove the property")}))))

(defn- drawn-in
  "The triangles of indexed segment `item` in world space, each corner
  drawn in towards the centre of its bounds by a thousandth."
  [{:keys [geom lo hi]}]
  (world-triangles geom (mapv #(/ (+ (double %1) (double %2)) 2.0) lo hi) 0.999))

(defn meshes-overlap?
  "Whether indexed segments `a` and `b` (see `index-of`), each drawn in
  by a thousandth, overlap: a triangle of one crosses one of the other,
  or one lies inside the other. `triangles` gives a segment's drawn-in
  triangles (by default worked out each time)."
  ([a b] (meshes-overlap? a b drawn-in))
  ([a b triangles]
   (let [ta (triangles a) tb (triangles b)
         near-a (vec (within ta (:lo b) (:hi b)))
         near-b (vec (within tb (:lo a) (:hi a)))]
     (boolean
      (or (some (fn [s] (some (fn [t] (or (edges-cross? s t) (edges-cross? t s))) near-b)) near-a)
          (and (seq ta) (seq tb) (or (inside? (first ta) tb) (inside? (first tb) ta))))))))

(defn overlap-warnings
  "Warnings for the segments of `index` that overlap at rest though no
  joint joins them; `joined` is a set of #{geom geom} pairs."
  [{:keys [items] :as index} joined]
  ;; a segment's triangles once, however many neighbours it has
  (let [triangles (memoize drawn-in)]
    (distinct
     (for [a items
           b (nearby index (:lo a) (:hi a))
           :let [ga (:geom a) gb (:geom b)
                 na (segment-name ga) nb (segment-name gb)]
           :when (neg? (compare na nb))
           :when (not (contains? joined #{ga gb}))
           :when (meshes-overlap? a b triangles)]
       {:kind :overlap :segments [na nb] :warning? true
        :message (str "segments " na " and " nb " overlap where they start, and no joint"
                      " joins them: Bullet will push them apart on the first step;"
                      " move them apart or join them")}))))

(defn limit-warnings
  "Warnings for the hinges of `joints` (maps of :name and :description,
  as a plan holds them) built outside their limits by more than
  projection lets be (cortex.projection/slack): a hinge reads 0 as
  built, so one whose limits leave out 0 is turned into them at the
  first step, whatever the designer drew."
  [joints]
  (let [trigger (double (first (projection/slack :hinge)))]
    (for [{:keys [name description]} joints
          :when (= :hinge (:type description))
          :let [[lo hi] (:limit description)
                off (max (- (double lo) trigger) (- (- (double hi)) trigger) 0.0)]
          :when (pos? off)]
      {:kind :built-outside-limits :joint name :warning? true
       :message (str "joint " (pr-str name) " is built " (format "%.3f" (+ off trigger))
                     " rad outside its limits " (pr-str (:limit description))
                     ": at the first step it is turned to within "
                     trigger " rad of them (see org/projection.org);"
                     " build the creature in a pose within its limits, or widen them")})))
