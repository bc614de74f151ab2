;; Generated from org/body.org by lein tangle: edit the chapter, not this file.
(ns cortex.segment
  "A creature's segments made solid: what each will be (`plan-segment`,
  plain data: mass, mass properties, hull points, friction, where it
  is) and the rigid body made from that (`build-segment!`).

  Entry points: `segments`, `segment-name`, `mass`, `mesh-points`,
  `simplify-hull`, `hull-from-points`, `mesh-triangles`,
  `plan-segment`, `build-segment!`, `bullet-moments`, `segment-pose`, `mass-offset`,
  `default-options`, `record` (what the creature's Node keeps)."
  (:require [cortex.engine :as engine]
            [cortex.mass :as mass]
            [cortex.sense :as sense]
            [cortex.shapes :as shapes]
            [cortex.util :as util])
  (:import (com.jme3.bullet.collision.shapes CompoundCollisionShape HullCollisionShape)
           (com.jme3.bullet.control RigidBodyControl)
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
  the lock that keeps jBullet's hull building correct on many threads,
  with collision margin `margin` (the engine's hull margin unless
  given)."
  (^HullCollisionShape [points] (hull-from-points points (engine/hull-margin)))
  (^HullCollisionShape [points margin]
   (let [coords (float-array (mapcat (fn [^Vector3f p] [(.x p) (.y p) (.z p)]) points))]
     (util/locked-shape
      ;; no collision margin, on either engine (see org/engine.org), but
      ;; a thin hull's (the shapes chapter, "Small and thin bodies")
      #(doto (HullCollisionShape. coords)
         (.setMargin (float margin)))))))

(defn hull-points
  "The points of `geom`'s convex hull: its mesh at the geometry's world
  scale (a rigid body has no scale of its own), simplified to at most
  `max-hull-points` points, as Vector3fs. The geometry keeps its full
  visual mesh."
  [^Geometry geom]
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
    points))

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

