;; Generated from org/blender-scene.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender.rigid-body
  "Blender's own rigid body physics as data: the settings of the Physics
  tab's Rigid Body (RigidBodyOb), Rigid Body Constraint (RigidBodyCon)
  and the scene's Rigid Body World, read through the file's SDNA by
  field name, as maps with keyword keys (:lin-damping,
  :use-limit-ang-z, :ob1 ...). Codes and flags are those of Blender's
  DNA_rigidbody_types.h.

  Entry points: `rigid-body`, `rigid-body-constraint`,
  `rigid-body-world` (an object's or scene's settings as data),
  `user-data` (what the loader attaches to an object's Node), and the
  names of that user data: `rigid-body-key`, `constraint-key`,
  `world-key`."
  (:require [clojure.string :as str]
            [cortex.blender.file :as f]
            [cortex.sense :as sense]))

(set! *warn-on-reflection* true)

(def rigid-body-key
  "The user data under which an object's Node carries its rigid body
  settings (see `rigid-body`)."
  sense/rigid-body-key)

(def constraint-key
  "The user data under which an object's Node carries its rigid body
  constraint (see `rigid-body-constraint`)."
  sense/constraint-key)

(def world-key
  "The user data under which the scene's Node carries its Rigid Body
  World (see `rigid-body-world`)."
  sense/world-key)

(def body-types
  "eRigidBodyOb_Type: what part a rigid body plays."
  {0 "ACTIVE" 1 "PASSIVE"})

(def shapes
  "eRigidBody_Shape, named as Blender's Python API names them
  (RB_SHAPE_CONVEXH is CONVEX_HULL, RB_SHAPE_TRIMESH is MESH)."
  {0 "BOX" 1 "SPHERE" 2 "CAPSULE" 3 "CYLINDER" 4 "CONE" 5 "CONVEX_HULL"
   6 "MESH" 7 "COMPOUND"})

(def body-flags
  "The bits of eRigidBodyOb_Flag a body needs, by their Python names.
  :disabled is the inverse of the Physics tab's Dynamic checkbox."
  {:kinematic 0 :use-deactivation 3 :use-start-deactivated 4
   :disabled 5 :use-margin 6 :use-deform 7})

(def constraint-types
  "eRigidBodyCon_Type; codes 2, 4, 7 and 10 are unused by Blender."
  {0 "POINT" 1 "HINGE" 3 "SLIDER" 5 "GENERIC" 6 "GENERIC_SPRING"
   8 "FIXED" 9 "PISTON" 11 "MOTOR"})

(def spring-types
  "eRigidBodyCon_SpringType: Bullet's two spring constraints."
  {0 "SPRING1" 1 "SPRING2"})

(def constraint-flags
  "The bits of eRigidBodyCon_Flag, by their Python names."
  {:enabled 0 :disable-collisions 2 :use-breaking 3
   :use-override-solver-iterations 4
   :use-limit-lin-x 5 :use-limit-lin-y 6 :use-limit-lin-z 7
   :use-limit-ang-x 8 :use-limit-ang-y 9 :use-limit-ang-z 10
   :use-spring-x 11 :use-spring-y 12 :use-spring-z 13
   :use-motor-lin 14 :use-motor-ang 15
   :use-spring-ang-x 16 :use-spring-ang-y 17 :use-spring-ang-z 18})

(def body-fields
  "The RigidBodyOb number fields kept, by their DNA names."
  ["mass" "friction" "restitution" "margin" "lin_damping" "ang_damping"
   "lin_sleep_thresh" "ang_sleep_thresh" "col_groups" "mesh_source"])

(def constraint-fields
  "The RigidBodyCon number fields kept, by their DNA names."
  (concat ["num_solver_iterations" "breaking_threshold"
           "motor_lin_target_velocity" "motor_ang_target_velocity"
           "motor_lin_max_impulse" "motor_ang_max_impulse"]
          (for [k ["lin" "ang"] a ["x" "y" "z"] e ["lower" "upper"]]
            (str "limit_" k "_" a "_" e))
          (for [p ["spring_stiffness_" "spring_damping_"]
                a ["x" "y" "z" "ang_x" "ang_y" "ang_z"]]
            (str p a))))

(defn dna-key
  "The key a DNA field name has in the settings maps: \"lin_damping\"
  -> :lin-damping."
  [dna-name]
  (keyword (str/replace dna-name "_" "-")))

(defn- numbers
  "The fields `names` (DNA names) that struct `r` has, as `dna-key`
  -> value."
  [r names]
  (into {} (for [n names
                 :when (f/has-field? r n)
                 :let [v (f/fget r n)]
                 :when (number? v)]
             [(dna-key n) v])))

(defn flag-bits
  "Each key of `bits` (key -> bit number) with whether `flag` has
  that bit set."
  [flag bits]
  (into {} (for [[k b] bits] [k (bit-test (long flag) (long b))])))

(defn- code-name
  "The name `table` gives code `c`, or \"UNKNOWN\" when it has none
  (the code itself stays under its own key for error messages)."
  [table c]
  (get table (some-> c long) "UNKNOWN"))

