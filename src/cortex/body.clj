;; Generated from org/body.org by lein tangle: edit the chapter, not this file.
(ns cortex.body
  "Give a creature loaded from Blender a physical body: a rigid body for
  every segment and a Bullet joint for every joint marker, as the
  creature's designer described them in Blender.

  Entry points: `body!` (all of it), `physical!` (segments made solid),
  `joints!` (segments joined), `joints` (the joint markers),
  `joint-targets` (the two segments a joint joins), `connect`,
  `joint-dispatch` (a multimethod: add joint types), `joint-types`,
  `read-joint` (a joint description, read safely), `read-description`
  (any such property), `segments`, `mass`,
  `pivot`, `pivot-in-world`, `cone-engine-angles` (a cone's angles as
  its engine reads them)."
  (:require [clojure.edn :as edn]
            [clojure.string :as str]
            [cortex.engine :as engine]
            [cortex.mass :as mass]
            [cortex.projection :as projection]
            [cortex.sense :as sense]
            [cortex.util :as util])
  (:import (com.jme3.bounding BoundingBox)
           (com.jme3.bullet.collision.shapes CompoundCollisionShape HullCollisionShape)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints HingeJoint PhysicsJoint)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.collision CollisionResults)
           (com.jme3.math Matrix3f Quaternion Vector3f)
           (com.jme3.scene Geometry Mesh Node Spatial VertexBuffer$Type)))

(set! *warn-on-reflection* true)

(def max-hull-points
  "The most points a segment's hull keeps. Bullet advises convex hulls of
  no more than about a hundred vertices: contacts on bigger hulls cost
  more and buy nothing a body needs."
  100)

(defn- finite-vector? [^Vector3f v]
  (and (Float/isFinite (.x v)) (Float/isFinite (.y v)) (Float/isFinite (.z v))))

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

(defn hull-from-points
  "A convex hull collision shape around `points` (Vector3fs), made under
  the lock that keeps jBullet's hull building correct on many threads."
  ^HullCollisionShape [points]
  (let [coords (float-array (mapcat (fn [^Vector3f p] [(.x p) (.y p) (.z p)]) points))]
    (util/locked-shape
     ;; no collision margin, on either engine (see org/engine.org)
     #(doto (HullCollisionShape. coords)
        (.setMargin (float (engine/hull-margin)))))))

(defn- hull-shape
  "A convex hull collision shape for `geom`: its mesh at the geometry's
  world scale (a rigid body has no scale of its own), simplified to at
  most `max-hull-points` points. The geometry keeps its full visual mesh."
  ^HullCollisionShape [^Geometry geom]
  (let [all (mesh-points (.getMesh geom) (.getWorldScale geom))
        _ (when-not (every? finite-vector? all)
            (throw (ex-info (str "segment " (pr-str (.getName geom)) ": its mesh has a vertex"
                                 " that is not made of finite numbers")
                            {:object (.getName geom)})))
        points (simplify-hull all max-hull-points)]
    (when (< (count points) 4)
      (throw (ex-info (str "segment " (pr-str (.getName geom)) " has " (count points)
                           " distinct vertices; a solid needs at least 4")
                      {:object (.getName geom) :vertices (count points)})))
    (hull-from-points points)))

(defn- property
  "The custom property `key` of segment `geom` as a non-negative finite
  number, `default` when it has none; anything else is an error naming
  the object."
  [^Geometry geom ^String key default]
  (let [v (sense/meta-data geom key)
        owner (if (some? (.getUserData geom key)) geom (.getParent geom))]
    (cond
      (nil? v) (double default)
      (and (util/finite? v) (not (neg? v))) (double v)
      :else (throw (ex-info (str "object " (pr-str (.getName ^Spatial owner))
                                 ": " key " must be a non-negative number, not "
                                 (pr-str v))
                            {:object (.getName ^Spatial owner) (keyword key) v})))))

(defn mass
  "The mass Blender's designer gave `geom` (its `mass` custom property),
  1 when there is none; 0 makes the segment static. Anything but a
  finite, non-negative number is an error naming the object."
  [^Geometry geom]
  (property geom "mass" 1.0))

