;; Generated from org/engine.org by lein tangle: edit the chapter, not this file.
(ns cortex.engine-speed
  "Step throughput of generated chains on the engine of this classpath:
  lein run -m cortex.engine-speed [N ...] (default 100 300)."
  (:require [cortex.bench.creatures :as creatures]
            [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.sim :as sim]))

(set! *warn-on-reflection* true)

(defn sim-seconds-per-second
  "Median simulated seconds per wall-clock second of a chain of `n`
  segments stepped `frames` times, over three runs after a warm-up."
  [n frames]
  (let [c (doto (creatures/creature (creatures/chain n) 1.5) (body/body!))
        s (sim/simulation c {:floor 0 :observe #{}})]
    (try
      (dotimes [_ (quot frames 2)] (sim/step! s))
      (let [runs (sort (repeatedly 3 #(let [t0 (System/nanoTime)]
                                        (dotimes [_ frames] (sim/step! s))
                                        (/ (/ frames 60.0) (/ (- (System/nanoTime) t0) 1e9)))))]
        (nth runs 1))
      (finally (sim/destroy! s)))))

(defn -main [& args]
  (let [ns (if (seq args) (map #(Long/parseLong %) args) [100 300])]
    (doseq [n ns]
      (let [frames (max 30 (quot 6000 n))]
        (println (format "%s chain-%d %.3f sim-s/s" (clojure.core/name engine/name) n
                         (double (sim-seconds-per-second n frames))))))
    (shutdown-agents)
    (System/exit 0)))
