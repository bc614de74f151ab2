;; Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
(ns cortex.physics-tab
  "Build a creature from Blender's own rigid body physics: every object
  with a Rigid Body (Physics tab) becomes a jBullet rigid body, every
  Rigid Body Constraint a jBullet joint between the two objects it
  names, placed and turned as the constraint object is. No custom
  property is needed.

  Entry points: `load-creature` (a .blend file with its Physics tab
  settings, any of its scenes), `physics-body!` (build the bodies and
  joints of the Rigid Body World, simulated as Blender's world says),
  `warnings` (what could not be built as Blender would, as data),
  `broken-joints` (the joints that broke), `world-settings` (the
  file's Rigid Body World), `simulation-settings` (its gravity,
  substeps, solver iterations and time scale, as data), `gravity` (its
  gravity as a jME vector), `rigid-body` and `rigid-body-constraint`
  (an object's settings)."
  (:require [clojure.string :as str]
            [cortex.blender :as blender]
            [cortex.blender.rigid-body :as physics]
            [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.sense :as sense]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.bullet.collision.shapes BoxCollisionShape CapsuleCollisionShape
                                             CollisionShape ConeCollisionShape
                                             CylinderCollisionShape GImpactCollisionShape
                                             HullCollisionShape SphereCollisionShape)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints PhysicsJoint SixDofJoint SliderJoint)
           (com.jme3.math Matrix3f Vector3f)
           (com.jme3.scene Geometry Mesh Node Spatial)
           (cortex FrameHingeJoint MeteredSixDofJoint MeteredSliderJoint)
           (java.util.concurrent ConcurrentHashMap)
           (java.util.logging Logger)
           (jme3tools.optimize GeometryBatchFactory)))

(set! *warn-on-reflection* true)

(defn rigid-body
  "The Blender rigid body settings of object `spatial` (its Node, or a
  Geometry of it) as the reader made them (see
  cortex.blender.rigid-body/rigid-body): a map with keyword keys
  (:type \"ACTIVE\", :shape \"BOX\", :mass, :friction, :lin-damping,
  :kinematic ...), or nil when it has none."
  [^Spatial spatial]
  (sense/meta-data spatial physics/rigid-body-key))

(defn rigid-body-constraint
  "The Blender rigid body constraint of object `spatial` as the reader
  made it: a map with keyword keys (:type \"HINGE\", :ob1, :ob2,
  :use-limit-ang-z, :limit-ang-z-lower ...), or nil when it has none."
  [^Spatial spatial]
  (sense/meta-data spatial physics/constraint-key))

(defn- objects-with
  "The object Nodes of `creature` that carry user data `key`."
  [^Node creature key]
  (filter #(and (instance? Node %) (some? (.getUserData ^Spatial % key)))
          (util/node-seq creature)))

(defn rigid-body-objects
  "The object Nodes of `creature` that have a Blender rigid body."
  [creature]
  (objects-with creature physics/rigid-body-key))

