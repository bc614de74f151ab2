;; Generated from org/physics-trust.org by lein tangle: edit the chapter, not this file.
(ns cortex.drops
  "A creature dropped and measured as the physics-trust chapter does it:
  `place!`, `drop!` (what happened in a 10 s fall), `speeds`, `export`,
  and the readings they use (`extent`, `overshoot`, `limit-overshoot`,
  `cone-angles`, `energy`). Shared by the drop tests and the measuring
  tools."
  (:require [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.proprioception :as p]
            [cortex.sim :as sim]
            [cortex.util :as util])
  (:import (com.jme3.bounding BoundingBox)
           (com.jme3.math Quaternion)
           (com.jme3.scene Geometry Node)))

(set! *warn-on-reflection* true)

(defn extent
  "[lowest highest] point of `creature`'s segments."
  [^Node creature]
  (.updateGeometricState creature)
  (let [bs (for [^Geometry g (body/segments creature)
                 :let [^BoundingBox b (.getWorldBound g)]]
             [(- (.y (.getCenter b)) (.getYExtent b)) (+ (.y (.getCenter b)) (.getYExtent b))])]
    [(apply min (map first bs)) (apply max (map second bs))]))

(defn overshoot
  "How far past its limits joint state `j` of description `d` is,
  radians, scaled to the allowance: a hinge's by 0.05, a cone's by 0.1,
  so that 1 is the most either may go past."
  [{:keys [type angle swing twist]} d]
  (case type
    :hinge (let [[lo hi] (:limit d)]
             (/ (max 0.0 (- (double lo) angle) (- angle (double hi))) 0.05))
    :cone (let [[sy sz] swing]
            (/ (max 0.0 (- (Math/abs (double twist)) (double (:twist d)))
                    (- (Math/abs (double sy)) (double (:limit-xz d)))
                    (- (Math/abs (double sz)) (double (:limit-xy d))))
               0.1))
    0.0))

(defn cone-angles
  "[angles limits] of the cone joint `sensor` (cortex.proprioception) of
  description `d` now: its three angles as its engine reads them (the
  Euler angles of its relative rotation in the frame body! gives the
  engine, turned when the wider swing is about jME's Y, see the body
  chapter) and the limits body! gave them."
  [sensor d]
  (let [[x y z w] (p/relative-rotation sensor)]
    (body/cone-engine-angles d (Quaternion. (float x) (float y) (float z) (float w)))))

