;; Generated from org/projection.org by lein tangle: edit the chapter, not this file.
(ns cortex.projection
  "Joints put back within their limits after every Bullet step, by
  turning the segments beyond them about their pivots (joint projection,
  as game engines call it; see org/projection.org).

  Entry points: `hold!` (the body chapter registers a joint and its
  limits; `held?`, `spec`), `install!` (a space projects after each of its steps),
  `enable!` (turn it on or off for one space), `project!` (one pass,
  now), `plan` (the tree a space's joints form), `hinge-angle`,
  `euler-angles` and `from-euler` (the angles a joint is held in),
  `slack` (how far past a limit is let be)."
  (:require [cortex.engine :as engine])
  (:import (com.jme3.bullet PhysicsSpace PhysicsTickListener)
           (com.jme3.bullet.joints PhysicsJoint)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.math Matrix3f Quaternion Vector3f)
           (java.util Collections IdentityHashMap Map WeakHashMap)
           (java.util.concurrent.atomic AtomicLong)))

(set! *warn-on-reflection* true)

(defn- wrap
  "The angle `a` brought into (-pi, pi]."
  ^double [^double a]
  (- a (* 2.0 Math/PI (Math/floor (/ (+ a Math/PI) (* 2.0 Math/PI))))))

(defn hinge-angle
  "The turn, radians in (-pi, pi], of the rotation `q` about the unit
  vector `axis` (both in the joint's frame)."
  ^double [^Quaternion q ^Vector3f axis]
  (wrap (* 2.0 (Math/atan2 (+ (* (.getX q) (.x axis)) (* (.getY q) (.y axis)) (* (.getZ q) (.z axis)))
                           (.getW q)))))

(defn euler-angles
  "The three angles [x y z] a cone's engine holds when its relative
  rotation is `q` and its frame is turned by `turn` (Quaternions): the
  Euler angles of the inverse of turn^-1 q turn, m^-1 = Rx Ry Rz."
  [^Quaternion q ^Quaternion turn]
  (let [^Matrix3f m (.toRotationMatrix (.mult (.mult (.inverse turn) q) turn))]
    [(Math/atan2 (- (.get m 2 1)) (.get m 2 2))
     (Math/asin (max -1.0 (min 1.0 (double (.get m 2 0)))))
     (Math/atan2 (- (.get m 1 0)) (.get m 0 0))]))

(defn- about
  ^Quaternion [angle ^Vector3f axis]
  (.fromAngleAxis (Quaternion.) (float angle) axis))

(defn from-euler
  "The relative rotation whose `euler-angles` under `turn` are [x y z]."
  ^Quaternion [[x y z] ^Quaternion turn]
  (let [m-inverse (.mult (.mult (about x Vector3f/UNIT_X) (about y Vector3f/UNIT_Y))
                         (about z Vector3f/UNIT_Z))]
    (.mult (.mult turn (.inverse m-inverse)) (.inverse turn))))

(def slack
  "By joint type, [trigger keep] in radians: a joint further past a
  limit than its trigger is put back to its keep past it."
  {:hinge [0.045 0.035]
   :cone [0.09 0.07]})

(defn- clamp ^double [^double x ^double lo ^double hi] (max lo (min hi x)))

(defn- past?
  "Whether any of `angles` is further than `margin` past its limit of
  `limits` (each angle within [-limit limit])."
  [angles limits ^double margin]
  (loop [i 0]
    (and (< i 3)
         (or (> (Math/abs (double (nth angles i))) (+ (double (nth limits i)) margin))
             (recur (inc i))))))

(defn corrected
  "The relative rotation a joint of limits `spec` (see `hold!`) should
  have in place of `q`, or nil when `q` is within the trigger of its
  limits."
  [{:keys [type axis limit turn limits]} ^Quaternion q]
  (let [s (slack type)
        trigger (double (nth s 0)) keep (double (nth s 1))]
    (case type
      :hinge (let [lo (double (nth limit 0)) hi (double (nth limit 1))
                   a (hinge-angle q axis)]
               (when (or (< a (- lo trigger)) (> a (+ hi trigger)))
                 (.mult (about (- (clamp a (- lo keep) (+ hi keep)) a) axis) q)))
      :cone (let [angles (euler-angles q turn)]
              (when (past? angles limits trigger)
                (from-euler (mapv (fn [a l] (let [l (+ (double l) keep)] (clamp a (- l) l)))
                                  angles limits)
                            turn))))))

(def ^:private ^Map held
  "Each joint `hold!` was given (weakly held) -> {:seq n :spec spec}."
  (Collections/synchronizedMap (WeakHashMap.)))

(def ^:private ^AtomicLong joint-count (AtomicLong.))

(defn- quaternion ^Quaternion [q]
  (if (instance? Quaternion q)
    q
    (let [[x y z w] q] (Quaternion. (float x) (float y) (float z) (float w)))))

(defn hold!
  "Register `joint`, made by the body chapter, for projection: `spec`
  nil for a joint without limits, else the joint's frame in each body,
  :frame-a and :frame-b (Quaternions or [x y z w], jME's axes), and for
  a hinge :type :hinge, its :axis (in the joint's frame) and :limit
  [lo hi], for a cone :type :cone, the :turn of the engine's frame
  (a Quaternion) and the :limits [x y z] of its three angles. Returns
  `joint`."
  [joint spec]
  (.put held joint {:seq (.incrementAndGet joint-count)
                    :spec (when spec
                            (cond-> (assoc spec
                                           :frame-a (quaternion (:frame-a spec))
                                           :frame-b (quaternion (:frame-b spec)))
                              (:axis spec) (update :axis #(let [[x y z] %]
                                                            (.normalizeLocal (Vector3f. (float x) (float y) (float z)))))
                              (:turn spec) (update :turn quaternion)))})
  joint)

(defn held?
  "Whether `joint` was registered with `hold!`."
  [joint]
  (.containsKey held joint))

(defn spec
  "The limits `hold!` registered `joint` with, or nil."
  [joint]
  (:spec (.get held joint)))

(defn- weight
  "A body's mass for choosing roots; a static body outweighs all."
  ^double [^PhysicsRigidBody b]
  (let [m (double (.getMass b))]
    (if (pos? m) m Double/POSITIVE_INFINITY)))

(defn plan
  "The order `project!` puts back the registered joints of `joints` (a
  collection of PhysicsJoints): a vector of {:joint j :spec s :far-b?
  (whether body B is the far one) :pivot (the joint's point in the far
  body's frame) :subtree [bodies beyond the joint, the far one first]},
  joints without limits left out."
  [joints]
  (let [js (->> joints
                (keep (fn [^PhysicsJoint j] (when-let [h (.get held j)] (assoc h :joint j))))
                (sort-by :seq)
                vec)
        ends (fn [{:keys [^PhysicsJoint joint]}] [(.getBodyA joint) (.getBodyB joint)])
        ;; bodies in the order they were first joined
        bodies (distinct (mapcat ends js))
        order (into {} (map-indexed (fn [i b] [b i])) bodies)
        neighbours (reduce (fn [m j] (let [[a b] (ends j)]
                                       (-> m (update a (fnil conj []) [j b]) (update b (fnil conj []) [j a]))))
                           {} js)
        subtree (fn subtree [b children]
                  (into [b] (mapcat #(subtree % children)) (children b)))]
    (loop [left (sort-by (juxt #(- (weight %)) order) bodies)
           seen #{}
           out []]
      (if-let [root (first (remove seen left))]
        ;; breadth first from root: [far-body joint near-body] in visit order
        (let [[visited edges]
              (loop [queue [root] visited #{root} edges []]
                (if-let [b (first queue)]
                  (let [fresh (for [[j other] (neighbours b) :when (not (visited other))] [other j b])
                        fresh (vec (vals (into (sorted-map) (map (fn [[o :as e]] [(order o) e])) fresh)))]
                    (recur (into (subvec queue 1) (map first) fresh)
                           (into visited (map first) fresh)
                           (into edges fresh)))
                  [visited edges]))
              children (reduce (fn [m [far _ near]] (update m near (fnil conj []) far)) {} edges)]
          (recur left (into seen visited)
                 (into out (for [[far {:keys [^PhysicsJoint joint spec]} _] edges
                                 :when spec
                                 :let [far-b? (identical? far (.getBodyB joint))
                                       [pa pb] (engine/pivots joint)]]
                             {:joint joint :spec spec :far-b? far-b?
                              :pivot (if far-b? pb pa)
                              :subtree (subtree far children)}))))
        out))))

(defn- rotation ^Quaternion [^PhysicsRigidBody b] (.getPhysicsRotation b (Quaternion.)))

(defn- turn-about!
  "Turn every body of `bodies` by the world rotation `d` about the
  world point `centre`."
  [bodies ^Quaternion d ^Vector3f centre]
  (doseq [^PhysicsRigidBody b bodies]
    (let [p (.getPhysicsLocation b (Vector3f.))]
      ;; the turn first: Minie's setPhysicsLocation turns a moving body
      ;; back to where it was at the start of the step (measured)
      (.setPhysicsRotation b (.normalizeLocal (.mult d (rotation b))))
      (.setPhysicsLocation b (.addLocal (.mult d (.subtractLocal p centre)) centre)))))

(defn- project-joint!
  "Put the joint of plan entry `entry` back, if it is past its trigger;
  whether it was."
  [{:keys [^PhysicsJoint joint spec far-b? ^Vector3f pivot subtree]}]
  (let [^PhysicsRigidBody a (.getBodyA joint)
        ^PhysicsRigidBody b (.getBodyB joint)
        wa (.mult (rotation a) ^Quaternion (:frame-a spec))
        wb (.mult (rotation b) ^Quaternion (:frame-b spec))
        q (.mult (.inverse wa) wb)]
    (when-let [^Quaternion q' (corrected spec q)]
      (let [d (.mult (.mult (.mult wa q') (.inverse q)) (.inverse wa))
            ^PhysicsRigidBody far (if far-b? b a)
            centre (.add (.getPhysicsLocation far (Vector3f.)) (.mult (rotation far) pivot))]
        (turn-about! subtree (.normalizeLocal (if far-b? d (.inverse d))) centre)
        true))))

(defn- awake?
  "Whether either body of the joint of plan entry `entry` is awake: a
  joint between two sleeping bodies has not moved since it was last
  looked at."
  [{:keys [^PhysicsJoint joint]}]
  (or (.isActive ^PhysicsRigidBody (.getBodyA joint)) (.isActive ^PhysicsRigidBody (.getBodyB joint))))

(defn project!
  "Put back every joint of `plan` (see `plan`) that is past its
  trigger, from the root outwards, but those whose bodies both sleep.
  Returns how many were put back."
  ^long [plan]
  ;; after every substep: a loop over the vector, which boxes and
  ;; allocates nothing (a reduce made a closure and boxed the count)
  (let [^clojure.lang.IPersistentVector plan plan
        size (count plan)]
    (loop [i 0 n 0]
      (if (< i size)
        (let [entry (.nth plan i)]
          (recur (inc i) (if (and (awake? entry) (project-joint! entry)) (inc n) n)))
        n))))

(def ^:private ^Map spaces
  "Each space `install!` was given (weakly held) -> a volatile
  {:enabled? bool :seen IdentityHashMap :entries plan}."
  (Collections/synchronizedMap (WeakHashMap.)))

(defn- current-plan
  "The plan of `space`'s joints, made again when they have changed
  since `state` was last given one."
  [^PhysicsSpace space state]
  (let [joints (.getJointList space)
        {:keys [^Map seen entries]} @state]
    (if (and seen (== (count joints) (.size seen))
             ;; every substep: an iterator, not a closure and a seq
             (let [it (.iterator ^java.util.Collection joints)]
               (loop []
                 (cond (not (.hasNext it)) true
                       (.containsKey seen (.next it)) (recur)
                       :else false))))
      entries
      (let [seen (IdentityHashMap.)
            p (plan joints)]
        (doseq [j joints] (.put seen j true))
        (vswap! state assoc :seen seen :entries p)
        p))))

(defn install!
  "Make `space` put its registered joints back after each of its
  steps (`enable!` turns it off and on). Returns `space`."
  ^PhysicsSpace [^PhysicsSpace space]
  (let [state (volatile! {:enabled? true})]
    (.put spaces space state)
    (.addTickListener space (reify PhysicsTickListener
                              (prePhysicsTick [_ _ _])
                              (physicsTick [_ s _]
                                (when (:enabled? @state)
                                  (project! (current-plan s state)))))))
  space)

(defn enable!
  "Turn projection on or off (`on?`) for `space`, which `install!` was
  given. Returns `space`."
  [space on?]
  (if-let [state (.get spaces space)]
    (vswap! state assoc :enabled? (boolean on?))
    (throw (ex-info "this space projects no joints: cortex.projection/install! was not given it"
                    {:space space})))
  space)

(defn enabled?
  "Whether `space` puts its joints back after each step."
  [space]
  (boolean (some-> ^clojure.lang.Volatile (.get spaces space) deref :enabled?)))
