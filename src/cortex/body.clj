(ns cortex.body
  "Give a creature loaded from Blender a physical body: a rigid body for
  every segment and a Bullet joint for every joint marker, as the
  creature's designer described them in Blender.

  Entry points: `body!` (all of it), `physical!` (segments made solid),
  `joints!` (segments joined), `joints` (the joint markers),
  `joint-targets` (the two segments a joint joins), `connect`,
  `joint-dispatch` (a multimethod: add joint types), `joint-types`,
  `read-joint` (a joint description, read safely), `segments`, `mass`,
  `pivot`, `pivot-in-world`."
  (:require [clojure.edn :as edn]
            [clojure.string :as str]
            [cortex.sense :as sense]
            [cortex.util :as util])
  (:import (com.jme3.bounding BoundingBox)
           (com.jme3.bullet.collision.shapes HullCollisionShape)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints ConeJoint HingeJoint SixDofJoint)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.collision CollisionResults)
           (com.jme3.math Matrix3f Vector3f)
           (com.jme3.scene Geometry Mesh Node Spatial VertexBuffer$Type)))

(set! *warn-on-reflection* true)

(def max-hull-points
  "The most points a segment's hull keeps. Bullet advises convex hulls of
  no more than about a hundred vertices: contacts on bigger hulls cost
  more and buy nothing a body needs."
  100)

(defn mesh-points
  "The distinct vertex positions of `mesh`, each multiplied by `scale`,
  as Vector3fs; none when the mesh has no positions."
  [^Mesh mesh ^Vector3f scale]
  (let [buffer (.getFloatBuffer mesh VertexBuffer$Type/Position)
        n (if buffer (quot (.limit buffer) 3) 0)]
    (distinct
     (for [i (range n)]
       (Vector3f. (* (.x scale) (.get buffer (int (* 3 i))))
                  (* (.y scale) (.get buffer (int (+ 1 (* 3 i)))))
                  (* (.z scale) (.get buffer (int (+ 2 (* 3 i))))))))))

(defn sphere-directions
  "`n` directions spread evenly over the unit sphere (a Fibonacci
  lattice): always the same ones for the same n."
  [n]
  (let [golden (* Math/PI (- 3 (Math/sqrt 5)))]
    (for [i (range n)
          :let [y (- 1 (/ (* 2 (+ i 0.5)) n))
                r (Math/sqrt (- 1 (* y y)))
                a (* golden i)]]
      (Vector3f. (* r (Math/cos a)) y (* r (Math/sin a))))))

