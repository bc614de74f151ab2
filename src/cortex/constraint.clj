;; Generated from org/rigid-bodies.org by lein tangle: edit the chapter, not this file.
(ns cortex.constraint
  "Blender's rigid body constraints (the Physics tab) and its Rigid Body
  World: each constraint as plan data (`plan-constraint`) and the
  Bullet joint made from that (`build-constraint!`), springs, breaking,
  and how Blender steps its world (`simulation-settings`,
  `simulation-control`).

  Entry points: `constraint-frame`, `limits`, `hinge-limit`, `locked`,
  `constraint-joint` (a multimethod, by Blender's constraint type),
  `plan-constraint`, `build-constraint!`, `constraint!`,
  `constraints!`, `world-settings`, `gravity`, `simulation-settings`,
  `simulation-key`, `substep-length`, `simulation-control`,
  `blender-joint-order`."
  (:require [clojure.string :as str]
            [cortex.engine :as engine]
            [cortex.joint :as joint]
            [cortex.rigid-body :as rigid-body :refer [fail finite rigid-body-constraint
                                                      constraint-objects rigid-body-objects
                                                      body-spatial]]
            [cortex.segment :as segment]
            [cortex.sense :as sense]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints PhysicsJoint SixDofJoint SliderJoint)
           (com.jme3.math Matrix3f Vector3f)
           (com.jme3.scene Node Spatial)
           (cortex FrameHingeJoint MeteredSixDofJoint MeteredSliderJoint)
           (java.util.concurrent ConcurrentHashMap)))

(set! *warn-on-reflection* true)

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

(defn plan-constraint
  "What the rigid body constraint of object `node` will be, as plan data
  (see cortex.plan): {:name :type :enabled? :segments [ob1 ob2]
  :settings (Blender's, as plain data) :pivot :rotation (the constraint
  object's world transform, jME axes) :breaking-threshold :warnings}.
  `bodies` holds the names of the creature's rigid bodies (as keys).
  Errors name the constraint object: an object not set or not a rigid
  body, an object joined to itself, a type jBullet cannot build, a limit
  or spring that is not a number."
  [^Spatial node bodies]
  (let [name (.getName node)
        rbc (rigid-body-constraint node)
        type (:type rbc)]
    (if-not (:enabled rbc)
      {:name name :type type :enabled? false :segments [(:ob1 rbc) (:ob2 rbc)]
       :warnings [(str "rigid body constraint " (pr-str name) " is disabled in Blender: no joint")]}
      (do (body-of name rbc bodies :ob1)
          (body-of name rbc bodies :ob2)
          (when (= (:ob1 rbc) (:ob2 rbc))
            (fail "rigid body constraint" name
                  (str "joins " (pr-str (:ob1 rbc)) " to itself") {}))
          (when-not (contains? (methods constraint-joint) type)
            (constraint-joint type {:name name :rbc rbc}))
          (limits name rbc "lin")
          (limits name rbc "ang")
          (springs name rbc)
          {:name name :type type :enabled? true :segments [(:ob1 rbc) (:ob2 rbc)]
           :settings (segment/plain rbc)
           :pivot (segment/vector-data (.getWorldTranslation node))
           :rotation (segment/quaternion-data (.getWorldRotation node))
           :breaking-threshold (when (:use-breaking rbc)
                                 (finite "rigid body constraint" name rbc :breaking-threshold))
           :warnings (caveats name rbc)}))))

(defn build-constraint!
  "Make the joint that constraint `p` of a plan (see `plan-constraint`)
  describes, between the bodies of the objects it names (`bodies`:
  object name -> {:control :spatial}). The joint's frame is the
  constraint object's world transform, as in Blender. Its bodies
  collide with each other unless Blender's Disable Collisions is on.
  Returns {:object :type :joint :bodies [ob1 ob2] :warnings}, plus
  :springs for GENERIC_SPRING and :breaking-threshold for a joint that
  breaks."
  [p bodies]
  (let [{:keys [name type enabled? segments settings pivot rotation breaking-threshold]} p]
    (if-not enabled?
      {:object name :type type :joint nil :bodies segments :warnings (:warnings p)}
      (let [rbc settings
            ^RigidBodyControl a (:control (body-of name rbc bodies :ob1))
            ^RigidBodyControl b (:control (body-of name rbc bodies :ob2))
            center (util/vec3 pivot)
            frame (.mult (.toRotationMatrix (segment/quaternion rotation)) util/blender-axes)
            ctx {:name name :rbc rbc :a a :b b
                 :pivot-a (joint/pivot a center) :pivot-b (joint/pivot b center)
                 :rot-a (joint/body-frame a frame) :rot-b (joint/body-frame b frame)}
            {:keys [^PhysicsJoint joint warnings] :as made} (constraint-joint type ctx)]
        (engine/collide-linked! joint (not (:disable-collisions rbc)))
        (when breaking-threshold
          (engine/breaking-threshold! joint breaking-threshold))
        (when-let [sc (:spring-control made)]
          (.addControl ^Spatial (:spatial (body-of name rbc bodies :ob2))
                       ^com.jme3.scene.control.Control sc))
        (cond-> (merge (dissoc made :spring-control)
                       {:object name :type type :joint joint :bodies segments
                        :warnings (into (vec warnings) (:warnings p))})
          breaking-threshold
          (assoc :breaking-threshold breaking-threshold))))))

(defn constraint!
  "Make the jBullet joint that constraint object `node` describes,
  between the bodies of the objects it names (`bodies`: object name ->
  the report of `rigid-body!`): `plan-constraint`, then
  `build-constraint!`. A disabled constraint makes no joint. Errors
  name the constraint object."
  [^Spatial node bodies]
  (build-constraint! (plan-constraint node bodies) bodies))

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
  (or (some #(.getUserData ^Spatial % ^String sense/world-key) (util/node-seq creature))
      (loop [^Spatial p (.getParent creature)]
        (when p
          (or (.getUserData p ^String sense/world-key) (recur (.getParent p)))))))

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

(defn blender-joint-order
  "The joints of `joints` (reports of `constraint!`) in the order of
  `names`, the world's constraints collection, in which Blender adds
  them to its world; any not in it after them, in name order."
  [joints names]
  (let [index (zipmap names (range))]
    (->> joints
         (filter :joint)
         (sort-by (juxt #(get index (:object %) Long/MAX_VALUE) :object))
         (mapv :joint))))

(defn simulation-control
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
        (when settings (engine/blender-velocities! s dt))
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
