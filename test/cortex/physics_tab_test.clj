;; Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
(ns cortex.physics-tab-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.blender :as blender]
            [cortex.blender-test :refer [read-json]]
            [cortex.physics-tab :as bp]
            [cortex.blender.rigid-body :as physics]
            [cortex.blender.scene :as scene]
            [cortex.blender.file :as file]
            [cortex.body :as body]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.app.state AbstractAppState)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints SliderJoint)
           (com.jme3.math Quaternion Vector3f)
           (com.jme3.scene Node Spatial)
           (cortex FrameHingeJoint MeteredSixDofJoint)))

(set! *warn-on-reflection* true)

(def versions ["b34" "b45" "b50"])

(defn fixture [v] (str "test/fixtures/blend/" v "/physics.blend"))

(defn oracle [v]
  (read-json (slurp (str "test/fixtures/blend/" v "/physics.json"))))

(defn same? [a b]
  (if (and (number? a) (number? b))
    (< (Math/abs (- (double a) (double b))) 1e-5)
    (= a b)))

(def body-names
  "Blender's Python names of rigid body settings -> the keys (DNA names,
  as keywords) the reader keeps them under."
  {"type" :type "kinematic" :kinematic "mass" :mass "collision_shape" :shape
   "friction" :friction "restitution" :restitution "use_margin" :use-margin
   "collision_margin" :margin "linear_damping" :lin-damping
   "angular_damping" :ang-damping "use_deactivation" :use-deactivation
   "use_start_deactivated" :use-start-deactivated
   "deactivate_linear_velocity" :lin-sleep-thresh
   "deactivate_angular_velocity" :ang-sleep-thresh})

(def constraint-renames
  "Blender's Python names of constraint settings whose DNA names differ
  -> the keys the reader keeps them under; every other Python name is
  its DNA name."
  {"object1" :ob1 "object2" :ob2 "solver_iterations" :num-solver-iterations})

(deftest reads-what-blender-says
  (doseq [v versions]
    (testing v
      (let [o (oracle v)
            bf (:file (blender/read-blend (fixture v)))
            sc (scene/current-scene bf)
            obs (into {} (map (juxt file/id-name identity)) (scene/scene-objects bf sc))]
        (doseq [t (get o "objects")
                :let [name (get t "name") ob (obs name)
                      rb (physics/rigid-body bf ob)
                      rbc (physics/rigid-body-constraint bf ob)]]
          (testing name
            (is (= (some? (get t "rigid_body")) (some? rb)))
            (is (= (some? (get t "rigid_body_constraint")) (some? rbc)))
            (when-let [trb (get t "rigid_body")]
              (is (= (get trb "enabled") (not (:disabled rb))))
              (doseq [[k key] body-names]
                (is (same? (get trb k) (get rb key)) k)))
            (when-let [trbc (get t "rigid_body_constraint")]
              (doseq [[k x] trbc]
                (is (same? x (get rbc (get constraint-renames k (physics/dna-key k)))) k)))))
        (let [w (physics/rigid-body-world bf sc)
              tw (get o "rigid_body_world")]
          (is (same? (get tw "time_scale") (:time-scale w)))
          (is (same? (get tw "solver_iterations") (:num-solver-iterations w)))
          (is (same? (get tw "substeps_per_frame") (:steps-per-second w)))
          (is (same? (get tw "effector_gravity") (:effector-gravity w)))
          (is (every? true? (map same? (get o "gravity") (:gravity w))))
          (is (= (get o "use_gravity") (:use-gravity w)))
          (is (every? true? (map same? [0 -9.81 0] (let [g (bp/gravity w)] [(.x g) (.y g) (.z g)])))))))))

