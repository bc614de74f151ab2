;; Generated from org/bench.org by lein tangle: edit the chapter, not this file.
(ns cortex.engine-speed
  "Build time and step throughput on the engine of this classpath, and
  both engines side by side (see org/engine.org):
    lein run -m cortex.engine-speed            measure, print
    lein run -m cortex.engine-speed --write    also write target/engines/ENGINE.edn
    lein run -m cortex.engine-speed --compare  print both engines' files side by side
    lein engines                               all three, jBullet then native"
  (:require [clojure.edn :as edn]
            [clojure.java.io :as io]
            [cortex.bench :refer [median]]
            [cortex.bench.creatures :as creatures]
            [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.sim :as sim]
            [cortex.blender]
            [cortex.util :as util]))

(set! *warn-on-reflection* true)

(def creatures
  "What is measured: name -> [a function making the creature, unbuilt,
  and the frames of one timed run]."
  {"worm" [#(util/load-blender-model "Models/test-creature/worm.blend") 600]
   "hand" [#(util/load-blender-model "Models/test-creature/hand.blend") 600]
   "chain-100" [#(creatures/creature (creatures/chain 100) 1.5) 60]
   "chain-300" [#(creatures/creature (creatures/chain 300) 1.5) 30]})


(defn build-ms
  "Median milliseconds of `body!` on a fresh creature from `make`, over
  three builds after one warm-up."
  [make]
  (let [once #(let [c (make) t0 (System/nanoTime)]
                (body/body! c)
                (/ (- (System/nanoTime) t0) 1e6))]
    (once)
    (median (repeatedly 3 once))))

(defn sim-seconds-per-second
  "Median simulated seconds per wall-clock second of the creature from
  `make` stepped `frames` times, over three runs after a warm-up."
  [make frames]
  (let [c (doto (make) (body/body!))
        s (sim/simulation c {:floor 0 :observe #{}})]
    (try
      (dotimes [_ (max 30 (quot frames 2))] (sim/step! s))
      (median (repeatedly 3 #(let [t0 (System/nanoTime)]
                               (dotimes [_ frames] (sim/step! s))
                               (/ (/ frames 60.0) (/ (- (System/nanoTime) t0) 1e9)))))
      (finally (sim/destroy! s)))))

(defn measure
  "{creature {:build-ms :sim-s-per-s}} on this engine."
  []
  (into (sorted-map)
        (for [[n [make frames]] creatures]
          [n {:build-ms (double (build-ms make))
              :sim-s-per-s (double (sim-seconds-per-second make frames))}])))

(defn- file-of ^java.io.File [e] (io/file "target/engines" (str (clojure.core/name e) ".edn")))

(defn compare-table
  "The text of both engines' measurements side by side, from
  target/engines/, with the native/jBullet ratios."
  []
  (let [[j n] (for [e [:jbullet :native] :let [f (file-of e)]]
                (if (.exists f)
                  (edn/read-string (slurp f))
                  (throw (ex-info (str (.getPath f) " is missing: run lein engines") {}))))
        row "| %-9s | %8.1f | %8.1f | %7.2f | %8.2f | %8.2f | %7.2f |"]
    (apply str
           (format "| %-9s | %8s | %8s | %7s | %8s | %8s | %7s |%n" "creature" "build ms" "build ms"
                   "ratio" "sim-s/s" "sim-s/s" "ratio")
           (format "| %-9s | %8s | %8s | %7s | %8s | %8s | %7s |%n" "" "jBullet" "native"
                   "jB/nat" "jBullet" "native" "nat/jB")
           (for [c (keys (:results j))
                 :let [a (get-in j [:results c]) b (get-in n [:results c])]]
             (format (str row "%n") c (:build-ms a) (:build-ms b)
                     (/ (:build-ms a) (:build-ms b))
                     (:sim-s-per-s a) (:sim-s-per-s b)
                     (/ (:sim-s-per-s b) (:sim-s-per-s a)))))))

(defn -main [& args]
  (let [args (set args)]
    (if (args "--compare")
      (print (compare-table))
      (let [results (measure)]
        (doseq [[c {:keys [build-ms sim-s-per-s]}] results]
          (println (format "%s %s build %.1f ms, %.3f sim-s/s" (clojure.core/name engine/name) c
                           build-ms sim-s-per-s)))
        (when (args "--write")
          (let [f (file-of engine/name)]
            (io/make-parents f)
            (spit f (pr-str {:engine engine/name :when (str (java.time.LocalDateTime/now))
                             :results results}))))))
    (flush)
    (shutdown-agents)
    (System/exit 0)))