(defn check-placement!
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

(defn mesh-triangles
  "The triangles of `geom`'s mesh at its world scale, in its own axes,
  as [[x y z] [x y z] [x y z]]s: cortex.shapes/triangles, which fits
  the shapes from the same triangles."
  [^Geometry geom]
  (shapes/triangles geom))

(defn vector-data
  "`v`, a Vector3f, as plan data: [x y z], doubles of its floats."
  [^Vector3f v]
  [(double (.x v)) (double (.y v)) (double (.z v))])

(defn quaternion-data
  "`q`, a Quaternion, as plan data: [x y z w], doubles of its floats."
  [^Quaternion q]
  [(double (.getX q)) (double (.getY q)) (double (.getZ q)) (double (.getW q))])

(defn quaternion
  "The Quaternion of plan data [x y z w]: exactly the one
  `quaternion-data` was given."
  ^Quaternion [[x y z w]]
  (Quaternion. (float x) (float y) (float z) (float w)))

(defn plain
  "`x` as plain data that clojure.edn reads back equal: a Vector3f or
  Quaternion becomes a vector of doubles, a Float or Ratio a double, a
  smaller integer a long, a Java map or list a Clojure one."
  [x]
  (cond (instance? Vector3f x) (vector-data x)
        (instance? Quaternion x) (quaternion-data x)
        (or (instance? Float x) (instance? clojure.lang.Ratio x)
            (instance? java.math.BigDecimal x)) (double x)
        (or (instance? Integer x) (instance? Short x) (instance? Byte x)
            (instance? clojure.lang.BigInt x) (instance? java.math.BigInteger x)) (long x)
        (map? x) (into {} (map (fn [[k v]] [(plain k) (plain v)])) x)
        (instance? java.util.Map x) (into {} (map (fn [[k v]] [(plain k) (plain v)])) x)
        (set? x) (into #{} (map plain) x)
        (or (sequential? x) (instance? java.util.List x)) (mapv plain x)
        :else x))

(defn- quaternion-of
  "The rotation whose matrix has the columns of `axes` (rows of numbers)."
  ^Quaternion [axes]
  (let [[[a b c] [d e f] [g h i]] axes]
    (.fromRotationMatrix (Quaternion.) (Matrix3f. a b c d e f g h i))))

(defn- largest-coordinate
  "The largest size of a coordinate of `triangles`, at least 1e-9."
  ^double [triangles]
  (let [bigger (fn [m x] (Math/max (double m) (Math/abs (double x))))]
    (reduce (fn [m t] (reduce #(reduce bigger %1 %2) m t)) 1e-9 triangles)))

(defn inertia-plan
  "How `geom` is to be massed: {:source :mesh :centre c :moments m
  :rotation q (or nil when the body is the segment's own frame)}, or
  {:source :box} when its mesh encloses no volume (`plan-segment` adds
  the :moments Bullet gives its shape). `triangles`, when
  given, are its `mesh-triangles`."
  ([geom mass] (inertia-plan geom mass (mesh-triangles geom)))
  ([^Geometry geom mass triangles]
    (if-let [{:keys [centre inertia]} (mass/mesh-properties triangles mass)]
      (let [size (largest-coordinate triangles)
            off-diagonal (max (Math/abs (double (get-in inertia [0 1])))
                              (Math/abs (double (get-in inertia [0 2])))
                              (Math/abs (double (get-in inertia [1 2]))))
            diagonal [(get-in inertia [0 0]) (get-in inertia [1 1]) (get-in inertia [2 2])]
            aligned? (<= off-diagonal (* 1e-6 (apply max 1e-12 diagonal)))
            centred? (every? #(<= (Math/abs (double %)) (* 1e-6 size)) centre)]
        (if (and aligned? centred?)
          {:source :mesh :centre [0.0 0.0 0.0] :moments (mapv double diagonal) :rotation nil}
          (let [{:keys [moments axes]} (if aligned?
                                         {:moments diagonal :axes [[1.0 0.0 0.0] [0.0 1.0 0.0] [0.0 0.0 1.0]]}
                                         (mass/principal inertia))]
            {:source :mesh :centre (mapv double centre) :moments (mapv double moments)
             :rotation (quaternion-data (quaternion-of axes))})))
      {:source :box})))

(defn- set-inertia!
  "Give `control`'s body the principal `moments` of inertia (Bullet keeps
  the inverse of each)."
  [^RigidBodyControl control mass [ix iy iz]]
  (when (pos? (double mass))
    (engine/set-inertia! control mass [ix iy iz])))

(defn place!
  "Give `geom` the world place `pos` (Vector3f) and turn `rot`
  (Quaternion) by setting its local transform under its parent, whose
  world transform must be up to date. Returns `geom`."
  [^Geometry geom ^Vector3f pos ^Quaternion rot]
  (if-let [parent (.getParent geom)]
    (do (.setLocalTranslation geom (.worldToLocal parent pos nil))
        (.setLocalRotation geom (.mult (.inverse (.getWorldRotation parent)) rot)))
    (do (.setLocalTranslation geom pos) (.setLocalRotation geom rot)))
  geom)

(defn- offset-control
  "A RigidBodyControl for `geom` whose body sits at the segment's centre
  of mass `centre` and is turned by `rotation` from the segment's own
  axes; each frame it places `geom` from its body by undoing that.
  Dereferenced, it gives {:centre [x y z] :rotation Quaternion}: the
  offset, which `segment-pose` undoes."
  ^RigidBodyControl [^Geometry geom shape mass ^Vector3f centre ^Quaternion rotation]
  (let [undo (.inverse rotation)
        offset {:centre (vector-data centre) :rotation rotation}]
    (proxy [RigidBodyControl clojure.lang.IDeref] [shape (float mass)]
      (deref [] offset)
      (update [tpf]
        (let [^RigidBodyControl this this]
          (when (and (.isEnabled this) (not (and (.isKinematic this) (.isKinematicSpatial this))))
            (let [rot (.mult (.getPhysicsRotation this) undo)]
              (place! geom (.subtract (.getPhysicsLocation this) (.mult rot centre)) rot))))))))

(defn- offset-shape
  "Shape data `shape`, in the segment's frame, seen from a body at `c`
  (Vector3f) turned by the inverse of `undo` (Quaternion): a compound
  whose children are placed p' = undo (p - c), turned undo r."
  [shape ^Vector3f c ^Quaternion undo]
  (let [children (if (= :compound (:type shape))
                   (:children shape)
                   [{:shape (dissoc shape :position :rotation)
                     :position (:position shape) :rotation (:rotation shape)}])]
    {:type :compound
     :children (vec (for [{s :shape p :position r :rotation} children]
                      {:shape s
                       :position (vector-data (.mult undo (.subtract (util/vec3 (or p [0 0 0])) c)))
                       :rotation (quaternion-data (.mult undo (quaternion (or r [0 0 0 1]))))}))}))

(defn shape-volume
  "The volume of shape data `shape`: a hull's by the engine, a
  primitive's by its formula, a compound's the sum of its children's."
  ^double [shape]
  (let [{:keys [type half-extents radius height axis points children]} shape
        pi Math/PI]
    (double
     (case type
       :hull (engine/hull-volume points)
       :box (let [[x y z] half-extents] (* 8.0 x y z))
       :sphere (* (/ 4.0 3.0) pi radius radius radius)
       :capsule (+ (* pi radius radius height) (* (/ 4.0 3.0) pi radius radius radius))
       :cylinder (let [h (nth half-extents (long (or axis 1)))
                       r (apply max (keep-indexed #(when (not= %1 (long (or axis 1))) %2) half-extents))]
                   (* pi r r 2.0 h))
       :cone (* (/ 1.0 3.0) pi radius radius height)
       :compound (reduce + (map #(shape-volume (:shape %)) children))
       0.0))))

(defn- collision-shape-of
  "The collision shape of a segment's plan `shape`, as its body gets it."
  [shape]
  (if (= :hull (:type shape))
    (hull-from-points (map util/vec3 (:points shape)) (shapes/margin shape))
    (shapes/collision-shape shape)))

(defn bullet-moments
  "The principal moments (the segment's own axes, jME's) that the running
  engine gives a body of plan `shape` and `mass` by Bullet's own rule:
  what a segment planned with {:source :box} has. Zeros for a static one."
  [mass shape]
  (if (pos? (double mass))
    (let [c (RigidBodyControl. ^com.jme3.bullet.collision.shapes.CollisionShape
                               (collision-shape-of shape) (float mass))]
      (mapv #(/ 1.0 (double %)) (engine/inverse-inertia (engine/rigid-body c))))
    [0.0 0.0 0.0]))

(defn- make-body
  "The rigid body control of segment `geom` as its plan `p` says (see
  `plan-segment`): its hull, its mass, its mass properties, and where
  it is. A body turned or moved from the segment's own frame (its
  centre of mass off the origin, or its principal axes turned) is an
  `offset-control`."
  ^RigidBodyControl [^Geometry geom {:keys [mass inertia shape position rotation]}]
  (let [{:keys [source centre moments]} inertia
        hull? (= :hull (:type shape))
        made (collision-shape-of shape)
        at (util/vec3 position)
        turn (quaternion rotation)]
    (if (and (= :mesh source) (:rotation inertia))
      (let [c (util/vec3 centre)
            rotation (quaternion (:rotation inertia))
            undo (.inverse rotation)
            shape (if hull?
                    (doto (CompoundCollisionShape.)
                      (.addChildShape made (.negate (.mult undo c)) (.toRotationMatrix undo)))
                    (shapes/collision-shape (offset-shape shape c undo)))
            control (offset-control geom shape mass c rotation)]
        (.addControl geom control)
        (.setPhysicsLocation control (.add at (.mult turn c)))
        (.setPhysicsRotation control (.mult turn rotation))
        (set-inertia! control mass moments)
        control)
      (let [control (RigidBodyControl. made (float mass))]
        (.addControl geom control)
        (.setPhysicsLocation control at)
        (.setPhysicsRotation control turn)
        (when moments (set-inertia! control mass moments))
        control))))

(defn mass-offset
  "How the rigid body of segment `geom` sits in the segment's own frame:
  {:centre [x y z] :rotation Quaternion} when it is moved to the
  centre of mass or turned to the principal axes, nil when the body is
  the segment's own frame."
  [^Geometry geom]
  (let [c (.getControl geom RigidBodyControl)]
    (when (instance? clojure.lang.IDeref c)
      @c)))

(defn segment-pose
  "Where segment `geom` is now, in its own frame as its designer made it:
  [position rotation] (a Vector3f and a Quaternion, jME's world axes),
  from its rigid body. The same as the Geometry's world transform once
  the scene graph has been brought up to date."
  [^Geometry geom]
  (let [^RigidBodyControl c (.getControl geom RigidBodyControl)
        {:keys [centre ^Quaternion rotation]} (mass-offset geom)]
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
                      origin, and the hull's bounding box);
  :shapes             :fit (each closed piece of a segment's mesh that
                      is a box, sphere, capsule or cylinder becomes one,
                      see the shapes chapter) or :hull (the seed's one
                      hull for every segment)."
  {:strict? true
   :tolerance nil
   :angular-damping 0.5
   :sleeping-thresholds [0.8 3.0]
   :mass-properties :mesh
   :shapes :fit})

(defn label [^Node creature] (str "creature " (pr-str (.getName creature))))

(defn in-creature
  "Run `f`; an ex-info it throws comes out prefixed with the creature."
  [^Node creature f]
  (try (f)
       (catch clojure.lang.ExceptionInfo e
         (throw (ex-info (str (label creature) ", " (ex-message e))
                         (assoc (ex-data e) :creature (.getName creature)) e)))))

(defn check-solid!
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

(defn- shape-property
  "The segment's `shape` property: :fit, :hull, or nil when it has
  none; anything else is an error naming the object."
  [^Geometry geom]
  (let [v (sense/meta-data geom "shape")]
    (cond (nil? v) nil
          (#{"fit" "hull"} v) (keyword v)
          :else (throw (ex-info (str "object " (pr-str (segment-name geom))
                                     ": its shape property must be \"fit\" or \"hull\", not "
                                     (pr-str v))
                                {:object (segment-name geom) :shape v})))))

(def ^:private fitted
  "The shapes of the last few hundred meshes fitted, by their triangles:
  a creature's segments are often copies of one mesh (a chain's links, a
  hand's finger bones), and fitting one costs a few milliseconds."
  (java.util.Collections/synchronizedMap
   (proxy [java.util.LinkedHashMap] [64 0.75 true]
     (removeEldestEntry [_] (> (.size ^java.util.Map this) 512)))))

(defn- fitted-shape
  "cortex.shapes/segment-shape of `triangles`, remembered when the mesh
  is small (a few thousand triangles at most: the cache holds them)."
  [triangles]
  (or (.get ^java.util.Map fitted triangles)
      (let [s (shapes/segment-shape triangles {:shapes :fit})]
        (when (<= (count triangles) 2000)
          (.put ^java.util.Map fitted triangles s))
        s)))

(defn shape-choice
  "The collision shape of segment `geom`, as data: `hull` (the seed's,
  see `hull-points`) when its `shape` property or else :shapes of
  `opts` says :hull, or when no piece of its mesh is a primitive (see
  cortex.shapes/segment-shape); else the primitives its pieces are."
  ([geom opts hull] (shape-choice geom opts hull (delay (mesh-triangles geom))))
  ([^Geometry geom opts hull triangles]
   (if (= :hull (or (shape-property geom) (:shapes opts)))
     hull
     (let [s (fitted-shape @triangles)]
       (if (= :hull (:type s)) hull s)))))

(defn plan-segment
  "What segment `geom` will be, as plain data: {:name (see
  `segment-name`) :mass :friction :restitution :angular-damping
  :sleeping-thresholds :position :rotation :scale (its world transform)
  :inertia (see `inertia-plan`) :shape}, the shape (see `shape-choice`)
  in the segment's own axes at its world scale: `given` when not nil
  (the Physics tab's, for a segment that has one), else as the
  segment's `shape` property or `opts` say. `opts` as
  `default-options`. Errors name the segment: a placement or scale that
  is not finite or leaves no volume, a bad mass, friction, restitution
  or shape property, a mesh with fewer than four distinct vertices."
  ([geom opts] (plan-segment geom opts nil))
  ([^Geometry geom opts given]
  (let [{:keys [angular-damping sleeping-thresholds mass-properties] :as opts}
        (merge default-options opts)]
    (check-placement! "segment" geom)
    (let [m (mass geom)
          ;; read once: for the mass properties and for the shapes
          triangles (delay (mesh-triangles geom))
          inertia (if (= :box mass-properties) {:source :box} (inertia-plan geom m @triangles))
          _ (check-solid! geom inertia)
          points (hull-points geom)
          hull {:type :hull :points (mapv vector-data points)}
          shape (or given (shape-choice geom opts hull triangles))]
      {:name (segment-name geom)
       :mass m
       :friction (property geom "friction" 0.5)
       :restitution (property geom "restitution" 0.0)
       :angular-damping (double angular-damping)
       :sleeping-thresholds (mapv double sleeping-thresholds)
       :position (vector-data (.getWorldTranslation geom))
       :rotation (quaternion-data (.getWorldRotation geom))
       :scale (vector-data (.getWorldScale geom))
       ;; Bullet's approximation: the moments its engine gives the shape
       :inertia (cond-> inertia
                  (= :box (:source inertia)) (assoc :moments (bullet-moments m shape)))
       :shape shape}))))

(defn build-segment!
  "Give `geom` the rigid body its plan `p` (see `plan-segment`) says.
  Returns the RigidBodyControl."
  ^RigidBodyControl [^Geometry geom p]
  (let [{:keys [friction restitution angular-damping] [lin ang] :sleeping-thresholds} p]
    (doto (make-body geom p)
      (.setFriction (float friction))
      (.setRestitution (float restitution))
      (.setSleepingThresholds (float lin) (float ang))
      (.setAngularDamping (float angular-damping)))))

(def record-key
  "The user data under which a creature's Node keeps what cortex made
  of it: {:plan (see cortex.plan) :built {...}}, nothing else."
  "cortex.creature")

(defn record
  "What a creature's Node keeps (see `record-key`), nil before it has a
  body."
  [^Node creature]
  (.getUserData creature ^String record-key))

(defn record!
  "Keep `r` as `creature`'s record. Returns the creature."
  [^Node creature r]
  (.setUserData creature ^String record-key r)
  creature)
