;; Generated from org/physics-trust.org by lein tangle: edit the chapter, not this file.
(ns cortex.rest-matrix
  "Do creatures come to rest? Each creature dropped N times, from seeded
  random tilts (up to 0.3 rad about each axis) and heights (0.5 to 1 m
  above its lowest point), on floors of friction 0.25, 0.5 and 1.0 in
  turn, for 600 steps of cortex.sim, under settings given as data; per
  creature the share of drops that meet the rest rule (every segment
  slower than 0.05 m/s through the last second, none moving more than
  0.02 between 8 s and 10 s), the worst speed in the last second, the
  most moved, the largest joint gap and the share asleep at the end; and
  the humanoid's steps per CPU second (sleeping off) against the first
  setting's, measured alternately in this JVM. jBullet only.

  bin/lein run -m cortex.rest-matrix N SETTING...   each SETTING a name
  in `configs` or an EDN map (keys: :ang-damp :lin-damp :sleep :mass
  :deact, and cortex.trust-matrix's :hinge :sixdof :iterations ...);
  CREATURES=quadruped,worm narrows the run, NOSPEED=1 skips the timing."
  (:require [cortex.body :as body]
            [cortex.sim :as sim]
            [cortex.blender]
            [cortex.util :as util]
            [cortex.drops :refer [extent]]
            [cortex.trust-matrix :as tm]
            [clojure.string :as str])
  (:import (com.jme3.scene Node)
           (com.jme3.bullet.control RigidBodyControl)
           (com.bulletphysics BulletGlobals)
           (java.util Random)))

(def creatures
  [["quadruped" "test/fixtures/designer/quadruped.blend"]
   ["worm" "Models/test-creature/worm.blend"]
   ["hand" "Models/test-creature/hand.blend"]
   ["humanoid" "test/fixtures/humanoid/humanoid.blend"]])

(def frictions [0.25 0.5 1.0])

(defn body-opts [cfg]
  (cond-> {}
    (:ang-damp cfg) (assoc :angular-damping (:ang-damp cfg))
    (:sleep cfg) (assoc :sleeping-thresholds (:sleep cfg))
    (:mass cfg) (assoc :mass-properties (:mass cfg))))

(defn configure!
  "Apply `cfg` to simulation `s` of `creature`: cortex.trust-matrix's
  solver and joint settings, linear damping, Bullet's deactivation time
  (a global: set for every drop, 2 s unless given)."
  [cfg s creature]
  (tm/configure! cfg s creature)
  (when-let [l (:lin-damp cfg)]
    (doseq [[_ ^RigidBodyControl c] (:controls s)]
      (.setDamping c (float l) (.getAngularDamping c))))
  (BulletGlobals/setDeactivationTime (float (or (:deact cfg) 2.0))))

(defn- norm ^double [v] (Math/sqrt (double (reduce + (map #(* (double %) (double %)) v)))))

(defn drop!
  "Drop number `i` of the creature in file `path` under `cfg`: tilt,
  height and friction from seed `i`."
  [cfg path i]
  (let [rnd (Random. (long i))
        [ax ay az] (repeatedly 3 #(* 0.3 (- (* 2.0 (.nextDouble rnd)) 1.0)))
        h (+ 0.5 (* 0.5 (.nextDouble rnd)))
        friction (frictions (mod i (count frictions)))
        ^Node c (util/load-blender-model path)
        _ (.rotate c (float ax) (float ay) (float az))
        [lo _] (extent c)
        _ (.move c 0 (float (- h lo)) 0)
        _ (.updateGeometricState c)
        ;; built where it was put: a RigidBodyControl takes its place
        ;; from its Geometry only when it is attached
        _ (tm/build! cfg c (body-opts cfg))
        joints (mapv :physics-joint (body/joint-records c))
        s (sim/simulation c {:floor {:height 0 :friction friction} :observe #{:segments}})
        _ (configure! cfg s c)
        speed (fn [obs] (apply max (for [[_ {:keys [velocity]}] (:segments obs)] (norm velocity))))
        spin (fn [obs] (apply max (for [[_ {w :angular-velocity}] (:segments obs)] (norm w))))
        gap (double-array 1)
        obs (vec (for [_ (range 600)]
                   (let [o (sim/step! s)]
                     (aset gap 0 (max (aget gap 0) (double (reduce max 0.0 (map body/joint-gap joints)))))
                     o)))
        last-second (subvec obs 540)
        moved (apply max (for [[n {p1 :position}] (:segments (obs 599))
                               :let [p0 (get-in obs [479 :segments n :position])]]
                           (norm (map - p1 p0))))
        fastest (apply max (map speed last-second))
        bodies (for [[_ ^RigidBodyControl rb] (:controls s) :when (pos? (.getMass rb))] rb)]
    {:i i :friction friction
     :last-second fastest
     :spin (apply max (map spin last-second))
     :moved moved :gap (aget gap 0)
     :asleep (every? #(not (.isActive ^RigidBodyControl %)) bodies)
     :rest? (and (< fastest 0.05) (< moved 0.02))}))

(defn speed-run
  "Steps per CPU second of the humanoid under `cfg`, sleeping off, 300
  warm-up and `n` timed steps."
  [cfg n]
  (let [c (tm/build! cfg (util/load-blender-model (second (last creatures)))
                     (assoc (body-opts cfg) :sleeping-thresholds [0 0]))
        s (sim/simulation c {:floor {:height -0.2 :friction 1.0} :observe #{}})]
    (configure! cfg s c)
    (dotimes [_ 300] (sim/step! s))
    (let [t0 (tm/cpu-ns)]
      (dotimes [_ n] (sim/step! s))
      (/ n (/ (- (tm/cpu-ns) t0) 1e9)))))

(def configs
  {"base" {}
   "ad0.7" {:ang-damp 0.7}
   "ad0.9" {:ang-damp 0.9}
   "ld0.1" {:lin-damp 0.1}
   "sl3" {:sleep [0.8 3.0]}
   "sl4" {:sleep [1.0 4.0]}
   "deact1" {:deact 1.0}
   "hinge-soft1" {:hinge [1.0 0.3 1.0]}
   "6dof-stiff" {:sixdof {:softness 1.0 :max-force 1e5}}})

(defn summary [cn cr rs]
  (let [n (count rs)]
    (format "%-40s %-10s rest %3d/%-3d  last-s %6.3f  moved %7.4f  gap %6.4f  asleep %3d/%-3d  spin %5.2f  not at rest: %s"
            cn cr (count (filter :rest? rs)) n
            (apply max (map :last-second rs)) (apply max (map :moved rs))
            (apply max (map :gap rs)) (count (filter :asleep rs)) n
            (apply max (map :spin rs))
            (str/join "," (for [r rs :when (not (:rest? r))] (str (:i r) "@" (:friction r)))))))

(defn -main
  "bin/lein run -m cortex.rest-matrix N SETTING..."
  [n & names]
  (let [n (Long/parseLong n)
        names (or (seq names) ["base"])
        only (when-let [c (System/getenv "CREATURES")] (set (str/split c #",")))
        cfgs (mapv (fn [nm] [nm (or (configs nm) (read-string nm))]) names)]
    (doseq [[cn cfg] cfgs
            [cr path] creatures :when (or (nil? only) (only cr))]
      (println (summary cn cr (mapv #(drop! cfg path %) (range n))))
      (flush))
    (when-not (System/getenv "NOSPEED")
      (let [speeds (atom {})]
        (dotimes [_ 3]
          (doseq [[cn cfg] cfgs]
            (swap! speeds update cn (fnil conj []) (speed-run cfg 2000))))
        (let [med #(nth (sort (@speeds %)) 1)
              base (med (first (first cfgs)))]
          (doseq [[cn _] cfgs]
            (println (format "%-40s humanoid steps/s %6.0f  x%.2f" cn (med cn) (/ (med cn) base)))))))
    (BulletGlobals/setDeactivationTime (float 2.0))
    (shutdown-agents)
    (System/exit 0)))