(defn limit-overshoot
  "How far past its limits the joint `sensor` (cortex.proprioception)
  of description `d` is now, scaled to the allowance (0.05 rad for a
  hinge, 0.1 for a cone), read in the limits' own terms: a hinge's angle
  about its axis; a cone's three angles as body! limits them, the Euler
  angles of its relative rotation in the frame body! gives the engine
  (turned when the wider swing is about jME's Y, see the body chapter)."
  [{:keys [type] :as sensor} d]
  (case type
    :hinge (overshoot (p/joint-state sensor) d)
    :cone (let [[angles limits] (cone-angles sensor d)]
            (/ (reduce max 0.0 (map (fn [a l] (- (Math/abs (double a)) (double l))) angles limits))
               0.1))
    0.0))

(defn energy
  "The mechanical energy of `sim`'s segments now, joules: each body's
  kinetic energy, of its centre of mass and of its turning about it
  (its principal moments), and its height above y = 0 under g = 9.81."
  ^double [sim]
  (reduce + (for [[_ rb] (:segments sim)
                  :let [inv-m (engine/inverse-mass rb)]
                  :when (pos? inv-m)]
              (let [m (/ 1.0 inv-m)
                    v (engine/linear-velocity rb)
                    [_ y] (engine/position rb)
                    ;; the angular velocity in the body's principal axes
                    w (p/rotate (p/q-conj (engine/orientation rb)) (engine/angular-velocity rb))]
                (+ (* 0.5 m (reduce + (map * v v)))
                   (* 0.5 (reduce + (map (fn [wi ii] (if (pos? ii) (/ (* wi wi) ii) 0.0))
                                         w (engine/inverse-inertia rb))))
                   (* m 9.81 y))))))

(defn lift!
  "Move `creature` (a Node, not yet built) so that its lowest point is
  1 m above y = 0, where every drop starts; its [lowest highest] before.
  It must be moved before its bodies are made: a RigidBodyControl takes
  its place from its Geometry only when it is attached."
  [^Node creature]
  (let [[lo :as e] (extent creature)]
    (.move creature 0 (float (- 1.0 (double lo))) 0)
    e))

(defn place!
  "`lift!` `creature` and build it (with body!'s `opts`); the speed limit
  of a clean fall from there, sqrt(2 g H) + 1 m/s, H the drop of its
  highest point."
  (^double [creature] (place! creature {}))
  (^double [^Node creature opts]
   (let [[lo hi] (lift! creature)]
     (body/body! creature opts)
     (+ 1.0 (Math/sqrt (* 2 9.81 (+ 1.0 (- (double hi) (double lo)))))))))

(def pinned
  "The drops whose every step the drop-hash test pins, by name: [how
  it is made (:markers, placed by `lift!`, or :physics-tab, where its
  file says), its path, body!'s options]."
  (array-map
   "worm" [:markers "assets/Models/test-creature/worm.blend"]
   "hand" [:markers "assets/Models/test-creature/hand.blend"]
   "worm-eyes" [:markers "assets/Models/test-creature/worm-eyes.blend"]
   "quadruped" [:markers "test/fixtures/designer/quadruped.blend"]
   "humanoid" [:markers "test/fixtures/humanoid/humanoid.blend"]
   "humanoid-heavy-hands" [:markers "test/fixtures/humanoid/humanoid-heavy-hands.blend"]
   "stranger-hand" [:markers "test/fixtures/strangers/hand.blend"]
   "stranger-humanoid" [:markers "test/fixtures/strangers/humanoid.blend"]
   "stranger-worm-eye" [:markers "test/fixtures/strangers/worm-eye.blend"]
   ;; the seed's one hull a segment, as every creature was built before
   ;; shapes were chosen: these keep the hashes they had then
   "hand/hulls" [:markers "assets/Models/test-creature/hand.blend" {:shapes :hull}]
   "quadruped/hulls" [:markers "test/fixtures/designer/quadruped.blend" {:shapes :hull}]
   "stranger-hand/hulls" [:markers "test/fixtures/strangers/hand.blend" {:shapes :hull}]
   "stranger-humanoid/hulls" [:markers "test/fixtures/strangers/humanoid.blend" {:shapes :hull}]
   "physics" [:physics-tab "test/fixtures/blend/b45/physics.blend"]
   "ragdoll" [:physics-tab "test/fixtures/physics-sim/ragdoll.blend"]))

(defn drop!
  "Drop `creature` (a Node, not yet built) with its lowest point 1 m
  above a floor of `friction` for 10 s, simulated with `opts` besides
  the floor (cortex.sim/simulation's; none by default); what happened."
  ([creature friction] (drop! creature friction {}))
  ([^Node creature friction opts]
  (let [limit (place! creature)
        described (into {} (map (juxt :name :description)) (body/joint-records creature))
        sensors (p/sensors creature)
        s (sim/simulation creature (assoc opts :floor {:height 0 :friction friction}))
        ;; how far past its limits each joint is, in the limits' terms
        ;; and in proprioception's (see the text)
        past (fn [] (into {} (for [{n :name :as sensor} sensors]
                               [n [(limit-overshoot sensor (described n))
                                   (overshoot (p/joint-state sensor) (described n))]])))
        start-past (past)
        speed (fn [obs] (apply max (for [[_ {:keys [velocity]}] (:segments obs)]
                                     (Math/sqrt (reduce + (map #(* % %) velocity))))))
        e0 (energy s)
        [obs pasts es] (reduce (fn [[obs pasts es] _]
                                 [(conj obs (sim/step! s)) (conj pasts (past)) (conj es (energy s))])
                               [[] [] []] (range 600))
        still-from (loop [i 599] (if (and (>= i 0) (< (speed (obs i)) 0.05)) (recur (dec i)) (inc i)))
        moved (apply max (for [[n {p1 :position}] (:segments (obs 599))
                               :let [p0 (get-in obs [479 :segments n :position])]]
                           (Math/sqrt (reduce + (map #(let [d (- %1 %2)] (* d d)) p1 p0)))))
        worst (fn [k] (apply max 0.0 (for [ps pasts [n p] ps] (- (p k) ((start-past n) k)))))]
    {:fastest (apply max (map speed obs)) :limit limit
     :fastest-segment (key (apply max-key (fn [[_ {:keys [velocity]}]] (reduce + (map * velocity velocity)))
                                  (mapcat :segments obs)))
     :worst-past (worst 0) :worst-past-proprioception (worst 1)
     :still-at (when (< still-from 600) (/ still-from 60.0)) :moved moved
     ;; the most energy the creature ever had beyond what it started
     ;; with, as a fraction of that
     :energy-gain (/ (- (apply max es) e0) e0)})))

(def table-creatures
  "What `-main` drops, in the order of its table: the drop test's
  creatures, a file each, and the benchmark's chain of 100 (nil)."
  [["humanoid" "test/fixtures/humanoid/humanoid.blend"]
   ["heavy-hands" "test/fixtures/humanoid/humanoid-heavy-hands.blend"]
   ["quadruped" "test/fixtures/designer/quadruped.blend"]
   ["hand" "Models/test-creature/hand.blend"]
   ["chain-100" nil]])

(defn- table-creature
  "A fresh, unbuilt creature from the .blend file at `path`, or the
  benchmark's chain of 100 when `path` is nil."
  ^Node [path]
  (if path
    ((requiring-resolve 'cortex.blender/load-blender-model) path)
    ((requiring-resolve 'cortex.bench.creatures/creature)
     ((requiring-resolve 'cortex.bench.creatures/chain) 100))))

(defn -main
  "lein run -m cortex.drops: the drop test's fifteen drops on the
  running engine, as an org table (the physics-trust chapter's)."
  [& _]
  ;; every drop first, so that what an engine prints as it starts up
  ;; does not fall inside the table
  (let [rows (vec (for [friction [0.25 0.5 1.0]
                        [name path] table-creatures]
                    (assoc (drop! (table-creature path) friction) :name name :friction friction)))]
    (println (str "drop! on " engine/label ", " (java.time.LocalDate/now)))
    (println (str "| creature    | friction | fastest | segment         | clean fall | past "
                  "| past (proprioception) | rest  | moved  | energy |"))
    (println (str "|-------------+----------+---------+-----------------+------------+------"
                  "+-----------------------+-------+--------+--------|"))
    (doseq [{:keys [name friction fastest fastest-segment limit worst-past
                    worst-past-proprioception still-at moved energy-gain]} rows]
      (println (format "| %-11s | %8.2f | %7.2f | %-15s | %10.2f | %4.2f | %21.2f | %5s | %6.4f | %5.2f%% |"
                       name (double friction) (double fastest) fastest-segment (double limit)
                       (double worst-past) (double worst-past-proprioception)
                       (if still-at (format "%.1f s" (double still-at)) "never")
                       (double moved) (* 100.0 (double energy-gain))))))
  (shutdown-agents))

(defn export
  "`creature` (a Node, not yet built) placed and built as `drop!` does
  it, as data in jME's axes (Y up, the floor at y = 0): every segment's
  name, mass, centre of mass :com, principal frame :quat [x y z w],
  principal :moments and world :vertices; every joint's name, two
  :segments, :pivot, :description and, for a hinge, its :world-axis."
  [^Node creature]
  (place! creature)
  (let [s (sim/simulation creature {:floor 0})
        geoms (into {} (map (juxt body/segment-name identity)) (body/segments creature))
        v3 (fn [^com.jme3.math.Vector3f v] [(.x v) (.y v) (.z v)])]
    {:segments
     (vec (for [[n rb] (sort-by first (:segments s))
                :let [^Geometry g (geoms n)]]
            {:name n :mass (/ 1.0 (engine/inverse-mass rb))
             :com (engine/position rb) :quat (engine/orientation rb)
             :moments (mapv #(/ 1.0 (double %)) (engine/inverse-inertia rb))
             :vertices (vec (for [^com.jme3.math.Vector3f p (body/mesh-points (.getMesh g) (.getWorldScale g))]
                              (v3 (.add (.mult (.getWorldRotation g) p) (.getWorldTranslation g)))))}))
     :joints
     (vec (for [{:keys [name segments pivot description] [x y z w] :rotation} (body/joint-records creature)
                :let [axis (:axis description)]]
            {:name name :segments segments :pivot (vec pivot)
             :description (into {} (for [[k v] description :when (not= k :axis)]
                                     [k (cond (instance? com.jme3.math.Vector3f v) (v3 v)
                                              (sequential? v) (vec v)
                                              :else v)]))
             ;; a hinge's axis is given in the empty's frame, Blender's axes
             :world-axis (when axis
                           (let [[ax ay az] (if (sequential? axis) axis (v3 axis))]
                             (v3 (.mult (Quaternion. (float x) (float y) (float z) (float w))
                                        (util/blender-to-jme (com.jme3.math.Vector3f.
                                                              (float ax) (float ay) (float az)))))))}))}))

(defn speeds
  "Every segment's speed, m/s, after each of `steps` steps of
  `creature` (a Node, not yet built) dropped as `drop!` drops it on a
  floor of `friction`: [[seconds {segment speed}] ...]."
  [^Node creature friction steps]
  (place! creature)
  (let [s (sim/simulation creature {:floor {:height 0 :friction friction} :observe #{:segments}})]
    (vec (for [i (range 1 (inc steps))
               :let [obs (sim/step! s)]]
           [(/ i 60.0) (into (sorted-map) (for [[n {v :velocity}] (:segments obs)]
                                            [n (Math/sqrt (reduce + (map * v v)))]))]))))