(defn rigid-body
  "The rigid body settings of Object struct `ob` as a map with keyword
  keys, or nil when the object has no rigid body. :type and :shape are
  names (\"ACTIVE\", \"BOX\"), :type-code and :shape-code the numbers
  the file holds, :flag the raw flags, decoded into :kinematic,
  :disabled, :use-margin...; :mass, :friction, :lin-damping and the
  other numbers by their DNA names."
  [bf ob]
  (when-let [rb (f/deref-ptr bf (f/fget ob "rigidbody_object") "RigidBodyOb")]
    (let [flag (long (or (f/fget rb "flag") 0))
          type (f/fget rb "type")
          shape (f/fget rb "shape")]
      (merge (numbers rb body-fields)
             (flag-bits flag body-flags)
             {:type (code-name body-types type) :type-code (or type -1)
              :shape (code-name shapes shape) :shape-code (or shape -1)
              :flag flag}))))

(defn- object-name
  "The name of the Object pointer `ptr` points at, or nil."
  [bf ptr]
  (some-> (f/deref-ptr bf ptr "Object") f/id-name))

(defn rigid-body-constraint
  "The rigid body constraint of Object struct `ob` as a map with
  keyword keys, or nil when it has none: :type (a name) and
  :type-code, :ob1 and :ob2 (the names of the objects it joins; absent
  when the pointer is empty or dangling), :spring-type, the raw :flag
  and its bits (:enabled, :disable-collisions, :use-limit-ang-z...),
  and every limit, spring, motor and breaking number by its DNA name
  (:limit-ang-z-lower, :spring-stiffness-x ...)."
  [bf ob]
  (when-let [rbc (f/deref-ptr bf (f/fget ob "rigidbody_constraint") "RigidBodyCon")]
    (let [flag (long (or (f/fget rbc "flag") 0))
          type (f/fget rbc "type")
          ob1 (object-name bf (f/fget rbc "ob1"))
          ob2 (object-name bf (f/fget rbc "ob2"))]
      (cond-> (merge (numbers rbc constraint-fields)
                     (flag-bits flag constraint-flags)
                     {:type (code-name constraint-types type) :type-code (or type -1)
                      :spring-type (code-name spring-types (f/fget rbc "spring_type"))
                      :flag flag})
        ob1 (assoc :ob1 ob1)
        ob2 (assoc :ob2 ob2)))))

(defn user-data
  "What an object's Node carries of Blender's physics, by user data
  name: its `rigid-body` under `rigid-body-key` and its
  `rigid-body-constraint` under `constraint-key`, each present only
  when the object has one."
  [bf ob]
  (let [rb (rigid-body bf ob)
        rbc (rigid-body-constraint bf ob)]
    (cond-> {}
      rb (assoc rigid-body-key rb)
      rbc (assoc constraint-key rbc))))

(defn- collection-names
  "The names of the objects in collection (2.8+) or group (before 2.8)
  `c`, its child collections included, as Blender's
  FOREACH_COLLECTION_OBJECT_RECURSIVE visits them; each collection
  visited once."
  [bf c]
  (loop [stack (if c [c] []) seen #{} out []]
    (if-let [c (peek stack)]
      (let [stack (pop stack)]
        (if (seen (:offset c))
          (recur stack seen out)
          (let [obs (keep #(or (f/deref-ptr bf (f/fget % "ob") "Object")
                               (f/deref-ptr bf (f/fget % "object") "Object"))
                          (f/list-seq bf (f/fget c "gobject")))
                kids (keep #(f/deref-ptr bf (f/fget % "collection") "Collection")
                           (f/list-seq bf (f/fget c "children") "CollectionChild"))]
            (recur (into stack kids) (conj seen (:offset c)) (into out (map f/id-name obs))))))
      (vec (distinct out)))))

(defn- world-collection
  "The Collection (2.8+) or Group (before 2.8) that field `field` of
  RigidBodyWorld `w` points at, or nil."
  [bf w field]
  (let [p (f/fget w field)]
    (or (f/deref-ptr bf p "Collection") (f/deref-ptr bf p "Group"))))

(defn rigid-body-world
  "The Rigid Body World of Scene struct `sc` as a map with keyword
  keys, or nil when it has none: :time-scale, :steps-per-second (the
  substeps per frame in files from 2.91 on, steps per second before;
  files that use the newer DNA name: :substeps-per-frame),
  :num-solver-iterations, :flag with :muted and :use-split-impulse, and
  :effector-gravity (how much of the scene's gravity its bodies feel);
  the scene's own :gravity (Blender axes) and :use-gravity; :fps, the
  scene's frame rate; :file-version (the version of Blender that saved
  the file, 304 for 3.4); and which objects Blender simulates: the
  names of the objects in the world's collection (:collection-objects)
  and in its constraints collection (:constraint-objects), each nil
  when the world has no such collection."
  [bf sc]
  (when-let [w (f/deref-ptr bf (f/fget sc "rigidbody_world") "RigidBodyWorld")]
    (let [flag (long (or (f/fget w "flag") 0))
          ew (f/deref-ptr bf (f/fget w "effector_weights") "EffectorWeights")
          phys (f/fget sc "physics_settings")
          r (f/fget sc "r")
          group (world-collection bf w "group")
          constraints (world-collection bf w "constraints")]
      (merge (numbers w ["time_scale" "substeps_per_frame" "steps_per_second"
                         "num_solver_iterations"])
             {:flag flag
              :muted (bit-test flag 0)
              :use-split-impulse (bit-test flag 2)
              :effector-gravity (or (f/fget ew "global_gravity") 1.0)
              :file-version (:version bf)
              :collection-objects (when group (collection-names bf group))
              :constraint-objects (when constraints (collection-names bf constraints))}
             (when-let [fps (f/fget r "frs_sec")]
               {:fps (/ (double fps) (double (or (f/fget r "frs_sec_base") 1.0)))})
             (when-let [g (f/fget phys "gravity")]
               {:gravity g
                :use-gravity (bit-test (long (or (f/fget phys "flag") 1)) 0)})))))
