;; Generated from org/geometry.org by lein tangle: edit the chapter, not this file.
(ns cortex.export.geometry
  "The exporters' geometry: vectors [x y z] and matrices (rows) of
  doubles, quaternions [x y z w], the change from jME's Y-up axes to
  Z up, convex hulls as triangles, a shape's solid pieces and the OBJ
  files of the pieces that are meshes."
  (:require [clojure.string :as str]))

(set! *warn-on-reflection* true)

(defn dot
  "The products of `a` and `b` summed left to right; for two vectors of
  three, the common case, with no sequence made (a creature's muscles
  take some thirty of these a joint)."
  ^double [a b]
  (if (and (vector? a) (vector? b) (== 3 (count a)) (== 3 (count b)))
    (+ (+ (* (double (a 0)) (double (b 0))) (* (double (a 1)) (double (b 1))))
       (* (double (a 2)) (double (b 2))))
    (reduce + (map #(* (double %1) (double %2)) a b))))
(defn v- [a b] (mapv #(- (double %1) (double %2)) a b))
(defn v+ [a b] (mapv #(+ (double %1) (double %2)) a b))
(defn v* [k v] (mapv #(* (double k) (double %)) v))
(defn norm ^double [v] (Math/sqrt (dot v v)))
(defn cross [[a b c] [x y z]]
  [(- (* b z) (* c y)) (- (* c x) (* a z)) (- (* a y) (* b x))])
(defn transpose [m] (apply mapv vector m))
(defn mv [m v] (mapv #(dot % v) m))
(defn mm [a b] (let [bt (transpose b)] (mapv (fn [row] (mapv #(dot row %) bt)) a)))
(def identity3 [[1.0 0.0 0.0] [0.0 1.0 0.0] [0.0 0.0 1.0]])

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

(def C [[1.0 0.0 0.0] [0.0 0.0 -1.0] [0.0 1.0 0.0]])

(defn z-up
  "A jME (Y-up) vector in Z-up axes: (x, y, z) -> (x, -z, y)."
  [v]
  (mv C v))

(defn z-up-rotation [m] (mm (mm C m) (transpose C)))

(defn hull-faces
  "The triangles [i j k] (indices into `points`, [[x y z] ...],
  counter-clockwise seen from outside) of the convex hull of `points`.
  An ex-info when they enclose no volume, its data's :normal the
  plane's (a unit vector) when they span one."
  [points]
  (let [ps (mapv #(mapv double %) points)
        n (count ps)
        size (max 1e-12 (reduce max (for [p ps q [(first ps)]] (norm (v- p q)))))
        eps (* 1e-6 size)
        _ (when (< n 3) (throw (ex-info (str n " points enclose no volume") {:points n})))
        far (fn [score] (apply max-key score (range n)))
        i0 0
        i1 (far #(norm (v- (ps %) (ps i0))))
        line (v- (ps i1) (ps i0))
        i2 (far #(norm (cross line (v- (ps %) (ps i0)))))
        normal (cross line (v- (ps i2) (ps i0)))
        i3 (far #(Math/abs (dot normal (v- (ps %) (ps i0)))))
        _ (when (or (< (norm line) eps) (< (/ (norm normal) (norm line)) eps))
            (throw (ex-info (str (count ps) " points lie on a line") {:points n})))
        _ (when (< (/ (Math/abs (dot normal (v- (ps i3) (ps i0)))) (norm normal)) eps)
            (throw (ex-info (str (count ps) " points lie on a plane")
                            {:points n :normal (v* (/ 1.0 (norm normal)) normal)})))
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

(defn obj-text
  "An OBJ file of the triangles `faces` over `points`: only the points
  the faces use, numbered from 1; `what` the piece is, for its first
  line."
  ([points faces] (obj-text points faces "a segment's convex hull"))
  ([points faces what]
   (let [used (vec (distinct (apply concat faces)))
         number (zipmap used (range 1 (inc (count used))))]
     (str "# " what ", written by cortex.export (metres, Z up)\n"
          (str/join (for [i used :let [[x y z] (points i)]]
                      (str "v " (double x) " " (double y) " " (double z) "\n")))
          (str/join (for [[a b c] faces]
                      (str "f " (number a) " " (number b) " " (number c) "\n")))))))

(def flat-thickness
  "How thick a flat piece is written: native Bullet's plate, its hull
  margin (0.001) on each side of the polygon."
  0.002)

(defn prism
  "The points of a flat piece, `points` on a plane of unit `normal`,
  each moved half of `thickness` to either side of it."
  [points normal thickness]
  (let [h (v* (/ (double thickness) 2) normal)]
    (vec (concat (map #(v+ % h) points) (map #(v- % h) points)))))

(defn axis-turn
  "The rotation that takes Z to the axis `k` (0, 1, 2 for X, Y, Z): how
  a primitive along cortex's axis k sits in MJCF, whose capsules and
  cylinders lie along their own Z."
  [k]
  (case (long (or k 1))
    0 [[0.0 0.0 1.0] [0.0 1.0 0.0] [-1.0 0.0 0.0]]
    1 [[1.0 0.0 0.0] [0.0 0.0 1.0] [0.0 -1.0 0.0]]
    2 identity3))

(defn pieces
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

(defn mesh-files
  "[segment-id piece-index] -> {:file name :points (Z-up, the segment's
  frame) :faces} of every mesh piece of `plan`, and :thickness for a
  flat piece written as a prism (see `prism`). An ex-info naming the
  segment for a piece with no area."
  [plan]
  (into {}
        (for [{:keys [id shape kind]} (:segments plan)
              :let [ps (vec (pieces shape))]
              [k {:keys [type points pos rot]}] (map-indexed vector ps)
              :when (= type :mesh)]
          (let [pts (mapv #(z-up (v+ pos (mv rot %))) points)
                [pts faces t]
                (try [pts (hull-faces pts) nil]
                     (catch clojure.lang.ExceptionInfo e
                       (if-let [normal (:normal (ex-data e))]
                         ;; flat: written as native Bullet's plate
                         (let [size (apply max (v- (apply mapv max pts) (apply mapv min pts)))
                               t (min flat-thickness (/ (double size) 100))
                               thick (prism pts normal t)]
                           [thick (hull-faces thick) t])
                         (throw (ex-info (str (if (= :rigid-body kind) "rigid body " "segment ")
                                              (pr-str id) " of creature " (:creature plan)
                                              " has no area: its " (ex-message e) ", and a"
                                              " mesh in MJCF or URDF must enclose a volume;"
                                              " give it faces that span a plane or a solid,"
                                              " or leave it out of the creature")
                                         {:segment id :creature (:creature plan)} e)))))]
            [[id k] (cond-> {:file (str (safe-name (-> (str (:creature plan)) (str/replace #".*/" "")
                                                       (str/replace #"\.blend$" "")))
                                        "-" (safe-name id)
                                        (when (next ps) (str "-" k)) ".obj")
                             :points pts :faces faces}
                      t (assoc :thickness t))]))))

(defn flat-notes
  "What a document says of segment `id`'s flat pieces in `meshes` (of
  `mesh-files`), each written as a prism: comments, one a piece."
  [meshes id]
  (for [[[i k] {:keys [thickness]}] (sort-by key meshes)
        :when (and (= i id) thickness)]
    (str "segment " id (when (pos? (long k)) (str ", piece " k)) " is flat: its polygon is"
         " written as a prism " thickness " thick (native Bullet's plate); its mass and"
         " inertia are cortex's")))

(defn meshes
  "The OBJ files `mjcf` and `urdf` name for `plan`: file name -> text.
  Each is a hull piece of a segment, in the segment's own frame, Z up."
  [plan]
  (into (sorted-map) (for [[[id] {:keys [file points faces thickness]}] (mesh-files plan)]
                       [file (if thickness
                               (obj-text points faces (str "flat segment " id "'s polygon as a prism "
                                                           thickness " thick"))
                               (obj-text points faces))])))