(defn constraint-objects
  "The object Nodes of `creature` that have a Blender rigid body
  constraint, in name order."
  [creature]
  (sort-by #(.getName ^Spatial %) (objects-with creature physics/constraint-key)))

(defn- fail
  "Throw an ex-info about object `name`."
  [what name msg data]
  (throw (ex-info (str what " " (pr-str name) ": " msg) (assoc data :object name))))

(defn- finite
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

(defn collision-shape
  "The jBullet collision shape for object Node `node` whose rigid body is
  `rb`: its shape type sized from the meshes of its Geometries at their
  world scale. CONVEX_HULL is cortex's simplified hull; MESH is a
  GImpact triangle mesh for a moving body and a static triangle mesh
  (BVH) for a body that never moves; COMPOUND (Blender 2.9+) is not
  something jBullet can build from one object, so it becomes a hull
  too. A mesh without vertices is a box of (nearly) zero size.
  `static?`: whether the body is PASSIVE. Returns [shape warnings]."
  [^Node node rb static?]
  (let [geoms (object-geometries node)
        name (.getName node)
        points (mapcat #(body/mesh-points (.getMesh ^Geometry %) (.getWorldScale ^Geometry %)) geoms)]
    (if (empty? points)
      ;; Blender gives a mesh without vertices a box of size zero
      [(util/locked-shape #(BoxCollisionShape. (Vector3f. (float (tiny 0)) (float (tiny 0)) (float (tiny 0))))) [] :empty]
      (sized-shape node rb static? geoms points))))

(defn- sized-shape
  "`collision-shape` for an object with vertices."
  [^Node node rb static? geoms points]
  (let [name (.getName node)
        scale (.getWorldScale ^Geometry (first geoms))
        half (mapv tiny (half-extents points))
        settings (shape-settings (:shape rb) half)
        hull #(body/hull-from-points (body/simplify-hull points body/max-hull-points))
        margin (:margin rb)
        use-margin? (or (:use-margin rb) (#{"CONVEX_HULL" "MESH" "CONE"} (:shape rb)))
        [shape warnings]
        (case (:shape settings)
          "BOX" [(util/locked-shape #(BoxCollisionShape. (util/vec3 (:half-extents settings))))]
          "SPHERE" [(SphereCollisionShape. (float (:radius settings)))]
          "CAPSULE" [(CapsuleCollisionShape. (float (tiny (:radius settings)))
                                             (float (:height settings)) (int up-axis))]
          "CYLINDER" [(CylinderCollisionShape. (util/vec3 (:half-extents settings)) (int up-axis))]
          "CONE" [(ConeCollisionShape. (float (tiny (:radius settings)))
                                       (float (tiny (:height settings))) (int up-axis))]
          "CONVEX_HULL" [(hull)]
          "MESH" [(let [^com.jme3.bullet.collision.shapes.CollisionShape
                        s (if static?
                            (engine/mesh-shape (merged-mesh geoms))
                            (engine/gimpact-shape (merged-mesh geoms)))]
                    (.setScale s ^Vector3f scale)
                    s)]
          "COMPOUND" [(hull) [(str "rigid body " (pr-str name)
                                   ": COMPOUND shapes are built as a convex hull")]]
          (fail "rigid body" name (str "unknown collision shape " (pr-str (:shape rb))
                                       " (code " (:shape-code rb) ")")
                {:shape (:shape rb)}))]
    (when (and use-margin? (number? margin) (Double/isFinite (double margin)) (>= margin 0))
      (.setMargin ^CollisionShape shape (float margin)))
    [shape (vec warnings)]))

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

(defn rigid-body!
  "Give object Node `node` the jBullet rigid body its Blender rigid body
  describes: shape, mass, friction, restitution and damping, collision
  collections as collision groups, deactivation as the file says; an
  animated (kinematic) body stays where it is (with a warning). The
  body goes on `body-spatial`. An object that already has a body keeps
  it. Returns {:object name :control c :spatial s :shape :mass
  :warnings}."
  [^Node node]
  (let [name (.getName node)
        rb (rigid-body node)
        spatial (body-spatial node)]
    (when-not (#{"ACTIVE" "PASSIVE"} (:type rb))
      (fail "rigid body" name (str "unknown type " (pr-str (:type rb))
                                   " (code " (:type-code rb) ")")
            {:type (:type rb)}))
    (if-let [c (.getControl spatial RigidBodyControl)]
      {:object name :control c :spatial spatial :shape (:shape rb) :mass (.getMass ^RigidBodyControl c) :warnings []}
      (let [mass (body-mass name rb)
            [shape warnings empty] (collision-shape node rb (= "PASSIVE" (:type rb)))
            c (RigidBodyControl. ^CollisionShape shape (float mass))
            groups (:col-groups rb)]
        (.setFriction c (float (finite "rigid body" name rb :friction)))
        (.setRestitution c (float (finite "rigid body" name rb :restitution)))
        ;; Bullet clamps damping to [0, 1] (btRigidBody::setDamping); Minie
        ;; refuses anything else, so both engines are given it clamped
        (.setDamping c (float (fraction (finite "rigid body" name rb :lin-damping)))
                     (float (fraction (finite "rigid body" name rb :ang-damping))))
        (when (integer? groups)
          (engine/set-collections! c groups))
        (when (:kinematic rb) (.setKinematic c true))
        (when empty
          (engine/clear-inertia! c))
        (when (contains? rb :use-deactivation)
          (if (:use-deactivation rb)
            (do (when (and (util/finite? (:lin-sleep-thresh rb)) (util/finite? (:ang-sleep-thresh rb)))
                  (.setSleepingThresholds c (float (:lin-sleep-thresh rb)) (float (:ang-sleep-thresh rb))))
                (when (and (:use-start-deactivated rb) (pos? mass))
                  (engine/set-sleep! c :start-asleep)))
            (when-not (:kinematic rb)
              (engine/set-sleep! c :never))))
        (.addControl spatial c)
        {:object name :control c :spatial spatial :shape (:shape rb) :mass mass
         :warnings (cond-> (vec warnings)
                     (:kinematic rb)
                     (conj (str "rigid body " (pr-str name) " is Animated (kinematic): cortex does"
                                " not play its animation, so it stays where it is")))}))))

(defn rigid-bodies!
  "Make every object of `creature` that has a Blender rigid body solid
  (see `rigid-body!`), or those of `nodes`. Returns the reports, in
  scene order."
  ([^Node creature] (rigid-bodies! creature (rigid-body-objects creature)))
  ([^Node creature nodes]
   (.updateGeometricState creature)
   (mapv rigid-body! nodes)))

(defn constraint-frame
  "The frame of constraint object `node` in the world, as Blender uses
  it: its world rotation (scale left out), whose columns are the
  object's own X, Y and Z axes in jME's world coordinates."
  ^Matrix3f [^Spatial node]
  (.mult (.toRotationMatrix (.getWorldRotation node)) util/blender-axes))

(def ^:private locked-angle
  "jBullet frees a 6-DOF angle whose lower limit equals its upper one
  (its RotationalLimitMotor tests lo >= hi); a limit that Blender gives
  as one value is widened by this much (radians) on each side, so it
  locks. Native Bullet's joint locks equal limits, and from the first
  step, which a widened angle would not be held in: there the margin
  is 0 (see MeteredSixDofJoint in org/engine.org)."
  MeteredSixDofJoint/ANGLE_LOCK_MARGIN)

(def ^:private axes ["x" "y" "z"])

(defn limits
  "The [lower upper] limits of constraint `rbc` for `kind` (\"lin\" or
  \"ang\") on each axis, nil for an axis Blender leaves free."
  [name rbc kind]
  (mapv (fn [a]
          (when (get rbc (keyword (str "use-limit-" kind "-" a)))
            [(finite "rigid body constraint" name rbc (keyword (str "limit-" kind "-" a "-lower")))
             (finite "rigid body constraint" name rbc (keyword (str "limit-" kind "-" a "-upper")))]))
        axes))

(defn- six-dof-limits
  "Lower and upper limit vectors for a 6-DOF joint: a free axis gets
  lower > upper, which Bullet reads as free; an angle locked at one
  value is widened by `locked-angle`."
  [ls angular?]
  (let [ls (map (fn [l]
                  (cond (nil? l) [0.0 -1.0]
                        (and angular? (= (first l) (second l)))
                        [(- (first l) locked-angle) (+ (second l) locked-angle)]
                        :else l))
                ls)]
    [(util/vec3 (map first ls)) (util/vec3 (map second ls))]))

(defn- six-dof
  "A 6-DOF joint (MeteredSixDofJoint: jME's SixDofJoint on jBullet, a
  New6Dof on native Bullet) in the frames of `ctx`, linear limits `lin`
  and angular limits `ang` (per axis [lower upper], nil for free),
  measured in body A's frame as Blender's constraints are."
  ^MeteredSixDofJoint [{:keys [a b pivot-a pivot-b rot-a rot-b]} lin ang]
  (let [[llo lhi] (six-dof-limits lin false)
        [alo ahi] (six-dof-limits ang true)]
    (doto (MeteredSixDofJoint. a b pivot-a pivot-b rot-a rot-b true)
      (.setLinearLowerLimit llo)
      (.setLinearUpperLimit lhi)
      (.setAngularLowerLimit alo)
      (.setAngularUpperLimit ahi))))

(defn- slider
  "A jME SliderJoint along the frame's X: linear limits `lin` and
  angular limits `ang` about X, each [lower upper] or nil (free)."
  ^SliderJoint [{:keys [a b pivot-a pivot-b rot-a rot-b]} lin ang]
  (let [[llo lhi] (or lin [1.0 -1.0])
        [alo ahi] (or ang [1.0 -1.0])]
    (doto (MeteredSliderJoint. a b pivot-a pivot-b rot-a rot-b true)
      (.setLowerLinLimit (float llo))
      (.setUpperLinLimit (float lhi))
      (.setLowerAngLimit (float alo))
      (.setUpperAngLimit (float ahi)))))

(def locked
  "Limits that hold an axis still."
  [0.0 0.0])

(defmulti constraint-joint
  "Make the jBullet joint for Blender constraint type `type` (a name:
  \"HINGE\"...). `ctx` holds :name (the constraint object's), :rbc (its
  settings), the bodies :a and :b, and the constraint's frame in each
  body: :pivot-a, :pivot-b, :rot-a, :rot-b. Returns {:joint j
  :warnings [...]}."
  (fn [type _ctx] type))

(defmethod constraint-joint :default
  [type {:keys [name rbc]}]
  (fail "rigid body constraint" name
        (str "jBullet cannot build constraint type " (pr-str type)
             " (code " (:type-code rbc) ")")
        {:type type}))

(defmethod constraint-joint "FIXED" [_ ctx]
  {:joint (six-dof ctx [locked locked locked] [locked locked locked])})

(defmethod constraint-joint "POINT" [_ ctx]
  {:joint (six-dof ctx [locked locked locked] [nil nil nil])})

(defn hinge-limit
  "The limit to give a jBullet hinge so that it stops at `angle`
  (radians). jBullet, like the Bullet 2.7 it ports, measures a hinge's
  angle with ScalarUtil/atan2Fast, an approximation off by up to a few
  hundredths of a radian; a limit is compared with that measure, so
  the limit is passed through the same approximation. Native Bullet's
  frame hinge measures exactly, and takes the angle as it is: see
  cortex.engine/frame-hinge-limit."
  [angle]
  (engine/frame-hinge-limit angle))

(defmethod constraint-joint "HINGE" [_ {:keys [name rbc a b pivot-a pivot-b rot-a rot-b]}]
  (let [j (FrameHingeJoint. a b pivot-a pivot-b rot-a rot-b)]
    (when-let [[lo hi] (nth (limits name rbc "ang") 2)]
      (.setLimit j (float (hinge-limit lo)) (float (hinge-limit hi))))
    {:joint j}))

(defmethod constraint-joint "SLIDER" [_ {:keys [name rbc] :as ctx}]
  {:joint (slider ctx (first (limits name rbc "lin")) locked)})

(defmethod constraint-joint "PISTON" [_ {:keys [name rbc] :as ctx}]
  {:joint (slider ctx (first (limits name rbc "lin")) (first (limits name rbc "ang")))})

(defmethod constraint-joint "GENERIC" [_ {:keys [name rbc] :as ctx}]
  {:joint (six-dof ctx (limits name rbc "lin") (limits name rbc "ang"))})

(defmethod constraint-joint "MOTOR" [_ {:keys [name rbc] :as ctx}]
  (let [j (six-dof ctx [nil nil nil] [nil nil nil])
        motor (.getRotationalLimitMotor j 0)]
    (when (:use-motor-ang rbc)
      (doto motor
        (.setEnableMotor true)
        (.setTargetVelocity (float (finite "rigid body constraint" name rbc :motor-ang-target-velocity)))
        (.setMaxMotorForce (float (finite "rigid body constraint" name rbc :motor-ang-max-impulse)))))
    {:joint j
     :warnings (when (:use-motor-lin rbc)
                 [(str "rigid body constraint " (pr-str name)
                       ": jBullet's 6-DOF joint has no linear motor; the linear motor is left off")])}))

(defn- springs
  "The springs of constraint `rbc`: for each axis whose spring is on,
  {:angular? :axis (0 1 2) :stiffness :damping}."
  [name rbc]
  (vec (for [[angular? prefix] [[false ""] [true "ang_"]]
             [i a] (map-indexed vector axes)
             :let [suffix (str (str/replace prefix "_" "-") a)]
             :when (get rbc (keyword (str "use-spring-" suffix)))]
         {:angular? angular? :axis i
          :stiffness (finite "rigid body constraint" name rbc (keyword (str "spring-stiffness-" suffix)))
          :damping (finite "rigid body constraint" name rbc (keyword (str "spring-damping-" suffix)))})))

(defn- frame-now
  "Where the frame (`pivot`, `rot`, in `c`'s body) is in the world now:
  [origin rotation]."
  [^RigidBodyControl c ^Vector3f pivot ^Matrix3f rot]
  (let [r (engine/rotation-matrix c)]
    [(.add (.getPhysicsLocation c) (.mult r pivot)) (.mult r rot)]))

(defn- point-velocity
  "The world velocity of the body point at world position `p`."
  ^Vector3f [^RigidBodyControl c ^Vector3f p]
  (.add (.getLinearVelocity c)
        (.cross (.getAngularVelocity c) (.subtract p (.getPhysicsLocation c)))))

(defn- rotation-vector
  "The rotation `m` as a rotation vector (axis times angle, radians)."
  ^Vector3f [^Matrix3f m]
  (let [q (.fromRotationMatrix (com.jme3.math.Quaternion.) m)
        ^com.jme3.math.Quaternion q (if (neg? (.getW q)) (.negate q) q)
        axis (Vector3f.)
        angle (.toAngleAxis q axis)]
    (if (< (.length axis) 1e-9) (Vector3f.) (.mult (.normalize axis) angle))))

(defn- spring-forces!
  "Push the bodies `a` and `b` of a spring constraint back towards the
  rest pose its frames had when it was made (both frames at one place,
  turned alike), as Bullet's 6-DOF spring does: along (and about) each
  sprung axis of frame A, a force -k x - c v, x the offset and v its
  rate of change, on B and its opposite on A, for a step of `dt`
  seconds. The force is given as the impulse it imparts over the step:
  jBullet calls tick listeners after it has already added up the step's
  forces."
  [{:keys [^RigidBodyControl a ^RigidBodyControl b pivot-a pivot-b rot-a rot-b]} springs dt]
  (let [[^Vector3f pa ^Matrix3f ra] (frame-now a pivot-a rot-a)
        [^Vector3f pb ^Matrix3f rb] (frame-now b pivot-b rot-b)
        rat (.transposeNew ra)
        offset (.mult rat (.subtract pb pa))
        rate (.mult rat (.subtract (point-velocity b pb) (point-velocity a pa)))
        turn (rotation-vector (.mult rat rb))
        spin (.mult rat (.subtract (.getAngularVelocity b) (.getAngularVelocity a)))]
    (doseq [{:keys [angular? axis stiffness damping]} springs
            :let [x (.get (if angular? turn offset) (int axis))
                  v (.get (if angular? spin rate) (int axis))
                  dir (.getColumn ra (int axis))
                  push (.mult dir (float (* (double dt) (- (+ (* stiffness x) (* damping v))))))]]
      (if angular?
        (do (.applyTorqueImpulse b push)
            (.applyTorqueImpulse a (.negate push)))
        (do (.applyImpulse b push (.subtract pb (.getPhysicsLocation b)))
            (.applyImpulse a (.negate push) (.subtract pa (.getPhysicsLocation a))))))))

(defn- spring-control
  "A jME physics control that runs `spring-forces!` before every physics
  step of the space it joins: jBullet has no spring constraint, so the
  springs of a GENERIC_SPRING constraint are forces cortex applies."
  [ctx springs]
  (let [space (atom nil)
        enabled (atom true)]
    (reify
      com.jme3.bullet.control.PhysicsControl
      (setPhysicsSpace [this s]
        (when-let [^com.jme3.bullet.PhysicsSpace old @space] (.removeTickListener old this))
        (reset! space s)
        (when s (.addTickListener ^com.jme3.bullet.PhysicsSpace s this)))
      (getPhysicsSpace [_] @space)
      (setEnabled [_ on] (reset! enabled (boolean on)))
      (isEnabled [_] @enabled)
      (cloneForSpatial [_ _] (spring-control ctx springs))
      (setSpatial [_ _])
      (update [_ _])
      (render [_ _ _])
      (write [_ _])
      (read [_ _])
      com.jme3.bullet.PhysicsTickListener
      (prePhysicsTick [_ _ dt]
        (when @enabled (spring-forces! ctx springs dt)))
      (physicsTick [_ _ _]))))

(defmethod constraint-joint "GENERIC_SPRING" [_ {:keys [name rbc b] :as ctx}]
  (let [j (six-dof ctx (limits name rbc "lin") (limits name rbc "ang"))
        ss (springs name rbc)]
    {:joint j
     :springs ss
     :spring-control (when (seq ss) (spring-control ctx ss))
     :warnings (when (and (seq ss) (= "SPRING1" (:spring-type rbc)))
                 [(str "rigid body constraint " (pr-str name)
                       ": SPRING1 damping is Bullet's velocity factor; cortex's springs"
                       " damp as SPRING2 does")])}))

(defn- body-of
  "The body report (see `rigid-body!`) of the object named by `k` (:ob1
  or :ob2) of constraint `rbc`, from `bodies` (object name -> report); an error
  naming the constraint when the name is missing or names no rigid body."
  [name rbc bodies k]
  (let [which (if (= k :ob1) "first object (ob1)" "second object (ob2)")
        target (get rbc k)]
    (cond
      (nil? target)
      (fail "rigid body constraint" name (str "its " which " is not set") {:missing k})
      (nil? (get bodies target))
      (fail "rigid body constraint" name
            (str "its " which " " (pr-str target) " is not a rigid body of this creature")
            {:missing k :target target})
      :else (get bodies target))))

(defn- caveats
  "What jBullet cannot do of constraint `rbc`, as warnings."
  [name rbc]
  (let [label (str "rigid body constraint " (pr-str name) ": ")]
    (cond-> []
      (:use-override-solver-iterations rbc)
      (conj (str label "jBullet has no per-joint solver iterations; "
                 (:num-solver-iterations rbc) " iterations are ignored")))))

(defn constraint!
  "Make the jBullet joint that constraint object `node` describes,
  between the bodies of the objects it names (`bodies`: object name ->
  the report of `rigid-body!`). The joint's frame is the constraint object's world
  transform, as in Blender. Its bodies collide with each other unless
  Blender's Disable Collisions is on. A disabled constraint makes no
  joint. Returns {:object :type :joint :bodies [ob1 ob2] :warnings}, plus
  :springs for GENERIC_SPRING and :breaking-threshold for a joint that
  breaks. Errors name the constraint object."
  [^Spatial node bodies]
  (let [name (.getName node)
        rbc (rigid-body-constraint node)
        type (:type rbc)]
    (if-not (:enabled rbc)
      {:object name :type type :joint nil :bodies [(:ob1 rbc) (:ob2 rbc)]
       :warnings [(str "rigid body constraint " (pr-str name) " is disabled in Blender: no joint")]}
      (let [^RigidBodyControl a (:control (body-of name rbc bodies :ob1))
            ^RigidBodyControl b (:control (body-of name rbc bodies :ob2))
            _ (when (identical? a b)
                (fail "rigid body constraint" name
                      (str "joins " (pr-str (:ob1 rbc)) " to itself") {}))
            _ (when-not (contains? (methods constraint-joint) type)
                (constraint-joint type {:name name :rbc rbc}))
            center (.getWorldTranslation node)
            frame (constraint-frame node)
            ctx {:name name :rbc rbc :a a :b b
                 :pivot-a (body/pivot a center) :pivot-b (body/pivot b center)
                 :rot-a (body/body-frame a frame) :rot-b (body/body-frame b frame)}
            {:keys [^PhysicsJoint joint warnings] :as made} (constraint-joint type ctx)
            threshold (when (:use-breaking rbc)
                        (finite "rigid body constraint" name rbc :breaking-threshold))]
        (engine/collide-linked! joint (not (:disable-collisions rbc)))
        (when threshold
          (engine/breaking-threshold! joint threshold))
        (when-let [sc (:spring-control made)]
          (.addControl ^Spatial (:spatial (body-of name rbc bodies :ob2))
                       ^com.jme3.scene.control.Control sc))
        (cond-> (merge (dissoc made :spring-control)
                       {:object name :type type :joint joint :bodies [(:ob1 rbc) (:ob2 rbc)]
                        :warnings (into (vec warnings) (caveats name rbc))})
          threshold
          (assoc :breaking-threshold threshold))))))

(defn constraints!
  "Make the joint of every rigid body constraint of `creature` (see
  `constraint!`), in the constraint objects' name order. `bodies` maps
  object names to the reports of `rigid-body!`; without it, the bodies
  the creature's rigid body objects already have are used. Returns the
  reports."
  ([^Node creature]
   (constraints! creature
                 (into {} (for [^Node n (rigid-body-objects creature)
                                :let [s (body-spatial n)
                                      c (.getControl s RigidBodyControl)]
                                :when c]
                            [(.getName n) {:control c :spatial s}]))))
  ([^Node creature bodies]
   (.updateGeometricState creature)
   (mapv #(constraint! % bodies) (constraint-objects creature))))

(defn world-settings
  "The Rigid Body World settings of the scene `creature` was loaded
  from, as the reader made them (see
  cortex.blender.rigid-body/rigid-body-world: :gravity, :time-scale,
  :steps-per-second, :num-solver-iterations, :fps,
  :collection-objects ...), or nil when the file has none. The loader
  leaves them on the scene Node: they are looked for in `creature` and
  below it, then in the Nodes above it."
  [^Spatial creature]
  (or (some #(.getUserData ^Spatial % ^String physics/world-key) (util/node-seq creature))
      (loop [^Spatial p (.getParent creature)]
        (when p
          (or (.getUserData p ^String physics/world-key) (recur (.getParent p)))))))

(defn gravity
  "Blender's gravity for rigid body world settings `world` (see
  `world-settings`): the scene's gravity times the world's effector
  weight, in jME's axes; zero when the scene's gravity is off, and
  Blender's default (0, -9.81, 0 in jME's axes) when `world` is nil."
  ^Vector3f [world]
  (let [g (get world :gravity [0.0 0.0 -9.81])
        w (double (get world :effector-gravity 1.0))]
    (if (get world :use-gravity true)
      (.mult (util/blender-to-jme (util/vec3 g)) (float w))
      (Vector3f.))))

(def ^{:arglists '([t k])} substep-length
  "cortex.world/substep-length, which lives below the reader so that the
  step loop needs none of it: the length of a substep that makes
  Bullet's fixed-step loop run exactly k in a step of t/60."
  world/substep-length)

(defn simulation-settings
  "How Blender simulates the world of settings `world` (see
  `world-settings`; Blender's defaults when nil), for a cortex step of
  1/60 s: {:gravity [x y z] (jME axes, m/s^2), :substeps k (Bullet
  steps per 1/60 s step), :step a (seconds of physics per substep:
  time-scale / (60 k), a hair less so that float arithmetic always
  gives k), :iterations n (solver iterations), :time-scale t, :blender
  {:fps :substeps-per-frame :rate}} (Blender's frame rate, substeps per
  frame and physics steps per second)."
  [world]
  (let [fps (double (or (:fps world) 24.0))
        raw (or (:substeps-per-frame world) (:steps-per-second world))
        new? (or (nil? world) (>= (long (or (:file-version world) 0)) 291)
                 (contains? world :substeps-per-frame))
        per-frame (if new? (max 1 (long (or raw 10))) (max 1 (Math/round (/ (double (or raw 60)) fps))))
        rate (if new? (* per-frame fps) (double (max 1 (long (or raw 60)))))
        k (max 1 (Math/round (/ rate 60.0)))
        t (let [t (double (or (:time-scale world) 1.0))]
            (if (and (util/finite? t) (pos? t)) t 1.0))
        g (gravity world)]
    {:gravity [(.x g) (.y g) (.z g)]
     :substeps k
     :step (substep-length t k)
     :iterations (max 1 (long (or (:num-solver-iterations world) 10)))
     :time-scale t
     :blender {:fps fps :substeps-per-frame per-frame :rate rate}}))

(def simulation-key
  "The user data under which `physics-body!` leaves the creature's
  `simulation-settings` (cortex.world/simulation-key)."
  world/simulation-key)

(defn- blender-joint-order
  "The joints of `joints` (reports of `constraint!`) in the order of
  `names`, the world's constraints collection, in which Blender adds
  them to its world; any not in it after them, in name order."
  [joints names]
  (let [index (zipmap names (range))]
    (->> joints
         (filter :joint)
         (sort-by (juxt #(get index (:object %) Long/MAX_VALUE) :object))
         (mapv :joint))))

(defn- simulation-control
  "A physics control that applies `settings` (see `simulation-settings`;
  nil applies none) to the space it joins, and removes each of
  `breakable` ({:object :joint :breaking-threshold}) after the first
  substep in which its applied impulse reaches its threshold, noting
  it in `broken`, a java.util.Map (object name -> substep). Before the
  first substep it adds `ordered` (joints) to the space again, in that
  order: Blender's."
  ([settings breakable broken] (simulation-control settings breakable broken []))
  ([settings breakable broken ordered]
  (let [space (atom nil)
        enabled (atom true)
        substeps (atom 0)]
    (reify
      com.jme3.bullet.control.PhysicsControl
      (setPhysicsSpace [this s]
        (when-let [^com.jme3.bullet.PhysicsSpace old @space] (.removeTickListener old this))
        (reset! space s)
        (when-let [^com.jme3.bullet.PhysicsSpace s s]
          (when settings
            (let [{:keys [substeps step iterations]} settings]
              (.setGravity s (util/vec3 (:gravity settings)))
              (.setSolverNumIterations s (int iterations))
              (.setAccuracy s (float step))
              (.setMaxSubSteps s (int substeps))
              (engine/blender-solver-order! s)))
          (.addTickListener s this)))
      (getPhysicsSpace [_] @space)
      (setEnabled [_ on] (reset! enabled (boolean on)))
      (isEnabled [_] @enabled)
      (cloneForSpatial [_ _] (simulation-control settings breakable (ConcurrentHashMap.) ordered))
      (setSpatial [_ _])
      (update [_ _])
      (render [_ _ _])
      (write [_ _])
      (read [_ _])
      com.jme3.bullet.PhysicsTickListener
      (prePhysicsTick [_ s dt]
        (when settings (engine/gyroscopic-step! s dt))
        (when (zero? @substeps)
          (let [^com.jme3.bullet.PhysicsSpace s s
                in-space (filter (set (.getJointList s)) ordered)]
            (doseq [^PhysicsJoint j in-space] (.remove s j))
            (doseq [^PhysicsJoint j in-space] (.add s j)))))
      (physicsTick [_ s _]
        (let [n (swap! substeps inc)]
          (when @enabled
            (doseq [{:keys [object ^PhysicsJoint joint breaking-threshold]} breakable
                    :when (and (not (.containsKey ^java.util.Map broken object))
                               (engine/broken? joint breaking-threshold))]
              (.remove ^com.jme3.bullet.PhysicsSpace s joint)
              (.destroy joint)
              (.put ^java.util.Map broken object n)))))))))

(def ^:private ^Logger logger (Logger/getLogger "cortex.physics-tab"))

(def ^:private warnings-key
  "The user data under which `physics-body!` leaves its warnings."
  "blender-physics-warnings")

(def ^:private broken-key
  "The user data under which `physics-body!` leaves the map of broken
  joints."
  "blender-broken-joints")

(defn- members
  "Of `nodes`, those whose names are in `names` and those that are not,
  or all of them when `names` is nil (no collection to go by) or `all?`."
  [nodes names all?]
  (if (or all? (nil? names))
    [nodes []]
    (let [in (set names)]
      [(filter #(in (.getName ^Spatial %)) nodes) (remove #(in (.getName ^Spatial %)) nodes)])))

(defn- names-of [nodes] (mapv #(.getName ^Spatial %) nodes))

(defn build!
  "Give `creature` (a Node loaded from Blender) the body Blender's Physics
  tab describes: rigid bodies, then joints for its rigid body
  constraints, of the objects Blender simulates (the Rigid Body World's
  collections), or of every object with settings when `opts` has
  :all-rigid-bodies? true. A creature that also has custom-property
  joints (a \"joints\" empty, see cortex.body) gets those too, by
  `cortex.body/body!`, between the two. The creature's Node gets a
  control that applies the world's `simulation-settings` to the space
  it joins (unless :simulation? false) and breaks joints that reach
  their breaking threshold. Returns {:creature :bodies :joints
  :warnings :simulation :broken}: the reports of `rigid-body!` and
  `constraint!`, every warning, the settings applied, and a map (a
  java.util.Map, filled in as the world runs) of the joints broken so
  far, constraint object name -> substep."
  ([creature] (build! creature {}))
  ([^Node creature {:keys [all-rigid-bodies? simulation?] :or {simulation? true}}]
   (let [world (world-settings creature)
         [body-nodes left] (members (rigid-body-objects creature) (:collection-objects world)
                                    all-rigid-bodies?)
         [con-nodes con-left] (members (constraint-objects creature) (:constraint-objects world)
                                       all-rigid-bodies?)
         bodies (rigid-bodies! creature body-nodes)
         by-name (into {} (map (juxt :object identity)) bodies)
         excluded (set (names-of left))
         [con-nodes skipped] (let [out? #(some excluded ((juxt :ob1 :ob2) (rigid-body-constraint %)))]
                               [(remove out? con-nodes) (filter out? con-nodes)])
         _ (when (seq (body/joints creature))
             (body/body! creature))
         joints (mapv #(constraint! % by-name) (do (.updateGeometricState creature) con-nodes))
         settings (when simulation? (simulation-settings world))
         breakable (filter :breaking-threshold joints)
         broken (ConcurrentHashMap.)
         warnings (vec (concat
                        (when (seq left)
                          [(str "rigid bodies " (pr-str (names-of left)) " are not in the Rigid Body"
                                " World's collection: Blender does not simulate them, and they are"
                                " not built ({:all-rigid-bodies? true} builds them)")])
                        (when (seq con-left)
                          [(str "rigid body constraints " (pr-str (names-of con-left)) " are not in"
                                " the Rigid Body World's constraints collection: not built")])
                        (when (seq skipped)
                          [(str "rigid body constraints " (pr-str (names-of skipped)) " join bodies"
                                " that are not built: not built")])
                        (when (and settings (> (double (:time-scale settings)) 1.0))
                          [(str "the Rigid Body World's time scale is " (:time-scale settings)
                                ": a cortex world steps at most 1/60 s of physics a frame; set its"
                                " BulletAppState's speed to the time scale to follow it")])
                        (mapcat :warnings bodies) (mapcat :warnings joints)))]
     (.addControl creature ^com.jme3.scene.control.Control
                  (simulation-control settings (vec breakable) broken
                                      (blender-joint-order joints (:constraint-objects world))))
     {:creature creature :bodies bodies :joints joints :warnings warnings
      :simulation settings :broken broken})))

(defn physics-body!
  "Like `cortex.body/body!`, for a creature made in Blender's Physics
  tab: build it (see `build!`, which takes the same `opts`), log the
  warnings, keep them as the creature's user data
  \"blender-physics-warnings\" (a list of strings) and its
  `simulation-settings` under `simulation-key`, and return the
  creature."
  ([creature] (physics-body! creature {}))
  ([^Node creature opts]
   (let [{:keys [warnings simulation broken]} (build! creature opts)]
     (doseq [w warnings] (.warning logger ^String w))
     (.setUserData creature ^String warnings-key (java.util.ArrayList. ^java.util.Collection warnings))
     (when simulation (.setUserData creature ^String simulation-key simulation))
     (.setUserData creature ^String broken-key broken)
     creature)))

(defn warnings
  "The warnings `physics-body!` left on `creature`."
  [^Node creature]
  (vec (.getUserData creature ^String warnings-key)))

(defn broken-joints
  "The joints of `creature` (built by `physics-body!`) that broke so far:
  constraint object name -> the substep (counted from the world's
  start) after which it broke."
  [^Node creature]
  (into {} (.getUserData creature ^String broken-key)))

(defn load-creature
  "Load the .blend file at `path` as a creature, with cortex's reader,
  which leaves every object's Blender physics on its Node (see
  `rigid-body`, `rigid-body-constraint`) and the scene's Rigid Body
  World on the scene Node (see `world-settings`); not yet physical.
  `opts` as for cortex.blender/load-blender-model: {:scene \"Game\"}
  loads that scene."
  (^Node [path] (load-creature path {}))
  (^Node [path opts] (blender/load-blender-model path opts)))
