;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.export
  "A creature's plan (see cortex.plan) written for other simulators:
  MuJoCo's MJCF and URDF, with its hulls as OBJ meshes beside them.

  Entry points: `mjcf` (the MJCF document of a plan, a string), `urdf`
  (the URDF document), `meshes` (the OBJ files both name, file name to
  text), `write!` (documents and meshes into files), `tree` (which
  segment hangs from which), `muscles` (each joint's strength and gains,
  from the plan), `hull-faces` (a convex hull's triangles)."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [cortex.body :as body]
            [cortex.muscle :as muscle]
            [cortex.vision :as vision])
  (:import (com.jme3.math Quaternion Vector3f)))

(set! *warn-on-reflection* true)

(defn- dot ^double [a b] (reduce + (map #(* (double %1) (double %2)) a b)))
(defn- v- [a b] (mapv #(- (double %1) (double %2)) a b))
(defn- v+ [a b] (mapv #(+ (double %1) (double %2)) a b))
(defn- v* [k v] (mapv #(* (double k) (double %)) v))
(defn- norm ^double [v] (Math/sqrt (dot v v)))
(defn- cross [[a b c] [x y z]]
  [(- (* b z) (* c y)) (- (* c x) (* a z)) (- (* a y) (* b x))])
(defn- transpose [m] (apply mapv vector m))
(defn- mv [m v] (mapv #(dot % v) m))
(defn- mm [a b] (let [bt (transpose b)] (mapv (fn [row] (mapv #(dot row %) bt)) a)))
(def ^:private identity3 [[1.0 0.0 0.0] [0.0 1.0 0.0] [0.0 0.0 1.0]])

(defn quat->matrix
  "The rotation matrix of the quaternion [x y z w] (normalised first);
  the identity for nil."
  [q]
  (if (nil? q)
    identity3
    (let [n (norm q)
          [x y z w] (map #(/ (double %) n) q)]
      [[(- 1 (* 2 (+ (* y y) (* z z)))) (* 2 (- (* x y) (* z w))) (* 2 (+ (* x z) (* y w)))]
       [(* 2 (+ (* x y) (* z w))) (- 1 (* 2 (+ (* x x) (* z z)))) (* 2 (- (* y z) (* x w)))]
       [(* 2 (- (* x z) (* y w))) (* 2 (+ (* y z) (* x w))) (- 1 (* 2 (+ (* x x) (* y y))))]])))

(defn matrix->quat
  "The quaternion [x y z w] (w >= 0) of the rotation matrix `m`."
  [m]
  (let [[[a b c] [d e f] [g h i]] m
        t (+ a e i)
        [x y z w] (cond
                    (> t 0) (let [s (* 2 (Math/sqrt (+ 1 t)))]
                              [(/ (- h f) s) (/ (- c g) s) (/ (- d b) s) (/ s 4)])
                    (and (> a e) (> a i)) (let [s (* 2 (Math/sqrt (- (+ 1 a) e i)))]
                                            [(/ s 4) (/ (+ b d) s) (/ (+ c g) s) (/ (- h f) s)])
                    (> e i) (let [s (* 2 (Math/sqrt (- (+ 1 e) a i)))]
                              [(/ (+ b d) s) (/ s 4) (/ (+ f h) s) (/ (- c g) s)])
                    :else (let [s (* 2 (Math/sqrt (- (+ 1 i) a e)))]
                            [(/ (+ c g) s) (/ (+ f h) s) (/ s 4) (/ (- d b) s)]))
        n (norm [x y z w])
        k (if (neg? w) (- n) n)]
    (mapv #(/ (double %) k) [x y z w])))

(def ^:private C [[1.0 0.0 0.0] [0.0 0.0 -1.0] [0.0 1.0 0.0]])

(defn z-up
  "A jME (Y-up) vector in Z-up axes: (x, y, z) -> (x, -z, y)."
  [v]
  (mv C v))

(defn- z-up-rotation [m] (mm (mm C m) (transpose C)))

(defn hull-faces
  "The triangles [i j k] (indices into `points`, [[x y z] ...],
  counter-clockwise seen from outside) of the convex hull of `points`.
  An ex-info when they enclose no volume."
  [points]
  (let [ps (mapv #(mapv double %) points)
        n (count ps)
        size (max 1e-12 (reduce max (for [p ps q [(first ps)]] (norm (v- p q)))))
        eps (* 1e-6 size)
        flat (fn [] (throw (ex-info (str (count ps) " points enclose no volume") {:points n})))
        _ (when (< n 4) (flat))
        far (fn [score] (apply max-key score (range n)))
        i0 0
        i1 (far #(norm (v- (ps %) (ps i0))))
        line (v- (ps i1) (ps i0))
        i2 (far #(norm (cross line (v- (ps %) (ps i0)))))
        normal (cross line (v- (ps i2) (ps i0)))
        i3 (far #(Math/abs (dot normal (v- (ps %) (ps i0)))))
        _ (when (or (< (norm line) eps)
                    (< (/ (norm normal) (norm line)) eps)
                    (< (/ (Math/abs (dot normal (v- (ps i3) (ps i0)))) (norm normal)) eps))
            (flat))
        inside (v* 0.25 (reduce v+ (map ps [i0 i1 i2 i3])))
        outward (fn [[a b c]]
                  (let [nrm (cross (v- (ps b) (ps a)) (v- (ps c) (ps a)))]
                    (if (pos? (dot nrm (v- (ps a) inside))) [a b c] [a c b])))
        height (fn [[a b c] p]
                 (let [nrm (cross (v- (ps b) (ps a)) (v- (ps c) (ps a)))
                       l (norm nrm)]
                   (if (zero? l) 0.0 (/ (dot nrm (v- p (ps a))) l))))
        start (mapv outward [[i0 i1 i2] [i0 i1 i3] [i0 i2 i3] [i1 i2 i3]])]
    (reduce
     (fn [faces i]
       (let [p (ps i)
             seen (filter #(> (height % p) eps) faces)]
         (if (empty? seen)
           faces
           (let [edges (set (for [[a b c] seen e [[a b] [b c] [c a]]] e))
                 rim (remove (fn [[a b]] (edges [b a])) edges)]
             (into (vec (remove (set seen) faces))
                   (for [[a b] rim] [a b i]))))))
     start
     (remove #{i0 i1 i2 i3} (range n)))))

(defn- obj-text
  "An OBJ file of the triangles `faces` over `points`: only the points
  the faces use, numbered from 1."
  [points faces]
  (let [used (vec (distinct (apply concat faces)))
        number (zipmap used (range 1 (inc (count used))))]
    (str "# a segment's convex hull, written by cortex.export (metres, Z up)\n"
         (str/join (for [i used :let [[x y z] (points i)]]
                     (str "v " (double x) " " (double y) " " (double z) "\n")))
         (str/join (for [[a b c] faces]
                     (str "f " (number a) " " (number b) " " (number c) "\n"))))))

(defn- box-moments
  "Bullet's box rule: the principal moments of mass `m` spread as a box
  the size of the bounding box of `points` (plus `margin` on every
  side), about the origin."
  [m points margin]
  (let [[lx ly lz] (for [k (range 3)
                         :let [xs (map #(double (nth % k)) points)]]
                     (+ (- (reduce max xs) (reduce min xs)) (* 2 (double margin))))
        k (/ (double m) 12)]
    [(* k (+ (* ly ly) (* lz lz))) (* k (+ (* lx lx) (* lz lz))) (* k (+ (* lx lx) (* ly ly)))]))

(defn- shape-points
  "The points (the segment's own frame, jME's axes) that bound `shape`:
  a hull's own; a primitive's bounding box's corners."
  [{:keys [type points half-extents radius height axis children] :as shape}]
  (case type
    (:hull :mesh) points
    :box (let [[x y z] half-extents] (for [a [-1 1] b [-1 1] c [-1 1]] [(* a x) (* b y) (* c z)]))
    :sphere (let [r radius] (for [a [-1 1] b [-1 1] c [-1 1]] [(* a r) (* b r) (* c r)]))
    (:capsule :cone :cylinder)
    (let [r (or radius (first half-extents))
          h (case type :capsule (+ (/ (double height) 2) r) :cone (/ (double height) 2)
                  :cylinder (nth half-extents (or axis 1)))
          ext (assoc [r r r] (or axis 1) h)]
      (for [a [-1 1] b [-1 1] c [-1 1]] (mapv * [a b c] ext)))
    :compound (for [{s :shape p :position q :rotation} children
                    pt (shape-points s)]
                (v+ p (mv (quat->matrix q) pt)))))

(defn- segment-info
  "What the writers need of plan segment `s`."
  [{:keys [id mass position rotation inertia shape] :as s}]
  (let [R (z-up-rotation (quat->matrix rotation))
        box? (= :box (:source inertia))
        Q (if box? identity3 (quat->matrix (:rotation inertia)))]
    (assoc s
           :pos (z-up position) :R R
           :com (if box? [0.0 0.0 0.0] (z-up (:centre inertia)))
           ;; the principal axes, columns, in the segment's Z-up frame
           :principal (mm C Q)
           :moments (vec (if box?
                           (box-moments mass (shape-points shape) (or (:margin shape) 0.0))
                           (:moments inertia)))
           :static? (zero? (double mass)))))

(defn tree
  "How the segments of `plan` hang together as a tree: {:roots [id
  ...], :children {id [id ...]}, :parent {id id}, :joint {child-id
  plan-joint}, :flipped #{joint names whose first segment is the
  child}}. `root` names the root segment (default: the heaviest; a
  static segment first). An ex-info names a joint that closes a loop."
  [plan & [root]]
  (let [segs (:segments plan)
        by-id (into {} (map (juxt :id identity)) segs)
        _ (when (and root (not (by-id root)))
            (throw (ex-info (str "no segment " (pr-str root) " to be the root; the segments are "
                                 (str/join ", " (map :id segs)))
                            {:root root})))
        rank (fn [id] (let [m (double (:mass (by-id id)))]
                        [(if (= id root) 0 1) (if (zero? m) 0 1) (- m)]))
        ordered (sort-by rank (map :id segs))
        joints (:joints plan)]
    (loop [unplaced ordered
           out {:roots [] :children {} :parent {} :joint {} :flipped #{}}]
      (if-let [r (first unplaced)]
        (let [out (loop [queue [r] placed (conj (set (keys (:parent out))) r)
                         out (update out :roots conj r) used #{}]
                    (if-let [p (first queue)]
                      (let [mine (filter #(and (some #{p} (:segments %)) (not (used (:name %)))) joints)
                            [queue placed out used]
                            (reduce (fn [[queue placed out used] {[a b] :segments n :name :as j}]
                                      (let [child (if (= a p) b a)]
                                        (when (placed child)
                                          (throw (ex-info (str "joint " (pr-str n) " joins " a " and " b
                                                               ", which other joints already join: it"
                                                               " closes a loop, and MJCF and URDF"
                                                               " describe a creature as a tree")
                                                          {:joint n})))
                                        [(conj queue child) (conj placed child)
                                         (-> out
                                             (update-in [:children p] (fnil conj []) child)
                                             (assoc-in [:parent child] p)
                                             (assoc-in [:joint child] j)
                                             (cond-> (not= child b) (update :flipped conj n)))
                                         (conj used n)]))
                                    [(subvec queue 1) placed out used] mine)]
                        (recur queue placed out used))
                      (assoc out ::placed placed)))]
          (recur (remove (::placed out) unplaced) (dissoc out ::placed)))
        out))))

(defn cone-frame
  "[turn limits] of a cone of description `d`: the turn (a matrix,
  columns the engine's X, Y and Z in the joint's frame, jME's axes)
  cortex's engine limits it in, and its three limits there."
  [d]
  (let [e 1e-3
        angles (fn [axis] (first (body/cone-engine-angles
                                  d (.fromAngleAxis (Quaternion.) (float e)
                                                    (Vector3f. (float (axis 0)) (float (axis 1))
                                                               (float (axis 2)))))))
        ;; a turn e about the frame's axis k moves the engine's angles by
        ;; -e (turn^-1 e_k): row k of the turn
        rows (mapv (fn [k] (mapv #(double (Math/round (/ (- (double %)) e)))
                                 (angles (assoc [0 0 0] k 1))))
                   (range 3))
        [_ limits] (body/cone-engine-angles d (Quaternion.))]
    (when-not (= (sort (map #(Math/abs (double %)) (flatten rows))) [0.0 0.0 0.0 0.0 0.0 0.0 1.0 1.0 1.0])
      (throw (ex-info (str "cone " (pr-str d) ": its engine frame is not a turn of its own")
                      {:rows rows})))
    [rows (mapv double limits)]))

(defn- axis-of
  "A hinge description's axis as [x y z] (Blender's axes), unit; X
  when it gives none."
  [{:keys [axis]}]
  (let [a (cond (nil? axis) [1 0 0]
                (instance? Vector3f axis) (let [^Vector3f v axis] [(.x v) (.y v) (.z v)])
                :else axis)]
    (v* (/ 1.0 (norm a)) a)))

(defn- blender->jme [[x y z]] [x z (- y)])

(defn- dofs
  "The one-axis degrees of freedom of plan joint `j` in the tree, the
  child's side first: [{:name :axis (Z-up world) :range [lo hi] :frame-axis
  k}], in the order the child hangs from them; for a point joint,
  :ball."
  [{:keys [name type description rotation]} flipped?]
  (let [E (quat->matrix rotation)]
    (case type
      :hinge (let [[lo hi] (:limit description)
                   [lo hi] (if flipped? [(- (double hi)) (- (double lo))] [(double lo) (double hi)])
                   a (blender->jme (axis-of description))]
               [{:name name :axis (z-up (mv E a)) :range [lo hi] :jme-axis (mv E a)}])
      :cone (let [[turn limits] (cone-frame description)
                  G (mm E turn)
                  order (if flipped? [0 1 2] [2 1 0])]
              (vec (for [k order
                         :let [l (nth limits k)
                               col (mapv #(nth % k) G)]]
                     {:name (str name "/" (nth ["x" "y" "z"] k))
                      :axis (z-up col) :range [(- l) l] :jme-axis col :engine-axis k
                      ;; which of the joint frame's own axes this is
                      :frame-axis (first (keep-indexed #(when-not (zero? (double %2)) %1)
                                                       (mapv #(nth % k) turn)))})))
      :point [{:name name :ball true}]
      (throw (ex-info (str "joint " (pr-str name) ": a " (clojure.core/name type)
                           " joint cannot be exported yet")
                      {:joint name :type type})))))

(defn- world-inertia
  "A segment's (jME world) centre of mass, principal axes (columns) and
  moments."
  [{:keys [position rotation inertia shape mass]}]
  (let [R (quat->matrix rotation)
        box? (= :box (:source inertia))]
    {:com (v+ position (mv R (if box? [0 0 0] (:centre inertia))))
     :axes (mm R (if box? identity3 (quat->matrix (:rotation inertia))))
     :moments (if box? (box-moments mass (shape-points shape) (or (:margin shape) 0.0))
                  (:moments inertia))
     :mass (double mass)}))

(defn- pin-inertia
  "cortex.muscle/pivot-inertia of a segment (see `world-inertia`) about
  the world axis `axis` through `pin` (relative to its centre of mass)."
  ^double [{:keys [axes moments mass]} axis pin]
  (if (zero? (double mass))
    Double/POSITIVE_INFINITY
    (let [inv (reduce + (map (fn [i k] (let [a (dot axis (mapv #(nth % k) axes))]
                                          (/ (* a a) (double i))))
                             moments (range 3)))
          own (if (pos? inv) (/ 1.0 inv) Double/POSITIVE_INFINITY)
          along (dot pin axis)]
      (+ own (* (double mass) (- (dot pin pin) (* along along)))))))

(defn muscles
  "Each joint's muscle, by name, as cortex.muscle works it out from the
  built creature, here from the plan: {:strength s :kp k :kd d} for a
  hinge, :kp and :kd [x y z] about the joint frame's axes (jME's
  order) for a cone or point joint."
  [plan]
  (let [segs (into {} (map (juxt :id world-inertia)) (:segments plan))]
    (into {}
          (for [{:keys [name type description pivot rotation] [a b] :segments} (:joints plan)]
            (let [A (segs a) B (segs b)
                  pa (v- pivot (:com A)) pb (v- pivot (:com B))
                  given (fn [k default] (if-some [v (get description k)] (double v) (default)))
                  strength (given :strength
                                  #(muscle/default-strength [[(:mass A) (norm pa)] [(:mass B) (norm pb)]]))
                  about (fn [ax pin-a pin-b]
                          (let [i (/ 1.0 (+ (/ 1.0 (pin-inertia A ax pin-a))
                                            (/ 1.0 (pin-inertia B ax pin-b))))]
                            (if (and (Double/isFinite i) (pos? i)) i 1.0)))
                  sized (fn [ax] (let [i (about ax pa pb)]
                                   (muscle/default-gains strength i
                                                         (min i (about ax [0 0 0] [0 0 0])))))
                  E (quat->matrix rotation)]
              [name
               (if (= type :hinge)
                 (let [g (sized (mv E (blender->jme (axis-of description))))]
                   {:strength strength :kp (given :kp #(:kp g)) :kd (given :kd #(:kd g))})
                 (let [gs (mapv #(sized (mapv (fn [row] (nth row %)) E)) (range 3))
                       per (fn [k] (if-some [v (get description k)]
                                     (vec (repeat 3 (double v)))
                                     (mapv k gs)))]
                   {:strength strength :kp (per :kp) :kd (per :kd)}))])))))

(defn- text [v]
  (cond (sequential? v) (str/join " " (map text v))
        (or (float? v) (ratio? v)) (str (double v))
        (keyword? v) (name v)
        :else (str v)))

(defn- escape [s]
  (-> (str s) (str/replace "&" "&amp;") (str/replace "<" "&lt;")
      (str/replace ">" "&gt;") (str/replace "\"" "&quot;")))

(defn- flatten-children
  "Children as given, with seqs of children spliced in."
  [children]
  (mapcat #(if (seq? %) (flatten-children %) [%]) children))

(defn- xml
  "The element `node` ([tag attrs & children], nil children skipped,
  strings written as comments) as indented text."
  ([node] (xml node ""))
  ([node indent]
   (if (string? node)
     (str indent "<!-- " (str/replace node "--" "- -") " -->\n")
     (let [[tag & more] node
           [attrs children] (if (map? (first more)) [(first more) (rest more)] [{} more])
           children (remove nil? (flatten-children children))
           open (str indent "<" (name tag)
                     (str/join (for [[k v] attrs :when (some? v)]
                                 (str " " (name k) "=\"" (escape (text v)) "\""))))]
       (if (empty? children)
         (str open "/>\n")
         (str open ">\n" (str/join (map #(xml % (str indent "  ")) children))
              indent "</" (name tag) ">\n"))))))

(defn- axis-turn
  "The rotation that takes Z to the axis `k` (0, 1, 2 for X, Y, Z): how
  a primitive along cortex's axis k sits in MJCF, whose capsules and
  cylinders lie along their own Z."
  [k]
  (case (long (or k 1))
    0 [[0.0 0.0 1.0] [0.0 1.0 0.0] [-1.0 0.0 0.0]]
    1 [[1.0 0.0 0.0] [0.0 0.0 1.0] [0.0 -1.0 0.0]]
    2 identity3))

(defn- pieces
  "The solid pieces of `shape`, each the shape with :pos and :rot (a
  matrix), in the segment's frame, jME's axes; a hull or cone as {:type
  :mesh :points [...]}."
  [{:keys [type] :as shape}]
  (let [at-origin #(assoc % :pos [0.0 0.0 0.0] :rot identity3)]
    (case type
      :compound (for [{s :shape p :position q :rotation} (:children shape)
                      piece (pieces s)]
                  (let [R (quat->matrix q)]
                    (-> piece (update :pos #(v+ p (mv R %))) (update :rot #(mm R %)))))
      (:hull :mesh) [(at-origin {:type :mesh :points (mapv #(mapv double %) (:points shape))})]
      :cone (let [{:keys [radius height axis] :or {axis 1}} shape
                  h (/ (double height) 2)
                  [i j] (remove #{axis} [0 1 2])
                  base (for [n (range 32) :let [a (/ (* 2 Math/PI n) 32)]]
                         (-> [0.0 0.0 0.0] (assoc axis (- h))
                             (assoc i (* (double radius) (Math/cos a)))
                             (assoc j (* (double radius) (Math/sin a)))))]
              [(at-origin {:type :mesh :points (vec (cons (assoc [0.0 0.0 0.0] axis h) base))})])
      (:box :sphere :capsule :cylinder) [(at-origin shape)]
      (throw (ex-info (str "a " (pr-str type) " shape cannot be exported") {:shape shape})))))

(defn- safe-name [s] (str/replace (str s) #"[^A-Za-z0-9._-]" "_"))

(defn- mesh-files
  "[segment-id piece-index] -> {:file name :points (Z-up, the segment's
  frame) :faces} of every mesh piece of `plan`."
  [plan]
  (into {}
        (for [{:keys [id shape]} (:segments plan)
              :let [ps (vec (pieces shape))]
              [k {:keys [type points pos rot]}] (map-indexed vector ps)
              :when (= type :mesh)]
          (let [pts (mapv #(z-up (v+ pos (mv rot %))) points)]
            [[id k] {:file (str (safe-name (-> (str (:creature plan)) (str/replace #".*/" "")
                                               (str/replace #"\.blend$" "")))
                                "-" (safe-name id)
                                (when (next ps) (str "-" k)) ".obj")
                     :points pts :faces (hull-faces pts)}]))))

(defn meshes
  "The OBJ files `mjcf` and `urdf` name for `plan`: file name -> text.
  Each is a hull piece of a segment, in the segment's own frame, Z up."
  [plan]
  (into (sorted-map) (for [[_ {:keys [file points faces]}] (mesh-files plan)]
                       [file (obj-text points faces)])))

(defn- wxyz [m] (let [[x y z w] (matrix->quat m)] [w x y z]))

(defn- local-point
  "The Z-up world point `p` in segment `info`'s Z-up frame."
  [{:keys [pos R]} p]
  (mv (transpose R) (v- p pos)))

(defn- local-vector [{:keys [R]} v] (mv (transpose R) v))

(defn- bounds
  "[centre half-sizes] of the bounding box of `points`."
  [points]
  (let [lo (apply mapv min points) hi (apply mapv max points)]
    [(v* 0.5 (v+ lo hi)) (v* 0.5 (v- hi lo))]))

(defn- piece-geom
  "The MJCF <geom> of `piece` (see `pieces`), number `k`, of segment `info`."
  [{:keys [id friction]} meshes k {:keys [type pos rot half-extents radius height axis] :as piece}]
  (let [common {:name (str id (when (pos? k) (str "/" k))) :friction [(double friction) 0.005 0.0001]}
        placed (fn [R] {:pos (z-up pos) :quat (wxyz (mm C R))})]
    (case type
      :mesh [:geom (merge common {:type "mesh" :mesh (:file (meshes [id k]))})]
      :box [:geom (merge common (placed rot) {:type "box" :size half-extents})]
      :sphere [:geom (merge common (placed rot) {:type "sphere" :size [radius]})]
      :capsule [:geom (merge common (placed (mm rot (axis-turn axis)))
                             {:type "capsule" :size [radius (/ (double height) 2)]})]
      :cylinder (let [k (or axis 1)
                      r (nth half-extents (if (zero? k) 1 0))]
                  [:geom (merge common (placed (mm rot (axis-turn k)))
                                {:type "cylinder" :size [r (nth half-extents k)]})]))))

(defn- eye-camera
  "The MJCF <camera> of plan eye `e`, in segment `info`'s body."
  [info {:keys [name spec position rotation]}]
  (let [fov (vision/field-of-view spec)
        [w h] (:resolution spec)
        R (z-up-rotation (quat->matrix rotation))]
    [:camera (merge {:name name :pos (local-point info (z-up position))
                     :quat (wxyz (mm (transpose (:R info)) R))
                     :resolution [w h]}
                    (if (= :orthographic (:projection spec))
                      {:projection "orthographic" :fovy (:height fov)}
                      {:fovy (:y fov)}))]))

(defn- mjcf-joints
  "The <joint>s by which segment `info` hangs from its parent by plan
  joint `j`."
  [info j dofs]
  (let [pin (local-point info (z-up (:pivot j)))]
    (for [{:keys [name axis range ball]} dofs]
      (if ball
        [:joint {:name name :type "ball" :pos pin}]
        [:joint {:name name :type "hinge" :pos pin :axis (local-vector info axis)
                 :range range}]))))

(defn- plan-dofs
  "Each plan joint's dofs (see `dofs`) in the tree `t`, by joint name."
  [plan {:keys [flipped]}]
  (into {} (for [j (:joints plan)] [(:name j) (dofs j (contains? flipped (:name j)))])))

(defn joint-dofs
  "How each joint of `plan` is written, by name: {:flipped? (its first
  segment is the child) :dofs [{:name (the MJCF joint) :axis (Z-up
  world) :range [lo hi] :engine-axis k (a cone's)} ...]}, or :ball."
  ([plan] (joint-dofs plan {}))
  ([plan {:keys [root]}]
   (let [{:keys [flipped] :as t} (tree plan root)]
     (into {} (for [[n ds] (plan-dofs plan t)]
                [n {:flipped? (contains? flipped n) :dofs ds}])))))

(defn mjcf
  "The MJCF document (a string) of `plan` (see cortex.plan), its meshes
  named by file (see `meshes`, written beside it). `opts`: :root, the
  segment to hang the rest from (default the heaviest)."
  ([plan] (mjcf plan {}))
  ([plan {:keys [root]}]
   (let [infos (into {} (map (juxt :id segment-info)) (:segments plan))
         {:keys [roots children joint] :as t} (tree plan root)
         all-dofs (plan-dofs plan t)
         meshes (mesh-files plan)
         ms (muscles plan)
         eyes (group-by :segment (:eyes plan))
         child-of (into {} (for [[child j] joint] [(:name j) child]))
         body (fn body [id parent]
                (let [{:keys [R pos com principal moments mass static? shape] :as info} (infos id)
                      j (joint id)
                      P (if parent (:R (infos parent)) identity3)]
                  [:body {:name id
                          :pos (if parent (mv (transpose P) (v- pos (:pos (infos parent)))) pos)
                          :quat (wxyz (mm (transpose P) R))}
                   (cond j (mjcf-joints info j (all-dofs (:name j)))
                         (not static?) [:freejoint {:name (str id "/free")}])
                   (when-not static?
                     [:inertial {:pos com :quat (wxyz principal) :mass (double mass)
                                 :diaginertia moments}])
                   (map-indexed #(piece-geom info meshes %1 %2) (pieces shape))
                   (let [[c half] (bounds (map z-up (shape-points shape)))]
                     [:site {:name (str id "/touch") :type "box" :pos c
                             :size (mapv #(+ 0.01 (double %)) half) :rgba [0 0 0 0]}])
                   (map #(eye-camera info %) (eyes id))
                   (map #(body % id) (children id))]))]
     (xml
      [:mujoco {:model (:creature plan)}
       (str "written by cortex.export from the plan of creature " (:creature plan)
            ": metres, kilograms, seconds, radians; Z up (cortex's jME Y is Z here,"
            " its Z is -Y); see org/export.org for every mapping and what is lost")
       [:compiler {:angle "radian" :inertiafromgeom "false" :autolimits "true"}]
       [:option {:timestep (/ 1.0 60) :gravity [0.0 0.0 -9.81] :integrator "implicitfast"
                 :solver "Newton" :cone "pyramidal"}]
       (when (seq meshes)
         [:asset (for [[_ {:keys [file]}] (sort-by key meshes)]
                   [:mesh {:name file :file file}])])
       [:worldbody (map #(body % nil) roots)]
       (when (seq (:joints plan))
         [:contact (for [{[a b] :segments} (:joints plan)] [:exclude {:body1 a :body2 b}])])
       [:actuator
        (for [{:keys [name rotation]} (:joints plan)
              :let [{:keys [strength kp kd]} (ms name)]
              {dof :name :keys [ball frame-axis]} (all-dofs name)]
          (if ball
            ;; a ball joint's torque is in its body's frame: the joint
            ;; frame's axes (Blender's X, Y, Z) there
            (for [[axis b] [["x" [1 0 0]] ["y" [0 1 0]] ["z" [0 0 1]]]]
              [:motor {:name (str "muscle/" dof "/" axis) :joint dof
                       :gear (concat (local-vector (infos (child-of name))
                                                   (z-up (mv (quat->matrix rotation) (blender->jme b))))
                                     [0 0 0])
                       :ctrlrange [(- strength) strength]}])
            [:position {:name (str "muscle/" dof) :joint dof
                        :kp (if frame-axis (nth kp frame-axis) kp)
                        :kv (if frame-axis (nth kd frame-axis) kd)
                        :forcerange [(- strength) strength]}]))]
       [:sensor
        (for [{:keys [name]} (:joints plan)
              {dof :name :keys [ball]} (all-dofs name)]
          (if ball
            (list [:ballquat {:name (str "angle/" dof) :joint dof}]
                  [:ballangvel {:name (str "speed/" dof) :joint dof}])
            (list [:jointpos {:name (str "angle/" dof) :joint dof}]
                  [:jointvel {:name (str "speed/" dof) :joint dof}])))
        (for [{:keys [id]} (:segments plan)]
          [:touch {:name (str "touch/" id) :site (str id "/touch")}])]]))))

(defn- rpy
  "Roll, pitch, yaw (URDF's fixed X, Y, Z angles: R = Rz Ry Rx) of `m`."
  [m]
  (let [[[a _ _] [d _ _] [g h i]] m]
    [(Math/atan2 h i) (Math/asin (max -1.0 (min 1.0 (- (double g))))) (Math/atan2 d a)]))

(defn- origin
  "URDF's <origin> of a frame at `p` turned by `R` (Z-up world), seen
  from the frame [o F]."
  [[o F] p R]
  [:origin {:xyz (mv (transpose F) (v- p o)) :rpy (rpy (mm (transpose F) R))}])

(defn- urdf-geometry
  [meshes id k {:keys [type half-extents radius height axis]}]
  [:geometry
   (case type
     :mesh [:mesh {:filename (:file (meshes [id k]))}]
     :box [:box {:size (v* 2 half-extents)}]
     :sphere [:sphere {:radius radius}]
     :capsule [:capsule {:radius radius :length height}]
     :cylinder (let [k (or axis 1)]
                 [:cylinder {:radius (nth half-extents (if (zero? k) 1 0))
                             :length (* 2 (double (nth half-extents k)))}]))])

(defn- urdf-link
  "The <link> of segment `info` whose frame is `frame` [o F]."
  [{:keys [id pos R com principal moments mass friction shape static?]} meshes frame]
  [:link {:name id}
   [:inertial
    (origin frame (v+ pos (mv R com)) (mm R principal))
    [:mass {:value (double mass)}]
    (let [[a b c] moments]
      [:inertia {:ixx a :ixy 0.0 :ixz 0.0 :iyy b :iyz 0.0 :izz c}])]
   (for [[k {:keys [type] :as piece}] (map-indexed vector (pieces shape))
         tag [:visual :collision]]
     (let [placed (if (= type :mesh)
                    [(:pos piece) identity3]
                    [(:pos piece) (mm (:rot piece)
                                      (if (#{:capsule :cylinder} type) (axis-turn (:axis piece)) identity3))])
           [pp pr] placed]
       [tag (origin frame (v+ pos (mv R (z-up pp))) (mm R (mm (mm C pr) (transpose C))))
        (urdf-geometry meshes id k piece)]))
   [:contact [:lateral_friction {:value (double friction)}]]])

(defn urdf
  "The URDF document (a string) of `plan`, naming the same meshes as
  `mjcf`. `opts` as for `mjcf`. An ex-info for a creature in several
  pieces (URDF is one tree)."
  ([plan] (urdf plan {}))
  ([plan {:keys [root]}]
   (let [infos (into {} (map (juxt :id segment-info)) (:segments plan))
         {:keys [roots children joint] :as t} (tree plan root)
         _ (when (next roots)
             (throw (ex-info (str "creature " (:creature plan) " is in " (count roots)
                                  " pieces (roots " (str/join ", " roots)
                                  "); a URDF robot is one tree")
                             {:roots roots})))
         all-dofs (plan-dofs plan t)
         meshes (mesh-files plan)
         ms (muscles plan)
         frame-of (fn [id] (if-let [j (joint id)]
                             [(z-up (:pivot j)) (:R (infos id))]
                             [(:pos (infos id)) (:R (infos id))]))
         tiny (fn [n] [:link {:name n}
                       [:inertial [:mass {:value 1e-6}]
                        [:inertia {:ixx 1e-9 :ixy 0.0 :ixz 0.0 :iyy 1e-9 :iyz 0.0 :izz 1e-9}]]])
         links (fn links [id]
                 (cons (urdf-link (infos id) meshes (frame-of id))
                       (mapcat links (children id))))
         joints (fn joints [parent]
                  (mapcat
                   (fn [id]
                     (let [{jn :name :keys [type rotation] :as j} (joint id)
                           [o F :as frame] (frame-of id)
                           ds (all-dofs jn)
                           strength (:strength (ms jn))
                           ds (if (some :ball ds)
                                (for [[k b] (map-indexed vector [[1 0 0] [0 1 0] [0 0 1]])]
                                  {:name (str jn "/" (["x" "y" "z"] k)) :continuous true
                                   :axis (z-up (mv (quat->matrix rotation) (blender->jme b)))})
                                ds)
                           chain (concat [parent] (for [k (range 1 (count ds))] (str "_" jn "/" k)) [id])]
                       (concat
                        (when (next ds)
                          [(str "joint " jn ": a " (name type) " joint, written as " (count ds)
                                " one-axis joints through links of negligible mass (_" jn "/1, ...)"
                                (when (= type :cone) ", in the order cortex's engine limits it"))])
                        (map tiny (butlast (rest chain)))
                        (for [[{:keys [name axis range continuous]} [p c]]
                              (map vector ds (partition 2 1 chain))]
                          [:joint {:name name :type (if continuous "continuous" "revolute")}
                           [:parent {:link p}] [:child {:link c}]
                           (if (= p parent)
                             (origin (frame-of parent) o F)
                             [:origin {:xyz [0.0 0.0 0.0] :rpy [0.0 0.0 0.0]}])
                           [:axis {:xyz (mv (transpose F) axis)}]
                           (if continuous
                             [:limit {:effort strength :velocity 100.0}]
                             [:limit {:lower (first range) :upper (second range)
                                      :effort strength :velocity 100.0}])])
                        (joints id))))
                   (children parent)))
         r (first roots)
         [o F] (frame-of r)]
     (xml
      [:robot {:name (:creature plan)}
       (str "written by cortex.export from the plan of creature " (:creature plan)
            ": metres, kilograms, seconds, radians; Z up; see org/export.org")
       (str "the root link " r " is placed in the world at xyz " (text o) ", quaternion [x y z w] "
            (text (matrix->quat F)))
       (links r)
       (joints r)]))))

(defn write!
  "Write `plan` as MJCF to `mjcf-path` and/or URDF to `urdf-path` (nil
  for neither), each with its meshes beside it. `opts` as for `mjcf`.
  Returns the files written."
  ([plan mjcf-path urdf-path] (write! plan mjcf-path urdf-path {}))
  ([plan mjcf-path urdf-path opts]
   (let [ms (meshes plan)]
     (vec (for [[path doc] [[mjcf-path mjcf] [urdf-path urdf]]
                :when path
                f (let [file (io/file path)
                        dir (or (.getParentFile (.getAbsoluteFile file)) (io/file "."))]
                    (io/make-parents file)
                    (spit file (doc plan opts))
                    (cons (str file) (for [[n t] ms]
                                       (let [mf (io/file dir n)]
                                         (spit mf t)
                                         (str mf)))))]
            f)))))
