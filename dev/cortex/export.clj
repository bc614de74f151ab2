;; Generated from org/physics-trust.org by lein tangle: edit the chapter, not this file.
(ns cortex.export
  "A creature placed and built as the drop test does it, written as JSON
  for scripts/compare/quadruped_whip.py (the physics-trust chapter).

  Entry point: `-main` (lein run -m cortex.export FILE.blend OUT.json)."
  (:require [clojure.java.io :as io]
            [cortex.compare :as compare]
            [cortex.physics-trust-test :as trust]
            [cortex.util :as util]))

(set! *warn-on-reflection* true)

(defn -main
  "lein run -m cortex.export FILE.blend OUT.json"
  [file out]
  (let [data (trust/export (util/load-blender-model file))]
    (io/make-parents (io/file out))
    (spit out (compare/json data))
    (println "wrote" out)
    (shutdown-agents)))