(defn simplify-hull
  "At most `limit` of `points` that span nearly the same convex hull:
  the point furthest out in each of `limit` evenly spread directions.
  Each is a corner of the true hull, so the simplified hull lies inside
  it and touches it in every direction sampled."
  [points limit]
  (if (<= (count points) limit)
    (vec points)
    (vec (distinct
          (for [^Vector3f d (sphere-directions limit)]
            (apply max-key #(.dot d ^Vector3f %) points))))))

(defn- hull-shape
  "A convex hull collision shape for `geom`: its mesh at the geometry's
  world scale (a rigid body has no scale of its own), simplified to at
  most `max-hull-points` points. The geometry keeps its full visual mesh."
  ^HullCollisionShape [^Geometry geom]
  (let [points (simplify-hull (mesh-points (.getMesh geom) (.getWorldScale geom))
                              max-hull-points)]
    (when (< (count points) 4)
      (throw (ex-info (str "segment " (pr-str (.getName geom)) " has " (count points)
                           " distinct vertices; a solid needs at least 4")
                      {:object (.getName geom) :vertices (count points)})))
    (HullCollisionShape. (float-array (mapcat (fn [^Vector3f p] [(.x p) (.y p) (.z p)])
                                              points)))))

(defn mass
  "The mass Blender's designer gave `geom` (its `mass` custom property),
  1 when there is none; 0 makes the segment static. Anything but a
  finite, non-negative number is an error naming the object."
  [^Geometry geom]
  (let [m (sense/meta-data geom "mass")
        owner (if (some? (.getUserData geom "mass")) geom (.getParent geom))]
    (cond
      (nil? m) 1.0
      (and (number? m) (Double/isFinite (double m)) (not (neg? m))) (double m)
      :else (throw (ex-info (str "object " (pr-str (.getName ^Spatial owner))
                                 ": mass must be a non-negative number, not "
                                 (pr-str m))
                            {:object (.getName ^Spatial owner) :mass m})))))

(defn segments
  "The Geometries of `creature`: its segments."
  [^Node creature]
  (filter #(instance? Geometry %) (util/node-seq creature)))

(defn physical!
  "Make every segment of `creature` solid: a rigid body with a convex
  hull shape and the segment's mass. Segments that already have a rigid
  body keep it, so calling this twice is harmless. Returns the creature."
  [^Node creature]
  (.updateGeometricState creature)
  (doseq [^Geometry geom (segments creature)
          :when (nil? (.getControl geom RigidBodyControl))]
    (.addControl geom (RigidBodyControl. (hull-shape geom) (float (mass geom)))))
  creature)

(def ^{:doc "The children of the creature's \"joints\" node: one empty
  per joint."
       :arglists '([creature])}
  joints
  (sense/sense-nodes "joints"))

(defn- physical?
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

(defn- cell-range
  "The grid cells, as [i j k], that the box from `lo` to `hi` covers."
  [cell lo hi]
  (let [[[i0 j0 k0] [i1 j1 k1]] (for [corner [lo hi]]
                                  (map #(long (Math/floor (/ (double %) cell))) corner))]
    (for [i (range i0 (inc i1)) j (range j0 (inc j1)) k (range k0 (inc k1))]
      [i j k])))

(defn- cell-count
  [cell lo hi]
  (reduce * (map #(inc (- (long (Math/floor (/ (double %2) cell)))
                          (long (Math/floor (/ (double %1) cell)))))
                 lo hi)))

(defn segment-index
  "The physical segments of `parts` indexed by where they are: each
  one's world bounds, and a grid of cells the size of a typical segment
  listing the segments that reach into each cell. The joint search asks
  the index for the segments near a point instead of testing every
  segment of the creature, which keeps building a body of n segments
  close to linear in n."
  [^Node parts]
  (let [items (vec (for [g (segments parts) :when (physical? g)]
                     (let [[lo hi] (corners g)] {:geom g :lo lo :hi hi})))
        sizes (sort (for [{:keys [lo hi]} items] (apply max (map - hi lo))))
        cell (max 1e-3 (if (seq sizes) (nth sizes (quot (count sizes) 2)) 1.0))
        {big true small false} (group-by #(let [{:keys [lo hi]} (items %)]
                                            (> (cell-count cell lo hi) max-cells-per-segment))
                                         (range (count items)))
        grid (reduce (fn [grid i]
                       (let [{:keys [lo hi]} (items i)]
                         (reduce #(update %1 %2 (fnil conj []) i) grid (cell-range cell lo hi))))
                     {} small)]
    {:items items :cell cell :grid grid :big (vec big)
     :lo (if (seq items) (apply map min (map :lo items)) [0 0 0])
     :hi (if (seq items) (apply map max (map :hi items)) [0 0 0])}))

(defn- overlaps?
  [lo hi lo' hi']
  (every? true? (map #(and (<= %1 %4) (<= %3 %2)) lo hi lo' hi')))

(defn- nearby
  "The items of `index` whose bounds meet the box from `lo` to `hi`."
  [{:keys [items cell grid big]} lo hi]
  (let [candidates (if (> (cell-count cell lo hi) (count items))
                     (range (count items))
                     (distinct (concat (mapcat grid (cell-range cell lo hi)) big)))]
    (for [i (sort candidates)
          :let [item (items i)]
          :when (overlaps? lo hi (:lo item) (:hi item))]
      item)))

(defn- touching
  "The physical segments in `index` whose triangles meet a cube of
  half-width `radius` centred on `center`."
  [index ^Vector3f center radius]
  (let [c [(.x center) (.y center) (.z center)]
        cube (BoundingBox. center (float radius) (float radius) (float radius))]
    (for [{:keys [^Geometry geom]} (nearby index (map #(- % radius) c) (map #(+ % radius) c))
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

(defn targets-near
  "The two physical segments in `index` (see `segment-index`) closest
  to `joint`, ordered as `joint-targets` says."
  [index ^Spatial joint]
  (let [center (.getWorldTranslation joint)
        limit (* 2 (max 0.01 (reach index center)))
        ;; each cube size is probed once, however often the search asks
        found (memoize (fn [r] (vec (touching index center r))))
        [lo hi] (loop [r 0.01]
                  (cond (>= (count (found r)) 2) [(/ r 2) r]
                        (> r limit)
                        (throw (ex-info (str "joint " (pr-str (.getName joint))
                                             ": found " (count (found r))
                                             " segment(s) near it, a joint needs two")
                                        {:joint (.getName joint)
                                         :found (map #(.getName ^Spatial %) (found r))}))
                        :else (recur (* 2 r))))
        r (loop [lo lo hi hi i 0]
            (if (or (= i 24) (= 2 (count (found hi))))
              hi
              (let [mid (/ (+ lo hi) 2)]
                (if (>= (count (found mid)) 2)
                  (recur lo mid (inc i))
                  (recur mid hi (inc i))))))
        pair (take 2 (sort-by #(.getName ^Spatial %) (found r)))]
    (sort-by #(.dot (Vector3f. 1 1 1) (joint-frame-position joint %)) pair)))

(defn joint-targets
  "The two physical segments of `parts` closest to `joint`, found by
  growing a cube around the joint from 0.01 by doubling until it touches
  two of them, then closing in on the smallest such cube. They are
  ordered by where they lie in the joint's frame (in Blender's axes):
  the one with the smaller x + y + z first. Call after `physical!`.
  When even a cube holding the whole creature finds fewer than two, the
  error names the joint."
  [^Node parts ^Spatial joint]
  (.updateGeometricState parts)
  (targets-near (segment-index parts) joint))

(def ^:private constants
  {'Math/PI Math/PI, 'java.lang.Math/PI Math/PI,
   'Math/E Math/E, 'java.lang.Math/E Math/E})

(def ^:private operators
  {'+ +, '- -, '* *, '/ /})

(def ^:private vector-constructors
  '#{Vector3f. com.jme3.math.Vector3f.})

(defn- not-allowed
  [form why]
  (throw (ex-info (str why ": " (pr-str form)) {:form form})))

(defn- evaluate
  "The value of `form`, a joint description read as data, allowing only
  numbers, keywords, vectors, maps, Math/PI, Math/E, + - * / and
  (Vector3f. x y z). Nothing else is evaluated, so nothing in a file
  can run code."
  [form]
  (cond
    (or (number? form) (keyword? form)) form
    (vector? form) (mapv evaluate form)
    (map? form) (into {} (map (fn [[k v]] [(evaluate k) (evaluate v)])) form)
    (symbol? form) (if (contains? constants form)
                     (constants form)
                     (not-allowed form "unknown symbol"))
    (seq? form)
    (let [[op & args] form]
      (when-not (or (contains? operators op) (contains? vector-constructors op))
        (not-allowed form "not an allowed operation"))
      (let [values (map evaluate args)]
        (when-not (every? number? values)
          (not-allowed form "arguments must be numbers"))
        (if (contains? operators op)
          (try (apply (operators op) values)
               (catch ArithmeticException e (not-allowed form (ex-message e))))
          (if (= 3 (count values))
            (let [[x y z] values] (Vector3f. (float x) (float y) (float z)))
            (not-allowed form "Vector3f takes three numbers")))))
    :else (not-allowed form "not allowed in a joint description")))

(def ^:private max-description-length 10000)

(defn read-joint
  "The joint description `text` (the `joint` custom property: a Clojure
  map such as {:type :hinge :limit [0 (/ Math/PI 2)]}) as a map. Read
  with the EDN reader, which cannot evaluate (#= is an error), then
  evaluated by `evaluate`."
  [^String text]
  (when-not (string? text)
    (throw (ex-info (str "the joint property must be text, not " (pr-str text))
                    {:form text})))
  (when (> (count text) max-description-length)
    (throw (ex-info (str "the joint property is " (count text)
                         " characters long, more than any joint needs")
                    {:length (count text)})))
  (let [form (try (edn/read-string {:readers {}} text)
                  (catch StackOverflowError _
                    (throw (ex-info "the joint property is nested too deeply" {})))
                  (catch Exception e
                    (throw (ex-info (str "cannot read " (pr-str text) ": " (ex-message e))
                                    {:text text} e))))
        value (try (evaluate form)
                   (catch StackOverflowError _
                     (throw (ex-info "the joint property is nested too deeply" {}))))]
    (when-not (and (map? value) (keyword? (:type value)))
      (throw (ex-info (str "a joint description is a map with a :type keyword, not "
                           (pr-str text))
                      {:text text})))
    value))

(defmulti joint-dispatch
  "Make the Bullet joint a joint description asks for, dispatching on its
  :type. Called with the description, the two rigid bodies, the joint's
  position in each body's frame, and the joint's world rotation as a
  Matrix3f. Add a joint type with defmethod."
  (fn [constraints & _] (:type constraints)))

(defn joint-types
  "The joint types joint-dispatch knows."
  []
  (sort (remove #{:default} (keys (methods joint-dispatch)))))

(defmethod joint-dispatch :default
  [constraints & _]
  (throw (ex-info (str "unknown joint type " (pr-str (:type constraints))
                       "; known types: " (str/join ", " (joint-types)))
                  {:type (:type constraints)})))

(defn body-frame
  "`rotation` (a world rotation) seen from inside `control`'s body: how
  a joint's frame is given to Bullet, which wants it in each body's own
  frame."
  ^Matrix3f [^RigidBodyControl control ^Matrix3f rotation]
  (.mult (.invert (.getPhysicsRotationMatrix control)) rotation))

(defn- number-field
  [constraints k]
  (let [v (get constraints k)]
    (if (util/finite? v)
      (float v)
      (throw (ex-info (str (name (:type constraints)) " joint needs a finite number for " k
                           ", not " (pr-str v))
                      {:key k :value v})))))

;; Bullet's point-to-point joint misbehaves in jBullet, so a point joint
;; is a six-degree-of-freedom joint whose translation is locked and whose
;; rotation is free.
(defmethod joint-dispatch :point
  [_ control-a control-b pivot-a pivot-b _]
  (doto (SixDofJoint. control-a control-b pivot-a pivot-b false)
    (.setLinearLowerLimit Vector3f/ZERO)
    (.setLinearUpperLimit Vector3f/ZERO)))

(defmethod joint-dispatch :hinge
  [constraints control-a control-b pivot-a pivot-b ^Matrix3f rotation]
  (let [axis (get constraints :axis Vector3f/UNIT_X)
        limit (:limit constraints)
        _ (when-not (and (instance? Vector3f axis) (pos? (.length ^Vector3f axis)))
            (throw (ex-info (str "hinge :axis must be a non-zero (Vector3f. x y z), not "
                                 (pr-str axis))
                            {:axis axis})))
        _ (when-not (and (vector? limit) (= 2 (count limit)) (every? number? limit)
                         (<= (first limit) (second limit)))
            (throw (ex-info (str "hinge needs :limit [low high] with low <= high, not "
                                 (pr-str limit))
                            {:limit limit})))
        axis (util/blender-to-jme (.normalize ^Vector3f axis))
        [low high] limit]
    (doto (HingeJoint. control-a control-b pivot-a pivot-b
                       (.mult (body-frame control-a rotation) axis)
                       (.mult (body-frame control-b rotation) axis))
      (.setLimit (float low) (float high)))))

(defmethod joint-dispatch :cone
  [constraints control-a control-b pivot-a pivot-b rotation]
  (let [xz (number-field constraints :limit-xz)
        xy (number-field constraints :limit-xy)
        twist (number-field constraints :twist)]
    (doto (ConeJoint. control-a control-b pivot-a pivot-b
                      (body-frame control-a rotation) (body-frame control-b rotation))
      (.setLimit xz xy twist))))

(defn pivot
  "`world-point` in the frame of `control`'s rigid body: relative to
  its position, undoing its rotation. (A body has no scale; its shape
  carries the segment's scale.)"
  ^Vector3f [^RigidBodyControl control ^Vector3f world-point]
  (.mult (.inverse (.getPhysicsRotation control))
         (.subtract world-point (.getPhysicsLocation control))))

(defn pivot-in-world
  "Where `local-point`, in the frame of the rigid body `body` (as `pivot`
  gives it), is in the world now: the inverse of `pivot`. The two ends
  of a joint, each seen from its own body, should stay together; how far
  apart they are is how far the joint has given."
  ^Vector3f [^PhysicsRigidBody body ^Vector3f local-point]
  (.add (.getPhysicsLocation body) (.mult (.getPhysicsRotation body) local-point)))

(defn connect
  "Join the physical segments `obj-a` and `obj-b` where the empty `joint`
  is, with the joint its `joint` property describes, for example
    {:type :point}
    {:type :hinge :limit [0 (/ Math/PI 2)] :axis (Vector3f. 0 1 0)}
    {:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.2}
  A hinge's :axis is in the joint empty's frame, in Blender's axes, and
  is X unless given. The two segments no longer collide with each
  other: the joint and its limits keep them apart. Creating the joint
  attaches it to both bodies; the world adds it to the physics space.
  Returns the joint. Errors name the joint."
  [^Spatial obj-a ^Spatial obj-b ^Spatial joint]
  (let [label (str "joint " (pr-str (.getName joint)))]
    (try
      (let [text (sense/meta-data joint "joint")
            _ (when (nil? text)
                (throw (ex-info "it has no joint property" {})))
            constraints (read-joint text)
            control-a (.getControl obj-a RigidBodyControl)
            control-b (.getControl obj-b RigidBodyControl)
            center (.getWorldTranslation joint)]
        (doto ^com.jme3.bullet.joints.PhysicsJoint
            (joint-dispatch constraints control-a control-b
                            (pivot control-a center) (pivot control-b center)
                            (.toRotationMatrix (.getWorldRotation joint)))
          (.setCollisionBetweenLinkedBodys false)))
      (catch clojure.lang.ExceptionInfo e
        (throw (ex-info (str label ": " (ex-message e))
                        (assoc (ex-data e) :joint (.getName joint)) e))))))

(defn joints!
  "Join the segments of `creature` with the joints its \"joints\" node
  describes. Call after `physical!`. Returns the creature."
  [^Node creature]
  (.updateGeometricState creature)
  (let [index (segment-index creature)]
    (doseq [joint (joints creature)]
      (try
        (let [[obj-a obj-b] (targets-near index joint)]
          (connect obj-a obj-b joint))
        (catch clojure.lang.ExceptionInfo e
          (throw (ex-info (str "creature " (pr-str (.getName creature)) ", " (ex-message e))
                          (assoc (ex-data e) :creature (.getName creature)) e))))))
  creature)

(defn body!
  "Give `creature` its whole physical body: solid segments joined as its
  designer said. Returns the creature."
  [^Node creature]
  (doto creature
    (physical!)
    (joints!)))
