;; Generated from org/body.org by lein tangle: edit the chapter, not this file.
(ns cortex.joint
  "Joints: a designer's joint description read safely as data, checked,
  and made into a Bullet joint by the `joint-dispatch` multimethod.

  Entry points: `read-description`, `read-joint`, `joint-description`
  (a marker's, read and checked), `description-data`, `joint-dispatch`
  (add joint types with defmethod), `joint-types`, `joint-keys`,
  `check-keys`, `build-joint!`, `connect`, `pivot`, `pivot-in-world`,
  `joint-gap`, `body-frame`, `cone-engine-angles`,
  `jbullet-hinge-limits`."
  (:require [clojure.edn :as edn]
            [clojure.string :as str]
            [cortex.engine :as engine]
            [cortex.projection :as projection]
            [cortex.segment :as segment]
            [cortex.sense :as sense]
            [cortex.util :as util])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints HingeJoint PhysicsJoint)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.math Matrix3f Quaternion Vector3f)
           (com.jme3.scene Spatial)))

(set! *warn-on-reflection* true)

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

(def angle-slack
  "How far past pi an angle limit may be and be taken as pi (written to
  a few places: 3.1416, or 3.141593 for 180 degrees)."
  0.001)

(defn- up-to-pi
  "Angle `v` as it is when within [`lo`, pi], one up to `angle-slack`
  past either end taken as that end, or nil."
  [v lo]
  (let [x (double v) lo (double lo)]
    (cond (<= lo x Math/PI) v
          (<= (- lo angle-slack) x (+ Math/PI angle-slack)) (max lo (min Math/PI x)))))

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