(defn segments
  "The Geometries of `creature`: its segments."
  [^Node creature]
  (filter #(instance? Geometry %) (util/node-seq creature)))

(defn segment-name
  "The Blender name of segment `geom`: that of the object Node the
  loader put it under (a Node carrying \"blender-type\"), or the
  Geometry's own name for segments made in code."
  ^String [^Geometry geom]
  (let [p (.getParent geom)]
    (if (and p (some? (.getUserData p "blender-type")))
      (.getName p)
      (.getName geom))))

(defn- finite-rotation? [^Quaternion q]
  (let [xs [(.getX q) (.getY q) (.getZ q) (.getW q)]]
    (and (every? #(Float/isFinite %) xs)
         (> (reduce + (map #(* % %) xs)) 1e-12))))

(defn- check-placement!
  "Throw an ex-info naming `what` when `spatial`'s world transform is not
  made of finite numbers (or its rotation has no length)."
  [what ^Spatial spatial]
  (let [bad (cond (not (finite-vector? (.getWorldTranslation spatial))) "position"
                  (not (finite-rotation? (.getWorldRotation spatial))) "rotation"
                  (not (finite-vector? (.getWorldScale spatial))) "scale")]
    (when bad
      (throw (ex-info (str what " " (pr-str (.getName spatial)) ": its " bad
                           " in the world is not made of finite numbers"
                           " (check the object and its parents in Blender)")
                      {:object (.getName spatial) :field (keyword bad)})))))

(defn- mesh-triangles
  "The triangles of `geom`'s mesh at its world scale, in its own axes,
  as [[x y z] [x y z] [x y z]]s."
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
        corners (if index
                  (map #(.get index (int %)) (range (.size index)))
                  (range n-vertices))]
    (if (and positions (= com.jme3.scene.Mesh$Mode/Triangles (.getMode mesh)))
      (map #(mapv vertex %) (partition 3 corners))
      [])))

(defn- quaternion-of
  "The rotation whose matrix has the columns of `axes` (rows of numbers)."
  ^Quaternion [axes]
  (let [[[a b c] [d e f] [g h i]] axes]
    (.fromRotationMatrix (Quaternion.) (Matrix3f. a b c d e f g h i))))

(defn- inertia-plan
  "How `geom` is to be massed: {:source :mesh :centre c :moments m
  :rotation q (or nil when the body is the segment's own frame)}, or
  {:source :box} when its mesh encloses no volume."
  [^Geometry geom mass]
  (let [triangles (mesh-triangles geom)]
    (if-let [{:keys [centre inertia]} (mass/mesh-properties triangles mass)]
      (let [size (apply max 1e-9 (map #(Math/abs (double %)) (flatten triangles)))
            off-diagonal (max (Math/abs (double (get-in inertia [0 1])))
                              (Math/abs (double (get-in inertia [0 2])))
                              (Math/abs (double (get-in inertia [1 2]))))
            diagonal [(get-in inertia [0 0]) (get-in inertia [1 1]) (get-in inertia [2 2])]
            aligned? (<= off-diagonal (* 1e-6 (apply max 1e-12 diagonal)))
            centred? (every? #(<= (Math/abs (double %)) (* 1e-6 size)) centre)]
        (if (and aligned? centred?)
          {:source :mesh :centre [0.0 0.0 0.0] :moments diagonal :rotation nil}
          (let [{:keys [moments axes]} (if aligned?
                                         {:moments diagonal :axes [[1.0 0.0 0.0] [0.0 1.0 0.0] [0.0 0.0 1.0]]}
                                         (mass/principal inertia))]
            {:source :mesh :centre centre :moments moments :rotation (quaternion-of axes)})))
      {:source :box})))

(defn- set-inertia!
  "Give `control`'s body the principal `moments` of inertia (Bullet keeps
  the inverse of each)."
  [^RigidBodyControl control mass [ix iy iz]]
  (when (pos? (double mass))
    (engine/set-inertia! control mass [ix iy iz])))

(defn- offset-control
  "A RigidBodyControl for `geom` whose body sits at the segment's centre
  of mass `centre` and is turned by `rotation` from the segment's own
  axes; each frame it places `geom` from its body by undoing that."
  ^RigidBodyControl [^Geometry geom shape mass ^Vector3f centre ^Quaternion rotation]
  (let [undo (.inverse rotation)]
    (proxy [RigidBodyControl] [shape (float mass)]
      (update [tpf]
        (let [^RigidBodyControl this this]
          (when (and (.isEnabled this) (not (and (.isKinematic this) (.isKinematicSpatial this))))
            (let [rot (.mult (.getPhysicsRotation this) undo)
                  pos (.subtract (.getPhysicsLocation this) (.mult rot centre))
                  parent (.getParent geom)]
              (if parent
                (do (.setLocalTranslation geom (.worldToLocal parent pos nil))
                    (.setLocalRotation geom (.mult (.inverse (.getWorldRotation parent)) rot)))
                (do (.setLocalTranslation geom pos) (.setLocalRotation geom rot))))))))))

(defn- make-body
  "The rigid body control of segment `geom`: its hull, its mass, and the
  mass properties `plan` (see `inertia-plan`)."
  ^RigidBodyControl [^Geometry geom mass {:keys [source centre moments ^Quaternion rotation]}]
  (let [hull (hull-shape geom)]
    (if (and (= :mesh source) rotation)
      (let [c (util/vec3 centre)
            undo (.inverse rotation)
            shape (doto (CompoundCollisionShape.)
                    (.addChildShape hull (.negate (.mult undo c)) (.toRotationMatrix undo)))
            control (offset-control geom shape mass c rotation)
            rot (.getWorldRotation geom)]
        (.addControl geom control)
        (.setPhysicsLocation control (.add (.getWorldTranslation geom) (.mult rot c)))
        (.setPhysicsRotation control (.mult rot rotation))
        (set-inertia! control mass moments)
        control)
      (let [control (RigidBodyControl. hull (float mass))]
        (.addControl geom control)
        (when (= :mesh source) (set-inertia! control mass moments))
        control))))

(defn segment-pose
  "Where segment `geom` is now, in its own frame as its designer made it:
  [position rotation] (a Vector3f and a Quaternion, jME's world axes),
  from its rigid body. The same as the Geometry's world transform once
  the scene graph has been brought up to date."
  [^Geometry geom]
  (let [^RigidBodyControl c (.getControl geom RigidBodyControl)
        {:keys [centre ^Quaternion rotation]} (.getUserData geom "cortex.body/mass")]
    (if rotation
      (let [rot (.mult (.getPhysicsRotation c) (.inverse rotation))]
        [(.subtract (.getPhysicsLocation c) (.mult rot (util/vec3 centre))) rot])
      [(.getPhysicsLocation c) (.getPhysicsRotation c)])))

(def default-options
  "What `body!` uses when not told otherwise:
  :strict?            refuse joints it has doubts about (true), or build
                      them and record a warning (false);
  :tolerance          the ambiguity window: a segment within this of a
                      joint's second nearest (an eye's nearest) makes
                      the pair doubtful; in world units, nil for a
                      tenth of the creature's median segment size;
  :angular-damping    each segment's, see above;
  :sleeping-thresholds [linear m/s, angular rad/s] below which a body
                      at rest for 2 s is put to sleep;
  :mass-properties    :mesh (centre of mass and inertia from the
                      segment's triangles) or :box (the seed's: the
                      origin, and the hull's bounding box)."
  {:strict? true
   :tolerance nil
   :angular-damping 0.5
   :sleeping-thresholds [0.8 3.0]
   :mass-properties :mesh})

(defn- label [^Node creature] (str "creature " (pr-str (.getName creature))))

(defn- in-creature
  "Run `f`; an ex-info it throws comes out prefixed with the creature."
  [^Node creature f]
  (try (f)
       (catch clojure.lang.ExceptionInfo e
         (throw (ex-info (str (label creature) ", " (ex-message e))
                         (assoc (ex-data e) :creature (.getName creature)) e)))))

(defn- check-solid!
  "Throw an ex-info naming segment `geom` when its world scale flattens
  it (zero along an axis, or so small that a float holds no volume: jME
  could not invert its transform), or when its mass properties `plan`
  are beyond what Bullet's floats hold (a vertex thrown far off, as in
  a damaged file)."
  [^Geometry geom {:keys [centre moments]}]
  (let [^Vector3f s (.getWorldScale geom)
        too-big? #(> (Math/abs (double %)) Float/MAX_VALUE)
        fail #(throw (ex-info (str "segment " (pr-str (segment-name geom)) ": " %
                                   " (check the object, its parents and its mesh in Blender)")
                              {:object (segment-name geom)}))]
    (cond (zero? (float (* (.x s) (.y s) (.z s))))
          (fail (str "its scale in the world, " s ", leaves it no volume"))
          (some too-big? (concat centre moments))
          (fail "its mesh reaches too far from its origin for its mass properties to fit in a float"))))

(defn physical!
  "Make every segment of `creature` solid: a rigid body with a convex
  hull shape and the segment's mass, the damping and sleeping thresholds
  of `opts` (see `default-options`). Segments that already have a rigid
  body keep it, so calling this twice is harmless. Returns the creature."
  ([creature] (physical! creature {}))
  ([^Node creature opts]
   (let [{:keys [angular-damping sleeping-thresholds mass-properties]} (merge default-options opts)
         [lin ang] sleeping-thresholds]
     (.updateGeometricState creature)
     (doseq [^Geometry geom (segments creature)
             :when (nil? (.getControl geom RigidBodyControl))]
       (in-creature
        creature
        (fn []
          (check-placement! "segment" geom)
          (let [m (mass geom)
                plan (if (= :box mass-properties) {:source :box} (inertia-plan geom m))]
            (check-solid! geom plan)
            (.setUserData geom "cortex.body/mass" plan)
            (doto (make-body geom m plan)
              (.setFriction (float (property geom "friction" 0.5)))
              (.setRestitution (float (property geom "restitution" 0.0)))
              (.setSleepingThresholds (float lin) (float ang))
              (.setAngularDamping (float angular-damping))))))))
   creature))

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
  "How many cells the box from `lo` to `hi` covers, counted in doubles:
  a box far out or huge (a damaged file's) covers more than a long
  holds."
  ^double [cell lo hi]
  (reduce * 1.0 (map #(inc (- (Math/floor (/ (double %2) cell))
                              (Math/floor (/ (double %1) cell))))
                     lo hi)))

(defn- gridded?
  "Whether the box from `lo` to `hi` goes in the grid: it covers at most
  `most` cells, numbered by whole numbers that a long holds (a box
  a hundred thousand billion cells out, or with no finite corners, is
  kept aside and checked every time instead)."
  [cell lo hi most]
  (and (<= (cell-count cell lo hi) (double most))
       (every? #(< (Math/abs (Math/floor (/ (double %) cell))) 1e14) (concat lo hi))))

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
        cell (max 1e-9 (if (seq sizes) (nth sizes (quot (count sizes) 2)) 1.0))
        {big false small true} (group-by #(let [{:keys [lo hi]} (items %)]
                                            (gridded? cell lo hi max-cells-per-segment))
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
  (let [candidates (if-not (gridded? cell lo hi (count items))
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
                                          " segment(s) near it, a " what " needs "
                                          (if (= 2 need) "two" need))
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

(defn- ordered-pair
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

(defn joint-doubts
  "The doubts about joint empty `joint-name` given its `measured` nearest
  segments (see `nearest-segments`) and the creature's `tolerance` (the
  ambiguity window): maps of :kind (:ambiguous-joint or :far-joint),
  :joint, :segments, :distances, :tolerance, for a far joint :allowed
  (half of each segment's thinnest side), and a :message saying what to
  change."
  [joint-name measured tolerance]
  (let [[a b & more] measured
        allowed (into {} (for [{:keys [name geom]} [a b]]
                           [name (* 0.5 (double (first (segment-sides geom))))]))
        outside (filter #(> (double (:distance %)) (double (allowed (:name %)))) [a b])
        base {:joint joint-name :tolerance tolerance
              :distances (into {} (map (juxt :name :distance)) measured)}]
    (cond-> []
      (seq more)
      (conj (assoc base :kind :ambiguous-joint
                   :segments (mapv :name measured)
                   :message (str "joint " (pr-str joint-name) " is about equally near "
                                 (count measured) " segments (" (distances-text measured)
                                 "; the tolerance is " (fmt tolerance) "), so which two it joins"
                                 " cannot be told; move the empty into the gap between the two"
                                 " it should join, with every other segment farther away")))
      (seq outside)
      (conj (assoc base :kind :far-joint
                   :segments [(:name a) (:name b)]
                   :allowed allowed
                   :message (str "joint " (pr-str joint-name) " is " (fmt (:distance a))
                                 " from " (:name a) " and " (fmt (:distance b)) " from "
                                 (:name b) ", more than half the thinnest side of "
                                 (str/join " and of " (for [{:keys [name]} outside]
                                                        (str name " (" (fmt (allowed name)) ")")))
                                 ": it lies outside the two it joins;"
                                 " move the empty into the gap where the two meet"))))))

(defn duplicate-doubts
  "A doubt for each pair of segments that more than one joint joins,
  given `pairs`: [joint-name [segment-name segment-name]] in order."
  [pairs]
  (for [[pair names] (group-by (comp set second) pairs)
        :when (> (count names) 1)
        :let [joints (mapv first names)]]
    {:kind :duplicate-joint :joints joints :segments (vec (sort pair))
     :message (str "joints " (str/join " and " (map pr-str joints)) " both join "
                   (str/join " and " (sort pair))
                   "; delete one, or move it into the gap it belongs to")}))

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

(defn read-description
  "The custom property `property` (\"joint\", \"eye\", ...) whose text
  is `text`, a Clojure map such as {:type :hinge :limit [0 (/ Math/PI
  2)]}, as a value. Read with the EDN reader, which cannot evaluate (#=
  is an error), then evaluated by `evaluate`."
  [property ^String text]
  (when-not (string? text)
    (throw (ex-info (str "the " property " property must be text, not " (pr-str text))
                    {:form text})))
  (when (> (count text) max-description-length)
    (throw (ex-info (str "the " property " property is " (count text)
                         " characters long, more than any " property " needs")
                    {:length (count text)})))
  (let [form (try (edn/read-string {:readers {}} text)
                  (catch StackOverflowError _
                    (throw (ex-info (str "the " property " property is nested too deeply") {})))
                  (catch Exception e
                    (throw (ex-info (str "cannot read " (pr-str text) ": " (ex-message e))
                                    {:text text} e))))]
    (try (evaluate form)
         (catch StackOverflowError _
           (throw (ex-info (str "the " property " property is nested too deeply") {}))))))

(defn read-joint
  "The joint description `text` (the `joint` custom property: a Clojure
  map such as {:type :hinge :limit [0 (/ Math/PI 2)]}) as a map, read
  safely by `read-description`."
  [^String text]
  (let [value (read-description "joint" text)]
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
  (.mult (.invert (engine/rotation-matrix control)) rotation))

(defn- frame-quaternion
  "The rotation matrix `m` as a quaternion [x y z w]."
  [^Matrix3f m]
  (let [q (doto (Quaternion.) (.fromRotationMatrix m))]
    [(double (.getX q)) (double (.getY q)) (double (.getZ q)) (double (.getW q))]))

(defn- hold-limits!
  "Hold the limits of `joint` between `control-a` and `control-b`,
  whose empty is turned by `rotation`, beyond what the engine's own
  joint does: the engine's rows that hold them as proprioception reads
  them (`rows`, see cortex.engine/limit-rows!) and the projection that
  puts the joint back when the solver has let it too far past (`held`,
  see cortex.projection/hold!). Both are given the joint's frame in
  each body. Returns `joint`."
  [joint control-a control-b ^Matrix3f rotation rows held]
  (let [frames {:frame-a (frame-quaternion (body-frame control-a rotation))
                :frame-b (frame-quaternion (body-frame control-b rotation))}]
    (engine/limit-rows! joint (merge rows frames))
    (projection/hold! joint (merge held frames))))

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
  (engine/six-dof-joint control-a control-b pivot-a pivot-b nil nil nil))

(def common-joint-keys
  "The keys every joint description may have."
  #{:type :strength :kp :kd})

(defmulti joint-keys
  "The keys, besides `common-joint-keys`, that a joint description of
  this :type may have; nil when any key is allowed."
  identity)

(defmethod joint-keys :default [_] nil)
(defmethod joint-keys :point [_] #{})
(defmethod joint-keys :hinge [_] #{:limit :axis})
(defmethod joint-keys :cone [_] #{:limit-xz :limit-xy :twist})
(defmethod joint-keys :spring [_] #{:limit-xz :limit-xy :twist :stiffness :damping})

(defn check-keys
  "`description`, or an error naming its unknown keys and the keys its
  type takes."
  [description]
  (when-let [known (joint-keys (:type description))]
    (let [allowed (into common-joint-keys known)
          unknown (remove allowed (keys description))]
      (when (seq unknown)
        (throw (ex-info (str (name (:type description)) " joint: unknown "
                             (if (next unknown) "keys " "key ")
                             (str/join ", " (sort unknown))
                             "; a " (name (:type description)) " joint takes "
                             (str/join ", " (sort allowed)))
                        {:unknown (vec unknown) :allowed allowed})))))
  description)

(defn- angle-error
  [what value allowed]
  (ex-info (str what " " (pr-str value) " is outside " allowed
                ": angles are in radians (90 degrees is (/ Math/PI 2))")
           {:value value}))

(defn jbullet-hinge-limits
  "The [low high] to give the engine's HingeJoint so that the designer's
  limits [lo hi] (radians, right-hand rule about the designer's axis,
  second segment relative to the first) hold exactly: see
  cortex.engine/hinge-limits. (The name is the one it had when jBullet
  was the only engine.)"
  [limits]
  (engine/hinge-limits limits))

(defn- axis-vector
  "A hinge :axis as a non-zero Vector3f: given as one, or as [x y z]."
  ^Vector3f [axis]
  (let [v (cond (instance? Vector3f axis) axis
                (and (vector? axis) (= 3 (count axis)) (every? util/finite? axis))
                (util/vec3 axis))]
    (if (and v (Float/isFinite (.length ^Vector3f v)) (pos? (.length ^Vector3f v)))
      v
      (throw (ex-info (str "hinge :axis must be a non-zero [x y z] or (Vector3f. x y z), not "
                           (pr-str axis))
                      {:axis axis})))))

(defmethod joint-dispatch :hinge
  [constraints control-a control-b pivot-a pivot-b ^Matrix3f rotation]
  (let [axis (axis-vector (get constraints :axis Vector3f/UNIT_X))
        limit (:limit constraints)
        _ (when-not (and (vector? limit) (= 2 (count limit)) (every? util/finite? limit)
                         (<= (first limit) (second limit)))
            (throw (ex-info (str "hinge needs :limit [low high] with low <= high, not "
                                 (pr-str limit))
                            {:limit limit})))
        _ (when-not (every? #(<= (- Math/PI) (double %) Math/PI) limit)
            (throw (angle-error "hinge :limit" limit "[-pi, pi]")))
        axis (util/blender-to-jme (.normalize axis))
        [low high] (jbullet-hinge-limits limit)
        axis-limit {:axis [(.x ^Vector3f axis) (.y ^Vector3f axis) (.z ^Vector3f axis)]
                    :limit (mapv double limit)}]
    (-> (HingeJoint. ^PhysicsRigidBody control-a ^PhysicsRigidBody control-b
                     ^Vector3f pivot-a ^Vector3f pivot-b
                     (.mult (body-frame control-a rotation) axis)
                     (.mult (body-frame control-b rotation) axis))
        (engine/zero-hinge!)
        (engine/limit-hinge! low high)
        ;; the rows and projection read the hinge the same way
        (hold-limits! control-a control-b rotation axis-limit (assoc axis-limit :type :hinge)))))

(defn- cone-limits
  "[frame-turn [x-limit y-limit z-limit]] for a cone of swing limits
  `xz` (about Blender's Y, jME's Z) and `xy` (about Blender's Z, jME's Y)
  and `twist` (about X): the turn of the joint's frame that puts the
  narrower swing on the engine's middle Euler angle (Y), the wider on Z
  and the twist on X (identity when the swing about jME's Y is already
  the narrower), or, when even the narrower swing is wider than the
  engine's `six-dof-safe-middle` and the twist narrower than it, the
  twist in the middle, the swing about jME's Z on X and the other on Z;
  and the three limits in the turned frame, none exactly 0, Y's at most
  1.5."
  [xz xy twist]
  (let [open #(max 1e-4 (double %))
        [t y z] [(double twist) (double xy) (double xz)]
        quarter-about-x (.toRotationMatrix (doto (Quaternion.) (.fromAngleAxis (float (/ Math/PI 2))
                                                                               Vector3f/UNIT_X)))
        [turn [lx ly lz]]
        (cond
          ;; the frame's X, Y, Z are the joint's Z, X, Y
          (and (> (min y z) (double engine/six-dof-safe-middle)) (< t (min y z)))
          [(Matrix3f. 0 1 0, 0 0 1, 1 0 0) [z t y]]
          (<= y z) [(Matrix3f.) [t y z]]
          ;; turned a quarter about X, the frame's Y is jME's Z and its Z
          ;; is jME's -Y
          :else [quarter-about-x [t z y]])]
    [turn [(open lx) (min 1.5 (open ly)) (open lz)]]))

(defn cone-engine-angles
  "[angles limits] of a cone of description `d` (see `joint-records`)
  whose body B is turned by the Quaternion `rel` relative to body A,
  both joint frames read as proprioception reads them (identity at
  rest): the three angles its engine limits, as the engine reads them,
  and the limits `joint-dispatch` gave them. The angles are the Euler
  angles in the frame the engine is given (turned by `cone-limits`);
  Bullet reads a 6-DOF joint's relative frame column by column
  (jBullet's getMatrixElem(i) is element (i mod 3, i div 3)), so they
  are those of the inverse rotation, m^-1 = Rx Ry Rz (see
  cortex.projection/euler-angles)."
  [d ^Quaternion rel]
  (let [[^Matrix3f turn limits] (cone-limits (:limit-xz d) (:limit-xy d) (:twist d))]
    [(projection/euler-angles rel (doto (Quaternion.) (.fromRotationMatrix turn))) limits]))

(defmethod joint-dispatch :cone
  [constraints control-a control-b pivot-a pivot-b ^Matrix3f rotation]
  (let [xz (number-field constraints :limit-xz)
        xy (number-field constraints :limit-xy)
        twist (number-field constraints :twist)]
    (doseq [k [:limit-xz :limit-xy :twist]
            :let [v (double (get constraints k))]
            :when (not (<= 0.0 v Math/PI))]
      (throw (angle-error (str "cone " k) (get constraints k) "[0, pi]")))
    (let [[^Matrix3f turn [t y z]] (cone-limits xz xy twist)
          frame (.mult rotation turn)]
      (-> (engine/six-dof-joint control-a control-b pivot-a pivot-b
                                (body-frame control-a frame) (body-frame control-b frame) [t y z])
          (hold-limits! control-a control-b rotation
                        {:twist (double twist) :limit-xz (double xz) :limit-xy (double xy)}
                        {:type :cone :turn (doto (Quaternion.) (.fromRotationMatrix turn))
                         :limits [t y z]})))))

(defmethod joint-dispatch :spring
  [constraints control-a control-b pivot-a pivot-b ^Matrix3f rotation]
  (let [field (fn [k default]
                (let [v (get constraints k default)]
                  (if (and (util/finite? v) (<= 0.0 (double v)))
                    (double v)
                    (throw (ex-info (str "spring joint needs a number >= 0 for " k ", not " (pr-str v))
                                    {:key k :value v})))))
        stiffness (field :stiffness nil)
        damping (field :damping 0.0)
        free (fn [k] (let [v (field k Math/PI)]
                       (if (<= v Math/PI) v (throw (angle-error (str "spring " k) v "[0, pi]")))))
        [^Matrix3f turn limits] (cone-limits (free :limit-xz) (free :limit-xy) (free :twist))
        frame (.mult rotation turn)]
    (engine/spring-joint control-a control-b pivot-a pivot-b
                         (body-frame control-a frame) (body-frame control-b frame)
                         limits stiffness damping)))

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

(defn joint-gap
  "How far apart the two ends of `joint` (a jBullet PhysicsJoint) are in
  the world now: each end is the joint's pivot carried by its own body.
  A joint that holds keeps it near zero."
  ^double [^PhysicsJoint joint]
  (let [[^Vector3f pa ^Vector3f pb] (engine/pivots joint)]
    (.distance (pivot-in-world (.getBodyA joint) pa)
               (pivot-in-world (.getBodyB joint) pb))))

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
            constraints (check-keys (read-joint text))
            control-a (.getControl obj-a RigidBodyControl)
            control-b (.getControl obj-b RigidBodyControl)
            center (.getWorldTranslation joint)]
        (let [j (joint-dispatch constraints control-a control-b
                                (pivot control-a center) (pivot control-b center)
                                (.toRotationMatrix (.getWorldRotation joint)))]
          (engine/collide-linked! j false)
          ;; every joint counts for projection's tree, limited or not
          (when-not (projection/held? j) (projection/hold! j nil))
          j))
      (catch clojure.lang.ExceptionInfo e
        (throw (ex-info (str label ": " (ex-message e))
                        (assoc (ex-data e) :joint (.getName joint)) e))))))

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

(defn- shrunk-bound
  ^BoundingBox [{:keys [lo hi]}]
  (let [c (map #(/ (+ (double %1) (double %2)) 2) lo hi)
        e (map #(* 0.499 (- (double %2) (double %1))) lo hi)
        [cx cy cz] c [ex ey ez] e]
    (BoundingBox. (Vector3f. cx cy cz) (float ex) (float ey) (float ez))))

(defn- meets? [^Geometry g ^BoundingBox b]
  (pos? (.collideWith g b (CollisionResults.))))

(defn overlap-warnings
  "Warnings for the segments of `index` that overlap at rest though no
  joint joins them; `joined` is a set of #{geom geom} pairs."
  [{:keys [items] :as index} joined]
  (distinct
   (for [a items
         b (nearby index (:lo a) (:hi a))
         :let [ga (:geom a) gb (:geom b)
               na (segment-name ga) nb (segment-name gb)]
         :when (neg? (compare na nb))
         :when (not (contains? joined #{ga gb}))
         :when (and (meets? ga (shrunk-bound b)) (meets? gb (shrunk-bound a)))]
     {:kind :overlap :segments [na nb] :warning? true
      :message (str "segments " na " and " nb " overlap where they start, and no joint"
                    " joins them: Bullet will push them apart on the first step;"
                    " move them apart or join them")})))

(defn limit-warnings
  "Warnings for the hinges of `made` (joint records) built outside their
  limits by more than projection lets be (cortex.projection/slack): a
  hinge reads 0 as built, so one whose limits leave out 0 is turned
  into them at the first step, whatever the designer drew."
  [made]
  (let [trigger (double (first (projection/slack :hinge)))]
    (for [{:keys [name description]} made
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

(def ^:private record-key "cortex.body")

(defn- plan-joint
  "What joint empty `marker` will join, measured."
  [index tol ^Spatial marker]
  (check-placement! "joint" marker)
  (let [measured (nearest-segments index marker tol)
        pair (vec (ordered-pair marker (map :geom (take 2 measured))))]
    {:marker marker :name (.getName marker) :measured measured :geoms pair
     :segments (mapv segment-name pair)}))

(defn- vec3-of [^Vector3f v] [(.x v) (.y v) (.z v)])

(defn- joint-record
  "What is kept of a made joint."
  [{:keys [^Spatial marker name measured geoms segments]} physics-joint]
  (let [description (read-joint (sense/meta-data marker "joint"))
        q (.getWorldRotation marker)]
    {:name name :type (:type description) :description description
     :physics-joint physics-joint :geoms geoms :segments segments
     :pivot (vec3-of (.getWorldTranslation marker))
     :rotation [(.getX q) (.getY q) (.getZ q) (.getW q)]
     :body-rotations (mapv (fn [^Geometry g]
                             (let [r (.getPhysicsRotation
                                      ^RigidBodyControl (.getControl g RigidBodyControl))]
                               [(.getX r) (.getY r) (.getZ r) (.getW r)]))
                           geoms)
     :distances (into {} (for [{n :name d :distance} (take 2 measured)] [n d]))}))

(defn- log-warnings!
  [^Node creature warnings]
  (let [logger (java.util.logging.Logger/getLogger "cortex.body")]
    (doseq [{:keys [message]} warnings]
      (.warning logger (str (label creature) ": " message)))))

(defn joints!
  "Join the segments of `creature` with the joints its \"joints\" node
  describes. Call after `physical!`. `opts` (see `default-options`):
  :strict? (default true) makes any doubt about a joint an error listing
  every doubt; false builds the joints anyway and keeps the doubts as
  warnings; :tolerance overrides the creature's ambiguity window.
  Returns the creature."
  ([creature] (joints! creature {}))
  ([^Node creature opts]
   (let [{:keys [strict?] :as opts} (merge default-options opts)]
     (.updateGeometricState creature)
     (let [index (segment-index creature)
           tol (double (or (:tolerance opts) (tolerance index)))
           plans (mapv #(in-creature creature (fn [] (plan-joint index tol %)))
                       (joints creature))
           naming (naming-doubts creature)
           doubts (vec (concat (remove :warning? naming)
                               (mapcat #(joint-doubts (:name %) (:measured %) tol) plans)
                               (duplicate-doubts (map (juxt :name :segments) plans))))]
       (when (and strict? (seq doubts))
         (throw (ex-info (str (label creature) ": " (count doubts)
                              (if (= 1 (count doubts)) " doubt" " doubts")
                              " about its joints:\n"
                              (str/join "\n" (map #(str "- " (:message %)) doubts))
                              "\n(to build it anyway, (body! creature {:strict? false}))")
                         {:creature (.getName creature) :doubts doubts})))
       (let [made (mapv (fn [{:keys [marker geoms] :as p}]
                          (in-creature creature
                                       #(joint-record p (connect (first geoms) (second geoms)
                                                                 marker))))
                        plans)
             joined (set (map #(set (:geoms %)) made))
             warnings (vec (concat (map #(assoc % :relaxed? true) doubts)
                                   (filter :warning? naming)
                                   (overlap-warnings index joined)
                                   (limit-warnings made)))]
         (log-warnings! creature warnings)
         (.setUserData creature record-key
                       {:joints made :warnings warnings :tolerance tol}))))
   creature))

(defn body!
  "Give `creature` its whole physical body: solid segments joined as its
  designer said, and its eyes, when it has an \"eyes\" node, fixed to
  their segments (see cortex.vision/eyes!). `opts` as for `physical!`
  and `joints!` (see `default-options`). Returns the creature."
  ([creature] (body! creature {}))
  ([^Node creature opts]
   (doto creature
     (physical! opts)
     (joints! opts))
   ;; eyes (see vision.org) are fixed to their segments as built; the
   ;; vision chapter is loaded only for a creature that has an eyes node
   (when (instance? Node (.getChild creature "eyes"))
     ((requiring-resolve 'cortex.vision/eyes!) creature opts))
   creature))

(defn- build-record
  [^Node creature]
  (or (.getUserData creature record-key)
      (throw (ex-info (str (label creature) " has no body yet: call body! first")
                      {:creature (.getName creature)}))))

(defn- segment-report
  [^Geometry g]
  (let [^RigidBodyControl c (.getControl g RigidBodyControl)
        points (engine/hull-points (.getCollisionShape c))
        {:keys [source centre moments]} (.getUserData g "cortex.body/mass")]
    (cond-> {:name (segment-name g) :mass (double (.getMass c))
             :hull-points (count points)
             :hull-volume (if points (engine/hull-volume points) 0.0)
             :mass-properties source}
      (= :mesh source) (assoc :centre-of-mass (vec3-of (util/jme-to-blender (util/vec3 centre)))
                              :principal-moments (vec moments)))))

(defn- joint-report
  [{:keys [name type description physics-joint segments pivot distances]}]
  (let [[x y z] pivot]
    {:name name :type type :class (.getSimpleName (class physics-joint))
     :segments segments
     :pivot (vec3-of (util/jme-to-blender (Vector3f. x y z)))
     :distances distances
     :limits (select-keys description [:limit :limit-xz :limit-xy :twist])}))

(defn report
  "What `body!` built of `creature`, as data: {:creature name, :segments
  [{:name :mass :hull-points :hull-volume}], :joints [{:name :type :class
  :segments [first second] :pivot [x y z] (Blender's world axes)
  :distances {segment distance} :limits {...}}], :warnings [{:kind
  :message ...}], :tolerance (the ambiguity window the doubts used)},
  and for a creature with eyes :eyes
  [{:name :kind :segment :distance :resolution :fov ...}] (see
  cortex.vision/eyes!)."
  [^Node creature]
  (let [{:keys [joints warnings tolerance]} (build-record creature)
        eyes (:report (.getUserData creature "cortex.vision"))]
    (cond-> {:creature (.getName creature)
             :segments (vec (for [g (segments creature)
                                  :when (.getControl ^Geometry g RigidBodyControl)]
                              (segment-report g)))
             :joints (mapv joint-report joints)
             :warnings warnings
             :tolerance tolerance}
      eyes (assoc :eyes eyes))))

(defn segment
  "The segment (a Geometry with a rigid body) of `creature` that Blender
  calls `object-name`; the first, for an object with several materials.
  An error names the segments there are when there is none."
  ^Geometry [^Node creature ^String object-name]
  (or (first (filter #(= object-name (segment-name %)) (segments creature)))
      (throw (ex-info (str (label creature) " has no segment " (pr-str object-name)
                           "; its segments are "
                           (str/join ", " (distinct (map segment-name (segments creature)))))
                      {:creature (.getName creature) :segment object-name}))))

(defn joint-records
  "The joints `body!` made of `creature`, in order, as maps of :name,
  :type, :description, :physics-joint (the jBullet joint), :geoms (the
  two segments, in order), :segments (their names), :pivot and
  :rotation (the joint empty's world position and rotation when it was
  made, jME axes), :body-rotations (the two rigid bodies' rotations
  then), :distances."
  [^Node creature]
  (:joints (build-record creature)))

(defn joint
  "The jBullet joint `body!` made for the joint empty `joint-name`."
  ^PhysicsJoint [^Node creature ^String joint-name]
  (or (:physics-joint (first (filter #(= joint-name (:name %)) (joint-records creature))))
      (throw (ex-info (str (label creature) " has no joint " (pr-str joint-name)
                           "; its joints are "
                           (str/join ", " (map :name (joint-records creature))))
                      {:creature (.getName creature) :joint joint-name}))))
