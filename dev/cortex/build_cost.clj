;; Generated from org/bench.org by lein tangle: edit the chapter, not this file.
(ns cortex.build-cost
  "lein run -m cortex.build-cost: physical! and body! of the hand and of
  chains of 100, 300 and 1000 segments, each on a fresh creature, as
  medians of wall ms, this thread's CPU ms and the MB it allocated."
  (:require [cortex.bench :refer [median]]
            [cortex.bench.creatures :as creatures]
            [cortex.blender]
            [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.util :as util])
  (:import (java.lang.management ManagementFactory)))

(set! *warn-on-reflection* true)

(def ^:private ^com.sun.management.ThreadMXBean threads
  (ManagementFactory/getThreadMXBean))

(defn- once
  "(f creature) on a creature `make` makes: [wall-ms cpu-ms mb], the
  CPU time and allocation this thread's."
  [f make]
  (let [c (make)
        _ (System/gc)
        id (.getId (Thread/currentThread))
        a0 (.getThreadAllocatedBytes threads id)
        c0 (.getCurrentThreadCpuTime threads)
        t0 (System/nanoTime)
        _ (f c)
        t1 (System/nanoTime)
        c1 (.getCurrentThreadCpuTime threads)
        a1 (.getThreadAllocatedBytes threads id)]
    [(/ (- t1 t0) 1e6) (/ (- c1 c0) 1e6) (/ (- a1 a0) 1e6)]))


(def creatures
  "The creatures measured: [name make], make making a fresh one."
  [["hand" #(util/load-blender-model "assets/Models/test-creature/hand.blend")]
   ["chain-100" (let [d (creatures/chain 100)] #(creatures/creature d))]
   ["chain-300" (let [d (creatures/chain 300)] #(creatures/creature d))]
   ["chain-1000" (let [d (creatures/chain 1000)] #(creatures/creature d))]])

(defn -main [& _]
  (dotimes [_ 3] (doseq [[_ make] (take 3 creatures)] (once body/body! make)))
  (println (str "physical! and body! on " engine/label ": medians of wall ms,"
                " this thread's CPU ms and MB allocated"))
  (println (format "%-10s %4s %10s %8s %8s %10s %8s %8s" "creature" "runs"
                   "physical!" "CPU" "MB" "body!" "CPU" "MB"))
  (doseq [[name make] creatures]
    (let [runs (if (= name "chain-1000") 5 7)
          p (vec (repeatedly runs #(once body/physical! make)))
          b (vec (repeatedly runs #(once body/body! make)))
          m (fn [rows k] (median (map #(nth % k) rows)))]
      (println (format "%-10s %4d %10.1f %8.1f %8.1f %10.1f %8.1f %8.1f" name runs
                       (m p 0) (m p 1) (m p 2) (m b 0) (m b 1) (m b 2)))))
  (shutdown-agents)
  (System/exit 0))