(defn- hinge-fields
  "A hinge description's {:axis Vector3f :limit [low high]}, checked."
  [constraints]
  (let [axis (axis-vector (get constraints :axis Vector3f/UNIT_X))
        limit (:limit constraints)]
    (when-not (and (vector? limit) (= 2 (count limit)) (every? util/finite? limit)
                   (<= (first limit) (second limit)))
      (throw (ex-info (str "hinge needs :limit [low high] with low <= high, not "
                           (pr-str limit))
                      {:limit limit})))
    (when-not (every? #(up-to-pi % (- Math/PI)) limit)
      (throw (angle-error "hinge :limit" limit "[-pi, pi]")))
    {:axis axis :limit (mapv #(up-to-pi % (- Math/PI)) limit)}))

(defmethod joint-dispatch :hinge
  [constraints control-a control-b pivot-a pivot-b ^Matrix3f rotation]
  (let [{:keys [^Vector3f axis limit]} (hinge-fields constraints)
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

(defn- cone-fields
  "A cone description's [limit-xz limit-xy twist], checked."
  [constraints]
  (let [xz (number-field constraints :limit-xz)
        xy (number-field constraints :limit-xy)
        twist (number-field constraints :twist)]
    (doseq [k [:limit-xz :limit-xy :twist]
            :when (not (up-to-pi (get constraints k) 0.0))]
      (throw (angle-error (str "cone " k) (get constraints k) "[0, pi]")))
    (mapv #(up-to-pi % 0.0) [xz xy twist])))

(defmethod joint-dispatch :cone
  [constraints control-a control-b pivot-a pivot-b ^Matrix3f rotation]
  (let [[xz xy twist] (cone-fields constraints)]
    (let [[^Matrix3f turn [t y z]] (cone-limits xz xy twist)
          frame (.mult rotation turn)]
      (-> (engine/six-dof-joint control-a control-b pivot-a pivot-b
                                (body-frame control-a frame) (body-frame control-b frame) [t y z])
          (hold-limits! control-a control-b rotation
                        {:twist (double twist) :limit-xz (double xz) :limit-xy (double xy)}
                        {:type :cone :turn (doto (Quaternion.) (.fromRotationMatrix turn))
                         :limits [t y z]})))))

(defn spring-fields
  "A spring description's {:stiffness :damping :limit-xz :limit-xy
  :twist}, checked, the defaults filled in: what the joint is built
  from, and what the exporter writes (see the export chapter)."
  [constraints]
  (let [field (fn [k default]
                (let [v (get constraints k default)]
                  (if (and (util/finite? v) (<= 0.0 (double v)))
                    (double v)
                    (throw (ex-info (str "spring joint needs a number >= 0 for " k ", not " (pr-str v))
                                    {:key k :value v})))))
        stiffness (field :stiffness nil)
        damping (field :damping 0.0)
        free (fn [k] (let [v (field k Math/PI)]
                       (or (up-to-pi v 0.0) (throw (angle-error (str "spring " k) v "[0, pi]")))))]
    {:stiffness stiffness :damping damping
     :limit-xz (free :limit-xz) :limit-xy (free :limit-xy) :twist (free :twist)}))

(defmethod joint-dispatch :spring
  [constraints control-a control-b pivot-a pivot-b ^Matrix3f rotation]
  (let [{:keys [stiffness damping] :as f} (spring-fields constraints)
        [^Matrix3f turn limits] (cone-limits (:limit-xz f) (:limit-xy f) (:twist f))
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

(defn- in-joint
  "Run `f`; an ex-info it throws comes out prefixed with joint `name`."
  [name f]
  (try (f)
       (catch clojure.lang.ExceptionInfo e
         (throw (ex-info (str "joint " (pr-str name) ": " (ex-message e))
                         (assoc (ex-data e) :joint name) e)))))

(defmulti ^:private check-fields
  "Check a built-in joint type's fields as its `joint-dispatch` method
  will read them; a type added with defmethod is checked when built."
  :type)

(defmethod check-fields :default [_] nil)
(defmethod check-fields :hinge [d] (hinge-fields d))
(defmethod check-fields :cone [d] (cone-fields d))
(defmethod check-fields :spring [d] (spring-fields d))

(defn description-data
  "Joint description `d` as plain data (see cortex.segment/plain): a
  (Vector3f. x y z) becomes [x y z], doubles of its floats. The
  built-in joints read either form alike."
  [d]
  (segment/plain d))

(defn joint-description
  "The description of joint empty `marker`, read (see `read-joint`) and
  checked: unknown keys, and the fields of the built-in types, as their
  `joint-dispatch` methods read them. Errors name the joint."
  [^Spatial marker]
  (in-joint (.getName marker)
            (fn []
              (let [text (sense/meta-data marker "joint")
                    _ (when (nil? text)
                        (throw (ex-info "it has no joint property" {})))
                    d (check-keys (read-joint text))]
                (check-fields d)
                d))))

(defn build-joint!
  "The Bullet joint between the rigid bodies `control-a` and
  `control-b` that joint `p` of a plan holds: its :description (see
  `joint-dispatch`), at :pivot [x y z] turned by :rotation [x y z w],
  both in the world. The two bodies no longer collide with each other:
  the joint and its limits keep them apart. Errors name the joint."
  [^RigidBodyControl control-a ^RigidBodyControl control-b {:keys [name description pivot rotation]}]
  (in-joint name
            (fn []
              (let [center (util/vec3 pivot)
                    j (joint-dispatch description control-a control-b
                                      (cortex.joint/pivot control-a center)
                                      (cortex.joint/pivot control-b center)
                                      (.toRotationMatrix (segment/quaternion rotation)))]
                (engine/collide-linked! j false)
                ;; every joint counts for projection's tree, limited or not
                (when-not (projection/held? j) (projection/hold! j nil))
                j))))

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
  (build-joint! (.getControl obj-a RigidBodyControl) (.getControl obj-b RigidBodyControl)
                {:name (.getName joint)
                 :description (description-data (joint-description joint))
                 :pivot (segment/vector-data (.getWorldTranslation joint))
                 :rotation (segment/quaternion-data (.getWorldRotation joint))}))