(defn by-name [^Node root name]
  (first (filter #(and (instance? Node %) (= name (.getName ^Spatial %))) (util/node-seq root))))

(defn control ^RigidBodyControl [root name]
  (.getControl (bp/body-spatial (by-name root name)) RigidBodyControl))

(deftest the-loader-attaches-physics
  (let [^Node root (blender/load-blender-model (fixture "b50"))]
    (is (= "HINGE" (:type (bp/rigid-body-constraint (by-name root "hinge-joint")))))
    (is (= ["hinge-a" "hinge-b"] ((juxt :ob1 :ob2) (bp/rigid-body-constraint (by-name root "hinge-joint")))))
    (is (= "MESH" (:shape (bp/rigid-body (by-name root "hinge-b")))))
    (is (nil? (bp/rigid-body (by-name root "seg-1"))))
    (testing "a Geometry answers for its object"
      (is (= "ACTIVE" (:type (bp/rigid-body (bp/body-spatial (by-name root "ball")))))))
    (testing "the settings are the reader's own data, unconverted"
      (let [{:keys [file scene-data]} (blender/read-blend (fixture "b50"))
            ob (some #(when (= "hinge-joint" (file/id-name %)) %)
                     (scene/scene-objects file (scene/current-scene file)))]
        (is (= (physics/rigid-body-constraint file ob)
               (bp/rigid-body-constraint (by-name root "hinge-joint"))))
        (is (= (:rigid-body-world scene-data) (bp/world-settings root)))))
    (testing "the scene's Rigid Body World is found from the root and from any object"
      (is (= 10 (:steps-per-second (bp/world-settings root))))
      (is (identical? (bp/world-settings root) (bp/world-settings (by-name root "ball"))))
      (let [g (bp/gravity (bp/world-settings root))]
        (is (every? true? (map same? [0 -9.81 0] [(.x g) (.y g) (.z g)])))))
    (testing "clones share the settings, which cannot change"
      (doseq [^Node copy [(.clone root false) (.deepClone root)]]
        (is (identical? (bp/rigid-body (by-name root "hinge-b"))
                        (bp/rigid-body (by-name copy "hinge-b"))))
        (is (= (bp/world-settings root) (bp/world-settings copy)))))))

(def joint-classes
  {"FIXED" MeteredSixDofJoint "POINT" MeteredSixDofJoint "GENERIC" MeteredSixDofJoint
   "GENERIC_SPRING" MeteredSixDofJoint "MOTOR" MeteredSixDofJoint "HINGE" FrameHingeJoint "SLIDER" SliderJoint "PISTON" SliderJoint})

(def shape-classes
  {"BOX" "BoxCollisionShape" "SPHERE" "SphereCollisionShape" "CAPSULE" "CapsuleCollisionShape"
   "CYLINDER" "CylinderCollisionShape" "CONE" "ConeCollisionShape"
   "CONVEX_HULL" "HullCollisionShape" "MESH" #{"GImpactCollisionShape" "MeshCollisionShape"}})

(deftest builds-what-blender-says
  (doseq [v versions]
    (testing v
      (let [o (oracle v)
            {:keys [creature bodies joints warnings]} (bp/build! (bp/load-creature (fixture v)))
            joints (into {} (map (juxt :object identity)) joints)
            theirs (into {} (map (juxt #(get % "name") identity)) (get o "objects"))]
        (testing "every constraint type is there"
          (is (= #{"FIXED" "POINT" "HINGE" "SLIDER" "PISTON" "GENERIC" "GENERIC_SPRING" "MOTOR"}
                 (set (map :type (vals joints))))))
        (doseq [[name t] theirs
                :let [rb (get t "rigid_body")
                      rbc (get t "rigid_body_constraint")]]
          (testing name
            (when rb
              (let [c (control creature name)
                    shape (.getSimpleName (class (.getCollisionShape c)))
                    want (shape-classes (get rb "collision_shape"))]
                (is (if (set? want) (contains? want shape) (= want shape)))
                (is (same? (if (= "ACTIVE" (get rb "type")) (get rb "mass") 0.0) (.getMass c)))
                (is (same? (get rb "friction") (.getFriction c)))
                (is (same? (get rb "restitution") (.getRestitution c)))
                (is (= (boolean (get rb "kinematic")) (.isKinematic c)))))
            (when rbc
              (let [{:keys [joint type] [a b] :bodies} (joints name)]
                (is (= (get rbc "type") type))
                (is (instance? (joint-classes type) joint))
                (is (= [(get rbc "object1") (get rbc "object2")] [a b]))
                (is (identical? (.getBodyA joint) (control creature a)))
                (is (identical? (.getBodyB joint) (control creature b)))
                (is (= (not (get rbc "disable_collisions")) (cortex.engine/collide-linked? joint)))
                (when (and (= "HINGE" type) (get rbc "use_limit_ang_z"))
                  (is (same? (bp/hinge-limit (get rbc "limit_ang_z_lower"))
                             (.getLowerLimit ^FrameHingeJoint joint)))
                  (is (same? (bp/hinge-limit (get rbc "limit_ang_z_upper"))
                             (.getUpperLimit ^FrameHingeJoint joint))))
                (when (#{"SLIDER" "PISTON"} type)
                  (is (same? (get rbc "limit_lin_x_lower") (.getLowerLinLimit ^SliderJoint joint)))
                  (is (same? (get rbc "limit_lin_x_upper") (.getUpperLinLimit ^SliderJoint joint))))
                (when (= "MOTOR" type)
                  (let [m (.getRotationalLimitMotor ^MeteredSixDofJoint joint 0)]
                    (is (= (get rbc "use_motor_ang") (.isEnableMotor m)))
                    (is (same? (get rbc "motor_ang_target_velocity") (.getTargetVelocity m)))
                    (is (same? (get rbc "motor_ang_max_impulse") (.getMaxMotorForce m)))))
                (when (= "GENERIC_SPRING" type)
                  (is (= [{:angular? false :axis 2 :stiffness 50.0 :damping 2.0}
                          {:angular? true :axis 0 :stiffness 5.0 :damping 0.5}]
                         (:springs (joints name)))))))))
        (testing "what jBullet cannot do is said, not dropped"
          (is (some #(re-find #"hinge-joint.*solver iterations.*30" %) warnings))
          (is (some #(re-find #"\"lift\" is Animated" %) warnings)))
        (testing "a breakable joint is made with its threshold"
          (is (= 50.0 (:breaking-threshold (joints "generic-joint")))))
        (testing "the custom-property joint in the same file is made too"
          (let [segment (control creature "seg-1")]
            (is (= 1 (count (cortex.engine/joints segment))))
            (is (identical? (control creature "seg-2")
                            (.getBodyB ^com.jme3.bullet.joints.PhysicsJoint (first (cortex.engine/joints segment)))))))))))

(defn- every-frame!
  "Run (f frame) at the start of every frame of world `w`."
  [w f]
  (let [frame (atom 0)]
    (.attach (.getStateManager w)
             (proxy [AbstractAppState] []
               (update [_] (f (swap! frame inc)))))
    w))

(defn- turn
  "The rotation that takes `from` to `to`, as [angle about `axis` (right
  handed), angle of what is left]."
  [^Quaternion from ^Quaternion to ^Vector3f axis]
  (let [q (.mult to (.inverse from))
        ^com.jme3.math.Quaternion q (if (neg? (.getW q)) (.negate q) q)
        v (Vector3f. (.getX q) (.getY q) (.getZ q))
        about (* 2 (Math/atan2 (.dot v axis) (.getW q)))
        rest (.subtract v (.mult axis (.dot v axis)))]
    [about (* 2 (Math/asin (min 1.0 (.length rest))))]))

(def sim-bodies
  "The active bodies whose resting places Blender's own simulation gives."
  ["fixed-b" "hinge-b" "slider-b" "piston-b" "generic-b" "spring-b" "ball"])

(defn- simulate
  "Build the physics fixture of version `v`, drop it under gravity for
  `frames` frames of 1/60 s, and measure every frame. Returns, per
  measure, all its values."
  [v frames]
  (let [{:keys [creature joints]} (bp/build! (bp/load-creature (fixture v)))
        joint (into {} (map (juxt :object :joint)) joints)
        c (partial control creature)
        start (into {} (for [n ["fixed-b" "hinge-b" "slider-b" "piston-b" "generic-b" "spring-b"]]
                         [n [(.getPhysicsLocation (c n)) (.getPhysicsRotation (c n))]]))
        axis (fn [joint-name col] (.getColumn (bp/constraint-frame (by-name creature joint-name)) (int col)))
        hinge-axis (axis "hinge-joint" 2)
        generic-axis (axis "generic-joint" 2)
        slider-axis (axis "slider-joint" 0)
        piston-axis (axis "piston-joint" 0)
        fixed-rel (fn [] (let [a (c "fixed-a") b (c "fixed-b")]
                           [(.mult (.inverse (.getPhysicsRotation a))
                                   (.subtract (.getPhysicsLocation b) (.getPhysicsLocation a)))
                            (.mult (.inverse (.getPhysicsRotation a)) (.getPhysicsRotation b))]))
        [fixed-p0 fixed-q0] (fixed-rel)
        moved (fn [n] (.subtract (.getPhysicsLocation (c n)) (first (start n))))
        off-axis (fn [n ^Vector3f ax] (let [d (moved n)] (.length (.subtract d (.mult ax (.dot d ax))))))
        seen (atom {})
        note! (fn [k x] (swap! seen update k (fnil conj []) x))
        seam (let [p (.getWorldTranslation (by-name creature "point-joint"))]
               {:a (c "point-a") :b (c "point-b")
                :pa (body/pivot (c "point-a") p) :pb (body/pivot (c "point-b") p)})
        w (world/world (util/nodify [creature]) {}
                       #(world/set-gravity % (Vector3f. 0 -9.81 0)) world/no-op)]
    (every-frame!
     w (fn [_]
         (let [[about rest] (turn (second (start "hinge-b")) (.getPhysicsRotation (c "hinge-b")) hinge-axis)]
           (note! :hinge (- about))
           (note! :hinge-bullet (.getHingeAngle ^FrameHingeJoint (joint "hinge-joint")))
           (note! :hinge-off rest))
         (let [[about rest] (turn (second (start "generic-b")) (.getPhysicsRotation (c "generic-b")) generic-axis)]
           (note! :generic about)
           (note! :generic-off rest))
         (let [[p q] (fixed-rel)]
           (note! :fixed-move (.distance ^Vector3f p fixed-p0))
           (note! :fixed-turn (second (turn fixed-q0 q Vector3f/UNIT_X)))
           (note! :fixed-turn-x (Math/abs (double (first (turn fixed-q0 q Vector3f/UNIT_X))))))
         (note! :slider (.dot (moved "slider-b") slider-axis))
         (note! :slider-off (off-axis "slider-b" slider-axis))
         (note! :slider-turn (reduce + (map #(Math/abs (double %))
                                            (turn (second (start "slider-b"))
                                                  (.getPhysicsRotation (c "slider-b")) slider-axis))))
         (note! :piston (.dot (moved "piston-b") piston-axis))
         (note! :piston-off (off-axis "piston-b" piston-axis))
         (note! :spring (.y (moved "spring-b")))
         (note! :point-gap (let [{:keys [a b pa pb]} seam]
                             (.distance (body/pivot-in-world a pa) (body/pivot-in-world b pb))))
         (note! :motor-spin (.y (.getAngularVelocity (c "motor-b"))))
         (note! :ball (.y (.getPhysicsLocation (c "ball"))))))
    (world/run-world! w frames)
    (assoc @seen :final (into {} (for [n sim-bodies]
                                   (let [p (.getPhysicsLocation (c n))] [n [(.x p) (.y p) (.z p)]]))))))

(def ^:private simulated
  "`simulate`, run once per version and length for all the tests that
  measure it."
  (memoize simulate))

(defn- within?
  "Do all of `xs` lie in [lo, hi]? (Checked on the extremes, so that a
  failure prints two numbers, not a whole run.)"
  [lo hi xs]
  (<= lo (apply min xs) (apply max xs) hi))

(deftest the-creature-moves-as-its-joints-allow
  (doseq [v ["b34" "b50"]]
    (testing v
      (let [m (simulated v 240)
            last-of #(peek (m %))
            tol 0.04]
        (testing "HINGE: about its axis only, within [-0.5, 0.7], resting at 0.7"
          (is (within? (- -0.5 tol) (+ 0.7 tol) (m :hinge)))
          (is (< (Math/abs (- 0.7 (last-of :hinge))) 0.005))
          (is (< (apply max (m :hinge-off)) 0.01))
          (is (< (Math/abs (- (bp/hinge-limit (last-of :hinge)) (last-of :hinge-bullet))) 0.001)))
        (testing "FIXED: the pair keeps its shape"
          (is (< (apply max (m :fixed-move)) 0.005))
          (is (< (apply max (concat (m :fixed-turn) (m :fixed-turn-x))) 0.005)))
        (testing "SLIDER: along its axis only, within [-0.3, 0.8], resting at 0.8"
          (is (< (apply max (m :slider-off)) 0.005))
          (is (< (apply max (m :slider-turn)) 0.005))
          (is (within? (- -0.3 tol) (+ 0.8 tol) (m :slider)))
          (is (< (Math/abs (- 0.8 (last-of :slider))) tol)))
        (testing "PISTON: along its axis only, within [-0.2, 0.6]"
          (is (< (apply max (m :piston-off)) 0.005))
          (is (within? (- -0.2 tol) (+ 0.6 tol) (m :piston))))
        (testing "GENERIC: about its Z only, within [-0.3, 0.3], resting at -0.3"
          (is (within? (- -0.3 tol) (+ 0.3 tol) (m :generic)))
          (is (< (Math/abs (- -0.3 (last-of :generic))) tol))
          (is (< (apply max (m :generic-off)) 0.01)))
        (testing "POINT: the two sides stay together"
          (is (< (apply max (m :point-gap)) 0.02)))
        (testing "GENERIC_SPRING: hangs where the spring holds its weight (m g / k = 0.196)"
          (is (< (Math/abs (- -0.196 (last-of :spring))) 0.03))
          (is (> (apply min (m :spring)) -1.02)))
        (testing "MOTOR: spins its hinge at the target 2 rad/s"
          (is (< (Math/abs (- 2.0 (Math/abs (double (last-of :motor-spin))))) 0.1)))
        (testing "an active sphere comes to rest on the passive MESH ground"
          (is (< (Math/abs (- 0.44 (last-of :ball))) 0.02)))))))

(defn- edit!
  "Change the Blender physics data `key` of object `name` in `creature`
  with (f settings), settings the reader's map with keyword keys."
  [creature name ^String key f]
  (let [^Node n (by-name creature name)]
    (.setUserData n key (f (.getUserData n key)))
    creature))

(defn- build-error
  "The message of the ex-info building `creature` throws, or :no-error.
  Anything but an ex-info fails the test."
  [creature]
  (try (bp/build! creature) :no-error
       (catch clojure.lang.ExceptionInfo e (ex-message e))))

(deftest bad-constraints-are-named-errors
  (let [fresh #(bp/load-creature (fixture "b50"))
        con physics/constraint-key
        rb physics/rigid-body-key]
    (is (re-find #"\"point-joint\".*second object \(ob2\) \"nobody\" is not a rigid body"
                 (build-error (edit! (fresh) "point-joint" con #(assoc % :ob2 "nobody")))))
    (is (re-find #"\"hinge-joint\".*first object \(ob1\) is not set"
                 (build-error (edit! (fresh) "hinge-joint" con #(dissoc % :ob1)))))
    (is (re-find #"\"slider-joint\".*jBullet cannot build constraint type \"UNKNOWN\" \(code 4\)"
                 (build-error (edit! (fresh) "slider-joint" con #(assoc % :type "UNKNOWN" :type-code 4)))))
    (is (re-find #"\"fixed-joint\".*joins \"fixed-a\" to itself"
                 (build-error (edit! (fresh) "fixed-joint" con #(assoc % :ob2 "fixed-a")))))
    (is (re-find #"\"generic-joint\".*limit_ang_z_upper must be a finite number"
                 (build-error (edit! (fresh) "generic-joint" con #(assoc % :limit-ang-z-upper Float/NaN)))))
    (is (re-find #"rigid body \"point-b\".*mass must be a finite number, not \"heavy\""
                 (build-error (edit! (fresh) "point-b" rb #(assoc % :mass "heavy")))))
    (is (re-find #"rigid body \"ball\".*mass must not be negative"
                 (build-error (edit! (fresh) "ball" rb #(assoc % :mass (float -1))))))
    (is (re-find #"rigid body \"ball\".*unknown collision shape"
                 (build-error (edit! (fresh) "ball" rb #(assoc % :shape "UNKNOWN" :shape-code 9)))))
    (testing "a disabled constraint makes no joint, and says so"
      (let [{:keys [joints warnings]} (bp/build! (edit! (fresh) "point-joint" con #(assoc % :enabled false)))]
        (is (nil? (:joint (first (filter #(= "point-joint" (:object %)) joints)))))
        (is (some #(re-find #"point-joint.*disabled" %) warnings))))
    (testing "any one number made NaN, infinite or huge ends in a joint or a named error"
      (doseq [[obj k x] [["hinge-joint" :limit-ang-z-lower Float/NaN]
                         ["spring-joint" :spring-stiffness-z Float/POSITIVE_INFINITY]
                         ["motor-joint" :motor-ang-target-velocity (float 1e30)]
                         ["slider-b" :friction Float/NaN]
                         ["piston-b" :lin-damping (float 1e30)]
                         ["spring-b" :margin Float/NEGATIVE_INFINITY]]]
        (let [key (if (re-find #"joint" obj) con rb)
              result (build-error (edit! (fresh) obj key #(assoc % k x)))]
          (is (or (= :no-error result) (re-find (re-pattern (str "\"" obj "\"")) result))
              (str obj " " k " " x)))))))

(deftest one-file-two-ways
  (testing "cortex.body alone builds the custom-property joint of a Physics-tab file"
    (let [creature (body/body! (bp/load-creature (fixture "b34")))
          seg (control creature "seg-1")]
      (is (= 1 (count (cortex.engine/joints seg))))))
  (testing "a Physics-tab file without custom joints needs no \"joints\" empty"
    (let [creature (bp/load-creature (fixture "b34"))
          joints (by-name creature "joints")]
      (.removeFromParent joints)
      (.removeFromParent (by-name creature "seg-1"))
      (.removeFromParent (by-name creature "seg-2"))
      (is (= 9 (count (:joints (bp/build! creature)))))))
  (testing "physics-body! returns the creature and keeps the warnings"
    (let [creature (bp/physics-body! (bp/load-creature (fixture "b50")))]
      (is (instance? Node creature))
      (is (= 2 (count (bp/warnings creature)))))))

(defn- blender-sim
  "What Blender's own simulation of the physics fixture of version `v`
  says (scripts/blender/simulate_physics.py): each body's place in the
  last frame (jME axes), and the motor body's spin about the vertical
  over the last frame, in rad/s."
  [v]
  (let [sim (read-json (slurp (str "test/fixtures/blend/" v "/physics_sim.json")))
        fps (get sim "fps")
        at (fn [n i] (get-in sim ["objects" n i]))
        place (fn [m] (let [[x y z] (map #(nth % 3) (take 3 m))] [x z (- y)]))
        yaw (fn [m] (Math/atan2 (get-in m [1 0]) (get-in m [0 0])))]
    {:final (into {} (for [n sim-bodies] [n (place (at n 2))]))
     :motor-spin (* fps (- (yaw (at "motor-b" 2)) (yaw (at "motor-b" 1))))}))

(deftest agrees-with-blenders-own-simulation
  (doseq [v ["b34" "b50"]]
    (testing v
      (let [ours (simulated v 240)
            theirs (blender-sim v)]
        (testing "after 4 s every jointed body rests where Blender's does"
          (doseq [n (remove #{"ball"} sim-bodies)]
            (is (< (apply max (map #(Math/abs (- (double %1) (double %2)))
                                   (get-in ours [:final n]) (get-in theirs [:final n])))
                   0.01)
                n)))
        (testing "the motor turns the same way, as fast"
          (is (< (Math/abs (- (:motor-spin theirs) (peek (:motor-spin ours)))) 0.05)))
        (testing "the ball rests on the MESH ground one collision margin (0.04) higher than in Blender"
          (is (< (Math/abs (- (+ 0.04 (second (get-in theirs [:final "ball"])))
                              (second (get-in ours [:final "ball"]))))
                 0.005)))))))
