;; Generated from org/physics-trust.org by lein tangle: edit the chapter, not this file.
(ns cortex.compare
  "cortex's side of scripts/compare/humanoid_compare.py: the humanoid
  and a 100-segment chain dropped in cortex.sim, timed, written as JSON.

  Entry point: `-main` (lein run -m cortex.compare [OUT.json] [runs])."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [cortex.body :as body]
            [cortex.sim :as sim]
            [cortex.util :as util])
  (:import (java.lang.management ManagementFactory)
           (com.jme3.scene Node)))

(set! *warn-on-reflection* true)

(def ^:private floor-z
  "Where MuJoCo's floor is under the fixture (its feet at 0)."
  -0.10703)

(defn- cpu-ns ^long []
  (.getCurrentThreadCpuTime (ManagementFactory/getThreadMXBean)))

(defn- timed-run
  "Build `make`'s creature (sleeping off), step warm-up then `steps`
  steps; [steps-per-cpu-second final-observation fastest-speed]."
  [make floor warm-up steps]
  (let [c (body/body! ^Node (make) {:sleeping-thresholds [0 0]})
        s (sim/simulation c {:floor {:height floor :friction 1.0} :observe #{}})
        speed (fn [o] (apply max (for [[_ {:keys [velocity]}] (:segments o)]
                                   (Math/sqrt (reduce + (map #(* % %) velocity))))))
        fastest (atom 0.0)]
    (dotimes [_ warm-up] (sim/step! s) (swap! fastest max (speed (sim/observe s #{:segments}))))
    (let [t0 (cpu-ns)]
      (dotimes [_ steps] (sim/step! s))
      (let [t (/ (- (cpu-ns) t0) 1e9)]
        [(/ steps t) (sim/observe s #{:segments}) @fastest]))))

(defn- median [xs] (nth (sort xs) (quot (count xs) 2)))

(defn measure
  "The numbers humanoid_compare.py reads, over `runs` runs."
  [runs]
  (let [humanoid #(util/load-blender-model "test/fixtures/humanoid/humanoid.blend")
        chain #((requiring-resolve 'cortex.bench.creatures/creature)
                ((requiring-resolve 'cortex.bench.creatures/chain) 100) 1.0)
        h (vec (repeatedly runs #(timed-run humanoid floor-z 1000 10000)))
        c (vec (repeatedly runs #(timed-run chain -0.2 1000 10000)))
        height (fn [obs seg floor] (- (double (second (get-in obs [:segments seg :position]))) floor))]
    {:engine "cortex (jBullet)"
     :settings "10 solver iterations, cones as 6-DOF, mesh mass properties, sleeping off"
     :humanoid {:steps_per_s (median (map first h))
                :final_torso_height (height (second (peek h)) "torso" floor-z)
                :max_speed (apply max (map #(nth % 2) h))}
     :chain {:steps_per_s (median (map first c))
             :final_height (median (for [[_ obs] c]
                                     (/ (reduce + (for [[_ {[_ y] :position}] (:segments obs)] (+ y 0.2)))
                                        (count (:segments obs)))))}}))

(defn- json
  "`x` (maps, strings, numbers) as JSON text."
  [x]
  (cond (map? x) (str "{" (str/join ", " (for [[k v] x] (str (json (name k)) ": " (json v)))) "}")
        (string? x) (str "\"" (str/replace x "\"" "\\\"") "\"")
        :else (str x)))

(defn -main
  "lein run -m cortex.compare [OUT.json] [runs]"
  [& [out runs]]
  (let [out (or out "out/bench/cortex-humanoid.json")
        m (measure (Long/parseLong (or runs "3")))]
    (io/make-parents out)
    (spit out (json m))
    (println (json m))
    (println "wrote" out)
    (shutdown-agents)))
