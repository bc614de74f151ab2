;; Generated from org/bench.org by lein tangle: edit the chapter, not this file.
(ns cortex.observe-cost
  "lein run -m cortex.observe-cost: what observing costs beside a step,
  in microseconds of this thread's CPU time, for four creatures on the
  engine of this classpath: a step observing nothing in the first 5 s of
  a drop, and each observation alone (:joints, :segments, :touch, all
  three) of the creature 2 s into its drop; medians of five rounds."
  (:require [cortex.bench :refer [median]]
            [cortex.blender]
            [cortex.engine :as engine]
            [cortex.sim :as sim]
            [cortex.util :as util])
  (:import (java.lang.management ManagementFactory)))

(set! *warn-on-reflection* true)

(def ^:private ^java.lang.management.ThreadMXBean threads
  (ManagementFactory/getThreadMXBean))

(defn- cpu-us-each
  "This thread's CPU microseconds per call of `f`, called `n` times."
  [n f]
  (let [c0 (.getCurrentThreadCpuTime threads)]
    (dotimes [_ n] (f))
    (/ (- (.getCurrentThreadCpuTime threads) c0) 1e3 n)))

(def creatures
  "The creatures measured: [name path]."
  [["strangers' humanoid" "test/fixtures/strangers/humanoid.blend"]
   ["humanoid" "test/fixtures/humanoid/humanoid.blend"]
   ["four-legged" "test/fixtures/designer/quadruped.blend"]
   ["hand" "assets/Models/test-creature/hand.blend"]])

(def parts
  "What is observed, and how it is labelled."
  [[#{:joints} "joints"] [#{:segments} "segments"] [#{:touch} "touch"]
   [#{:joints :segments :touch} "all three"]])

(defn- simulation [path observe]
  (sim/simulation (util/load-blender-model path) {:floor {:height 0 :friction 1.0}
                                                  :observe observe}))

(defn- round
  "One round for the creature at `path`: {label µs}."
  [path]
  (let [s (simulation path #{})
        step (try (cpu-us-each 300 #(sim/step! s)) (finally (sim/destroy! s)))
        o (simulation path #{})]
    (try
      (dotimes [_ 120] (sim/step! o))
      (into {"step" step}
            (for [[ps label] parts]
              [label (do (cpu-us-each 2000 #(sim/observe o ps))
                         (cpu-us-each 20000 #(sim/observe o ps)))]))
      (finally (sim/destroy! o)))))

(defn -main [& _]
  (doseq [[_ path] creatures] (round path))
  (println (str "observing on " engine/label ": medians of five rounds, CPU µs;"
                " share = all three / (step + all three)"))
  (println (format "%-20s %8s %8s %9s %8s %10s %6s" "creature" "step" "joints" "segments"
                   "touch" "all three" "share"))
  (doseq [[name path] creatures]
    (let [rounds (vec (repeatedly 5 #(round path)))
          m (fn [k] (median (map #(get % k) rounds)))]
      (println (format "%-20s %8.1f %8.1f %9.1f %8.1f %10.1f %6.2f" name (m "step") (m "joints")
                       (m "segments") (m "touch") (m "all three")
                       (/ (m "all three") (+ (m "step") (m "all three")))))))
  (shutdown-agents)
  (System/exit 0))
