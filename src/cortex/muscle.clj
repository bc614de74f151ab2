;; Generated from org/muscle.org by lein tangle: edit the chapter, not this file.
(ns cortex.muscle
  "Muscles: torques at a creature's joints for the next physics step.

  Entry points: `actuate!` (apply a map of actions to a creature),
  `muscles` (what acting needs, per joint, worked out once), `efforts`
  (actions checked and turned into clamped torques, nothing applied),
  `apply-efforts!`, `default-strength`, `default-gains`, `clamp`.

    {\"knee\" 1.5}                torque about a hinge's axis, N.m
    {\"hip\" [0 0.3 0]}           torque in a cone or point joint's frame
    {\"knee\" {:target 0.4}}      PD towards a hinge angle, rad
    {\"hip\" {:target [0 0.2 0]}} PD towards a relative rotation vector
    (a :target map may give :kp and :kd for the step; a cone or point
    joint has a gain per axis of its frame, [x y z], or one for all)

  Vectors are in the joint empty's frame, Blender's axes, as
  cortex.proprioception reads them. A torque is internal: +t on the
  second segment, -t on the first. Every effort is clamped to the
  joint's strength. Bad actions are ex-infos naming the joint, raised
  before any torque is applied."
  (:require [clojure.string :as str]
            [cortex.engine :as engine]
            [cortex.proprioception :as p]
            [cortex.strength :as strength])
  (:import (com.jme3.bullet.joints PhysicsJoint)
           (com.jme3.math Vector3f)
           (com.jme3.scene Node)))

(set! *warn-on-reflection* true)

(def ^{:doc "The gravity, m/s^2, that default strengths are sized against
  (cortex.strength/gravity)."}
  gravity strength/gravity)

(def ^{:doc "The physics step the default gains are sized for, s
  (cortex.strength/step)."}
  step strength/step)

(def ^{:arglists '([loads]) :doc "cortex.strength/default-strength."}
  default-strength strength/default-strength)

(def ^{:arglists '([strength inertia own]) :doc "cortex.strength/default-gains."}
  default-gains strength/default-gains)

(defn- v3 [^Vector3f v] [(double (.x v)) (double (.y v)) (double (.z v))])

(defn- mass-of ^double [rb]
  (let [inv (engine/inverse-mass rb)]
    (if (zero? inv) 0.0 (/ 1.0 inv))))

(defn pivot-inertia
  "The moment of inertia of `rb` about the axis through `pivot` along
  the unit `axis`, both in the body's own frame (jME's axes): its own
  moment about a parallel axis through its centre of mass, plus m r^2.
  Infinite for a static body."
  ^double [rb axis pivot]
  (if (zero? (engine/inverse-mass rb))
    Double/POSITIVE_INFINITY
    (let [inv (engine/inverse-inertia rb)
          own-inverse (reduce + (map (fn [i a] (* (double i) (double a) (double a))) inv axis))
          own (if (pos? own-inverse) (/ 1.0 own-inverse) Double/POSITIVE_INFINITY)
          along (p/dot pivot axis)
          r2 (- (p/dot pivot pivot) (* along along))]
      (+ own (* (mass-of rb) r2)))))


(defn- given
  "The non-negative number the joint's description gives for `k`, or
  `default` (called) when it gives none."
  [{:keys [name record]} k default]
  (let [v (get-in record [:description k])]
    (cond (nil? v) (default)
          (and (number? v) (Double/isFinite (double v)) (not (neg? (double v)))) (double v)
          :else (throw (ex-info (str "joint " (pr-str name) ": " k " must be a finite,"
                                     " non-negative number, not " (pr-str v)
                                     "; change it in the joint empty's joint property")
                                {:joint name k v})))))

(defn- blender-order
  "Three per-axis values of a joint frame, given for jME's X, Y and Z,
  in the order of Blender's axes (X, Y, Z = jME's X, -Z, Y), the axes
  actions and errors are given in."
  [[x y z]]
  [x z y])

(defn muscle
  "What acting on the joint of proprioception sensor `sensor` needs:
  the sensor with :strength, :kp, :kd and :inertia; for a cone or point
  joint :kp, :kd and :inertia are [x y z], one per axis of the joint's
  frame in Blender's axes. `scale` (1 when not given) is how many times
  the creature's size its bodies were built (a simulation's :scale):
  lengths read from them count 1/scale, moments 1/scale^2, so that the
  muscle is the creature's own."
  ([sensor] (muscle sensor 1.0))
  ([{:keys [type axis frame-a frame-b rb-a rb-b record] :as sensor} scale]
   (let [^PhysicsJoint j (:physics-joint record)
         sc (double scale)
         [pa pb] (map v3 (engine/pivots j))
         strength (given sensor :strength
                         #(default-strength [[(mass-of rb-a) (/ (Math/sqrt (p/dot pa pa)) sc)]
                                             [(mass-of rb-b) (/ (Math/sqrt (p/dot pb pb)) sc)]]))
         ;; the moment about the pin, and each body's own about its centre
         ;; of mass (what one step of jBullet's solver lets a torque see)
         reduced (fn [ax pin-a pin-b]
                   (let [ia (pivot-inertia rb-a (p/rotate frame-a ax) pin-a)
                         ib (pivot-inertia rb-b (p/rotate frame-b ax) pin-b)]
                     (/ (/ 1.0 (+ (/ 1.0 ia) (/ 1.0 ib))) (* sc sc))))
         about (fn [ax pin-a pin-b]
                 (let [i (reduced ax pin-a pin-b)]
                   (if (and (Double/isFinite i) (pos? i)) i 1.0)))
         ;; [pin's moment, own moments] about one axis
         sized (fn [ax] (let [i (about ax pa pb)]
                          [i (default-gains strength i (min i (about ax [0 0 0] [0 0 0])))]))
         given-or (fn [k gains] (given sensor k #(gains k)))]
     (if (= type :hinge)
       (let [[inertia gains] (sized axis)]
         (assoc sensor :strength strength :inertia inertia
                :kp (given-or :kp gains) :kd (given-or :kd gains)))
       (let [axes (blender-order (map sized [[1 0 0] [0 1 0] [0 0 1]]))
             ;; a gain in the description is the same on every axis
             gain (fn [k] (let [g (given sensor k (constantly nil))]
                            (if g [g g g] (mapv #(get (second %) k) axes))))]
         (assoc sensor :strength strength :inertia (mapv first axes)
                :kp (gain :kp) :kd (gain :kd)))))))

(defn ^:api muscles
  "The muscles of `creature` (built by cortex.body/body!), by joint name."
  [^Node creature]
  (into {} (for [s (p/sensors creature)] [(:name s) (muscle s)])))

(defn clamp
  "`effort` (a number or an [x y z] torque) limited to `strength`: a
  number into [-strength, strength], a vector scaled down to that length."
  [effort ^double strength]
  (if (number? effort)
    (max (- strength) (min strength (double effort)))
    (let [n (Math/sqrt (p/dot effort effort))]
      (if (<= n strength)
        (mapv double effort)
        (mapv #(* (/ strength n) (double %)) effort)))))

(defn- per-axis
  "A gain as three, one per axis: a number the same on each."
  [g]
  (if (number? g) [g g g] g))

(defn- pd-torque
  "The PD torque, unclamped, towards `target` for `muscle` as it is now."
  [{:keys [type axis] :as muscle} {:keys [target] :as action}]
  (let [kp (get action :kp (:kp muscle))
        kd (get action :kd (:kd muscle))
        q (p/relative-rotation muscle)
        w (p/relative-angular-velocity muscle)]
    (if (= type :hinge)
      (- (* (double kp) (p/wrap-angle (- (double target) (p/twist-angle q axis))))
         (* (double kd) (p/dot w axis)))
      (let [error (p/rotation-vector (p/q* (p/from-rotation-vector target)
                                           (p/q-conj (p/jme->blender q))))]
        (mapv #(- (* (double %3) (double %1)) (* (double %4) (double %2)))
              error (p/jme->blender w) (per-axis kp) (per-axis kd))))))

(defn- fail
  [joint message data]
  (throw (ex-info (str "joint " (pr-str joint) ": " message) (assoc data :joint joint))))

(defn- finite? [x] (and (number? x) (Double/isFinite (double x))))

(defn- finite-vector? [v] (and (sequential? v) (= 3 (count v)) (every? finite? v)))

(defn- takes
  "What a joint of `type` takes, for messages."
  [type]
  (if (= type :hinge)
    "a finite torque (a number) or {:target angle}"
    "a finite torque [x y z] or {:target [x y z]} (a rotation vector)"))

(defn effort
  "The torque, clamped to strength, that `action` asks of `muscle`: a
  number for a hinge, [x y z] (joint frame, Blender's axes) otherwise.
  An ex-info naming the joint when the action does not fit it."
  [{:keys [name type strength] :as muscle} action]
  (let [hinge? (= type :hinge)]
    (cond
      (map? action)
      (let [{:keys [target]} action]
        (when-not (if hinge? (finite? target) (finite-vector? target))
          (fail name (str "a " (clojure.core/name type) " joint takes " (takes type)
                          ", not " (pr-str action)) {:action action}))
        (doseq [k [:kp :kd]
                :let [g (get action k)
                      gain? #(and (finite? %) (not (neg? (double %))))]
                :when (some? g)]
          (when-not (or (gain? g) (and (not hinge?) (finite-vector? g) (every? gain? g)))
            (fail name (str k " must be a finite, non-negative number"
                            (when-not hinge? " or three of them, [x y z]")
                            ", not " (pr-str g))
                  {:action action})))
        (clamp (pd-torque muscle action) strength))

      (if hinge? (finite? action) (finite-vector? action))
      (clamp action strength)

      :else
      (fail name (str "a " (clojure.core/name type) " joint takes " (takes type)
                      ", not " (pr-str action)) {:action action}))))

(defn efforts
  "The clamped torque for every joint `actions` names, by name, given
  `muscles` (see `muscles`). Every action is checked first: an ex-info
  names the first bad joint, in name order, and nothing is computed."
  [muscles actions]
  (when-not (map? actions)
    (throw (ex-info (str "actions must be a map from joint name to action, not "
                         (pr-str actions))
                    {:actions actions})))
  (let [names (sort-by str (keys actions))]
    (doseq [n names
            :when (not (contains? muscles n))]
      (fail n (str "there is no such joint; the joints are "
                   (str/join ", " (sort (keys muscles))))
            {:known (vec (sort (keys muscles)))}))
    (into {} (for [n names] [n (effort (muscles n) (actions n))]))))

(defn world-torque
  "The torque `effort` asks of `muscle`, in jME's world axes."
  [{:keys [type axis] :as muscle} effort]
  (let [frame (p/frame-now muscle)]
    (if (= type :hinge)
      (mapv #(* (double effort) (double %)) (p/rotate frame axis))
      (p/rotate frame (p/blender->jme effort)))))

(defn- apply-torque!
  [{:keys [rb-a rb-b]} torque]
  (engine/apply-torques! rb-a rb-b torque))

(defn apply-efforts!
  "Apply `efforts` (from `efforts`) at the joints of `muscles`; on bodies
  built `scale` times the creature's size (see `muscle`), each torque
  times scale^2, the same turn in the larger world."
  ([muscles efforts] (apply-efforts! muscles efforts 1.0))
  ([muscles efforts scale]
   (let [k2 (* (double scale) (double scale))]
     (doseq [[n e] efforts
             :let [m (muscles n)
                   t (world-torque m e)]]
       (apply-torque! m (if (== 1.0 k2) t (mapv #(* k2 (double %)) t)))))))

(defn ^:api actuate!
  "Apply `actions` (see the namespace doc) at the joints of `creature`,
  built by cortex.body/body!, for the next physics step; or at
  `muscles` (see `muscles`), which saves working them out every step.
  Checks every action before applying any. Returns the efforts applied,
  by joint name (N.m, joint frame)."
  [creature-or-muscles actions]
  (let [ms (if (instance? Node creature-or-muscles)
             (muscles creature-or-muscles)
             creature-or-muscles)
        es (efforts ms actions)]
    (apply-efforts! ms es)
    es))
