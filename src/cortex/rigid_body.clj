;; Generated from org/rigid-bodies.org by lein tangle: edit the chapter, not this file.
(ns cortex.rigid-body
  "Blender's rigid bodies (the Physics tab): each object's settings, read
  from the scene graph, as plan data (`plan-rigid-body`: shape, mass,
  friction, damping, collisions, sleep), and the Bullet rigid body made
  from that (`build-rigid-body!`).

  Entry points: `rigid-body`, `rigid-body-constraint`,
  `rigid-body-objects`, `constraint-objects`, `body-spatial`,
  `collision-shape`, `shape-of`, `plan-rigid-body`,
  `build-rigid-body!`, `rigid-body!`, `rigid-bodies!`."
  (:require [clojure.string :as str]
            [cortex.engine :as engine]
            [cortex.segment :as segment]
            [cortex.sense :as sense]
            [cortex.util :as util])
  (:import (com.jme3.bullet.collision.shapes BoxCollisionShape CapsuleCollisionShape
                                             CollisionShape ConeCollisionShape
                                             CylinderCollisionShape SphereCollisionShape)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Mesh Node Spatial)
           (jme3tools.optimize GeometryBatchFactory)))

(set! *warn-on-reflection* true)

(defn rigid-body
  "The Blender rigid body settings of object `spatial` (its Node, or a
  Geometry of it) as the reader made them (see
  cortex.blender.rigid-body/rigid-body): a map with keyword keys
  (:type \"ACTIVE\", :shape \"BOX\", :mass, :friction, :lin-damping,
  :kinematic ...), or nil when it has none."
  [^Spatial spatial]
  (sense/meta-data spatial sense/rigid-body-key))

(defn rigid-body-constraint
  "The Blender rigid body constraint of object `spatial` as the reader
  made it: a map with keyword keys (:type \"HINGE\", :ob1, :ob2,
  :use-limit-ang-z, :limit-ang-z-lower ...), or nil when it has none."
  [^Spatial spatial]
  (sense/meta-data spatial sense/constraint-key))

(defn- objects-with
  "The object Nodes of `creature` that carry user data `key`."
  [^Node creature key]
  (filter #(and (instance? Node %) (some? (.getUserData ^Spatial % key)))
          (util/node-seq creature)))

(defn rigid-body-objects
  "The object Nodes of `creature` that have a Blender rigid body."
  [creature]
  (objects-with creature sense/rigid-body-key))

(defn constraint-objects
  "The object Nodes of `creature` that have a Blender rigid body
  constraint, in name order."
  [creature]
  (sort-by #(.getName ^Spatial %) (objects-with creature sense/constraint-key)))

(defn fail
  "Throw an ex-info about object `name`."
  [what name msg data]
  (throw (ex-info (str what " " (pr-str name) ": " msg) (assoc data :object name))))

(defn finite
  "The number under `k` in `settings` as a double; an error naming the
  object when it is missing or not finite."
  [what name settings k]
  (let [v (get settings k)]
    (if (util/finite? v)
      (double v)
      (fail what name (str (str/replace (clojure.core/name k) "-" "_") " must be a finite number, not "
                           (pr-str v))
            {:key k :value v}))))

(defn- fraction
  "`x` clamped to [0, 1]."
  ^double [^double x]
  (min 1.0 (max 0.0 x)))

(defn- object-geometries
  "The Geometries of object Node `node` (one per material)."
  [^Node node]
  (filter #(instance? Geometry %) (.getChildren node)))

(defn body-spatial
  "Where an object's rigid body goes: its Geometry when it has just one,
  as cortex.body puts a segment's body there (so `cortex.body/body!`
  finds it and leaves it alone); else the object Node itself."
  ^Spatial [^Node node]
  (let [gs (object-geometries node)]
    (if (= 1 (count gs)) (first gs) node)))

(defn- half-extents
  "Half the size of the bounding box of `points` along jME's x, y, z."
  [points]
  (mapv (fn [axis]
          (let [cs (map axis points)]
            (/ (- (apply max cs) (apply min cs)) 2.0)))
        [#(.x ^Vector3f %) #(.y ^Vector3f %) #(.z ^Vector3f %)]))

(defn- merged-mesh
  "One Mesh of all `geoms` (object-local, unscaled)."
  ^Mesh [geoms]
  (if (= 1 (count geoms))
    (.getMesh ^Geometry (first geoms))
    (let [m (Mesh.)]
      (GeometryBatchFactory/mergeGeometries (java.util.ArrayList. ^java.util.Collection geoms) m)
      m)))

(def ^:private up-axis
  "jME's Y: the axis Blender's upright shapes (capsule, cylinder, cone),
  which stand on the object's local Z, stand on once in Y-up."
  1)

(defn- shape-settings
  "What Blender's rigidbody_validate_sim_shape makes of a shape, as
  data: the shape's name and sizes, from `half` (the half extents of the
  object's scaled bounding box, jME axes: Blender's x, z, y). Like
  Blender, the shape is centred on the object's origin. Capsules,
  cylinders and cones take the larger of Blender's x and y as radius and
  Blender's z as half height; a sphere takes the largest half extent."
  [shape [hx hy hz]]
  (let [radius (max hx hz)]
    (case shape
      "BOX" {:shape "BOX" :half-extents [hx hy hz]}
      "SPHERE" {:shape "SPHERE" :radius (max hx hy hz)}
      "CAPSULE" {:shape "CAPSULE" :radius radius :height (max 0.0 (* 2 (- hy radius)))}
      "CYLINDER" {:shape "CYLINDER" :half-extents [radius hy radius]}
      "CONE" {:shape "CONE" :radius radius :height (* 2 hy)}
      {:shape shape})))


(defn- tiny
  "Bullet refuses shapes of zero size; keep every size above a hair."
  [x]
  (max 1e-4 (double x)))

(declare sized-shape)

(defn shape-plan
  "The collision shape of object Node `node` whose rigid body is `rb`, as
  plan data (see cortex.plan): its shape type sized from the meshes of
  its Geometries at their world scale. CONVEX_HULL is cortex's
  simplified hull; MESH is a GImpact triangle mesh for a moving body and
  a static triangle mesh (BVH) for a body that never moves, made from
  the object's meshes when built; COMPOUND (Blender 2.9+) is not
  something jBullet can build from one object, so it becomes a hull
  too. A mesh without vertices is a box of (nearly) zero size.
  `static?`: whether the body is PASSIVE. Returns {:shape :warnings
  :empty?}."
  [^Node node rb static?]
  (let [geoms (object-geometries node)
        points (mapcat #(segment/mesh-points (.getMesh ^Geometry %) (.getWorldScale ^Geometry %)) geoms)]
    (if (empty? points)
      ;; Blender gives a mesh without vertices a box of size zero
      {:shape {:type :box :half-extents [(tiny 0) (tiny 0) (tiny 0)]} :warnings [] :empty? true}
      (sized-shape node rb static? geoms points))))

(defn- sized-shape
  "`shape-plan` for an object with vertices."
  [^Node node rb static? geoms points]
  (let [name (.getName node)
        scale (.getWorldScale ^Geometry (first geoms))
        half (mapv tiny (half-extents points))
        settings (shape-settings (:shape rb) half)
        hull #(hash-map :type :hull
                        :points (mapv segment/vector-data
                                      (segment/simplify-hull points segment/max-hull-points)))
        margin (:margin rb)
        ;; a Convex Hull's margin is embedded in it, or none (see above)
        use-margin? (or (:use-margin rb) (#{"MESH" "CONE"} (:shape rb)))
        [shape warnings]
        (case (:shape settings)
          "BOX" [{:type :box :half-extents (:half-extents settings)}]
          "SPHERE" [{:type :sphere :radius (double (:radius settings))}]
          "CAPSULE" [{:type :capsule :radius (tiny (:radius settings))
                      :height (double (:height settings)) :axis up-axis}]
          "CYLINDER" [{:type :cylinder :half-extents (:half-extents settings) :axis up-axis}]
          "CONE" [{:type :cone :radius (tiny (:radius settings))
                   :height (tiny (:height settings)) :axis up-axis}]
          "CONVEX_HULL" [(hull)]
          "MESH" [{:type :mesh :static? (boolean static?) :scale (segment/vector-data scale)}]
          "COMPOUND" [(hull) [(str "rigid body " (pr-str name)
                                   ": COMPOUND shapes are built as a convex hull")]]
          (fail "rigid body" name (str "unknown collision shape " (pr-str (:shape rb))
                                       " (code " (:shape-code rb) ")")
                {:shape (:shape rb)}))]
    {:shape (cond-> shape
              (and use-margin? (number? margin) (Double/isFinite (double margin)) (>= margin 0))
              (assoc :margin (double margin)))
     :warnings (vec warnings)
     :empty? false}))

(defn shape-of
  "The Bullet collision shape that plan data `shape` (see `shape-plan`)
  describes, for object Node `node` (whose meshes a MESH shape is made
  of)."
  ^CollisionShape [shape ^Node node]
  (let [{:keys [type half-extents radius height axis points static? scale margin]} shape
        ^CollisionShape s
        (case type
          :box (util/locked-shape #(BoxCollisionShape. (util/vec3 half-extents)))
          :sphere (SphereCollisionShape. (float radius))
          :capsule (CapsuleCollisionShape. (float radius) (float height) (int axis))
          :cylinder (CylinderCollisionShape. (util/vec3 half-extents) (int axis))
          :cone (ConeCollisionShape. (float radius) (float height) (int axis))
          :hull (segment/hull-from-points (map util/vec3 points))
          :mesh (let [geoms (object-geometries node)
                      ^CollisionShape m (if static?
                                          (engine/mesh-shape (merged-mesh geoms))
                                          (engine/gimpact-shape (merged-mesh geoms)))]
                  (.setScale m (util/vec3 scale))
                  m))]
    (when margin
      (.setMargin s (float margin)))
    s))

(defn collision-shape
  "The collision shape for object Node `node` whose rigid body is `rb`
  (see `shape-plan`), made: [shape warnings empty?]."
  [^Node node rb static?]
  (let [{:keys [shape warnings empty?]} (shape-plan node rb static?)]
    [(shape-of shape node) warnings empty?]))

(defn- body-mass
  "The mass Blender simulates a rigid body with: its mass when it is
  ACTIVE and dynamic, 0 (it never moves by itself) when it is PASSIVE,
  animated (kinematic) or not dynamic, as Blender's RBO_GET_MASS."
  [name rb]
  (let [m (finite "rigid body" name rb :mass)]
    (when (neg? m)
      (fail "rigid body" name (str "mass must not be negative, not " m) {:mass m}))
    (if (or (not= "ACTIVE" (:type rb)) (:kinematic rb) (:disabled rb))
      0.0
      m)))

(defn plan-rigid-body
  "What the Blender rigid body of object Node `node` will be, as plan
  data (see cortex.plan): {:name :kind :rigid-body :kept? (it already
  has a body, which it keeps) :blender-shape :shape (see `shape-plan`)
  :empty? :mass :friction :restitution :damping [linear angular]
  :collision-groups :kinematic? :sleeping-thresholds :sleep (nil,
  :start-asleep or :never) :warnings}. Errors name the object."
  [^Node node]
  (let [name (.getName node)
        rb (rigid-body node)
        spatial (body-spatial node)]
    (when-not (#{"ACTIVE" "PASSIVE"} (:type rb))
      (fail "rigid body" name (str "unknown type " (pr-str (:type rb))
                                   " (code " (:type-code rb) ")")
            {:type (:type rb)}))
    (if (.getControl spatial RigidBodyControl)
      {:name name :kind :rigid-body :kept? true :blender-shape (:shape rb) :warnings []}
      (let [mass (body-mass name rb)
            {:keys [shape warnings empty?]} (shape-plan node rb (= "PASSIVE" (:type rb)))
            groups (:col-groups rb)
            deactivation? (contains? rb :use-deactivation)]
        {:name name :kind :rigid-body :kept? false :blender-shape (:shape rb)
         :shape shape :empty? empty? :mass mass
         :friction (finite "rigid body" name rb :friction)
         :restitution (finite "rigid body" name rb :restitution)
         ;; Bullet clamps damping to [0, 1] (btRigidBody::setDamping); Minie
         ;; refuses anything else, so both engines are given it clamped
         :damping [(fraction (finite "rigid body" name rb :lin-damping))
                   (fraction (finite "rigid body" name rb :ang-damping))]
         :collision-groups (when (integer? groups) (long groups))
         :kinematic? (boolean (:kinematic rb))
         :sleeping-thresholds (when (and deactivation? (:use-deactivation rb)
                                         (util/finite? (:lin-sleep-thresh rb))
                                         (util/finite? (:ang-sleep-thresh rb)))
                                [(double (:lin-sleep-thresh rb)) (double (:ang-sleep-thresh rb))])
         :sleep (when deactivation?
                  (if (:use-deactivation rb)
                    (when (and (:use-start-deactivated rb) (pos? mass)) :start-asleep)
                    (when-not (:kinematic rb) :never)))
         :warnings (cond-> (vec warnings)
                     (:kinematic rb)
                     (conj (str "rigid body " (pr-str name) " is Animated (kinematic): cortex does"
                                " not play its animation, so it stays where it is")))}))))

(defn build-rigid-body!
  "Give `spatial` (see `body-spatial`) of object Node `node` the rigid
  body that plan `p` (see `plan-rigid-body`) says. Returns its
  RigidBodyControl."
  ^RigidBodyControl [^Spatial spatial ^Node node p]
  (let [{:keys [mass shape friction restitution damping collision-groups kinematic? empty?
                sleeping-thresholds sleep]} p
        c (RigidBodyControl. (shape-of shape node) (float mass))
        [lin ang] damping]
    (.setFriction c (float friction))
    (.setRestitution c (float restitution))
    (.setDamping c (float lin) (float ang))
    (when collision-groups
      (engine/set-collections! c collision-groups))
    (when kinematic? (.setKinematic c true))
    (when empty?
      (engine/clear-inertia! c))
    (when-let [[l a] sleeping-thresholds]
      (.setSleepingThresholds c (float l) (float a)))
    (when sleep
      (engine/set-sleep! c sleep))
    (.addControl spatial c)
    c))

(defn rigid-body!
  "Give object Node `node` the jBullet rigid body its Blender rigid body
  describes (see `plan-rigid-body`): shape, mass, friction, restitution
  and damping, collision collections as collision groups, deactivation
  as the file says; an animated (kinematic) body stays where it is
  (with a warning). The body goes on `body-spatial`. An object that
  already has a body keeps it. Returns {:object name :control c
  :spatial s :shape :mass :warnings}."
  [^Node node]
  (let [p (plan-rigid-body node)
        spatial (body-spatial node)
        c (if (:kept? p)
            (.getControl spatial RigidBodyControl)
            (build-rigid-body! spatial node p))]
    {:object (:name p) :control c :spatial spatial :shape (:blender-shape p)
     :mass (if (:kept? p) (.getMass ^RigidBodyControl c) (:mass p)) :warnings (:warnings p)}))

(defn rigid-bodies!
  "Make every object of `creature` that has a Blender rigid body solid
  (see `rigid-body!`), or those of `nodes`. Returns the reports, in
  scene order."
  ([^Node creature] (rigid-bodies! creature (rigid-body-objects creature)))
  ([^Node creature nodes]
   (.updateGeometricState creature)
   (mapv rigid-body! nodes)))
