;; Generated from org/shapes.org by lein tangle: edit the chapter, not this file.
(ns cortex.shape-figures
  "The figures behind cortex.shapes' tolerances: lein run -m
  cortex.shape-figures prints them as the shapes chapter's table."
  (:require [cortex.blender :as blender]
            [cortex.shapes :as shapes]
            [cortex.util :as util])
  (:import (com.jme3.scene Geometry)))

(set! *warn-on-reflection* true)

(def pieces
  "[fixture segment, what it was drawn as, how the table names it]."
  [["uv-sphere" :sphere "UV sphere 32 x 16 (default)"]
   ["uv-sphere-16" :sphere "UV sphere 16 x 8"]
   ["icosphere" :sphere "icosphere, 2 subdivisions (default)"]
   ["icosphere-3" :sphere "icosphere, 3 subdivisions"]
   ["cylinder-10" :cylinder "cylinder, 10 sides"]
   ["cylinder-8" :cylinder "cylinder, 8 sides"]
   ["capsule-10" :capsule "capsule, 10 sides, rings 30 deg apart"]
   ["cylinder-6" :cylinder "cylinder, 6 sides (a hex prism)"]
   ["uv-sphere-8" :sphere "UV sphere 8 x 4"]
   ["icosphere-1" :sphere "icosphere, 1 subdivision (a d20)"]])

(defn rows
  "[name face-depth volume-difference verdict] for each of `pieces`."
  []
  (let [gs (into {} (for [g (util/node-seq (blender/load-blender-model "test/fixtures/shapes/shapes.blend"))
                          :when (instance? Geometry g)]
                      ;; a mesh object's Geometry hangs from a Node named as the object
                      [(.getName (.getParent ^Geometry g)) g]))
        open {:tolerance 1.0 :volume-tolerance 1.0 :face-tolerance 1.0}]
    (for [[id drawn label] pieces
          :let [piece (first (shapes/pieces (shapes/triangles (gs id))))
                best (apply min-key :face-deviation
                            (filter #(and (= drawn (:type %)) (:face-deviation %))
                                    (shapes/judge piece open)))]]
      [label (:face-deviation best) (:volume-difference best) (:type (shapes/fit piece))])))

(defn -main [& _]
  (println "| piece                               | face depth | volume diff. | verdict   |")
  (println "|-------------------------------------+------------+--------------+-----------|")
  (doseq [[label fd dv verdict] (rows)]
    (println (format "| %-35s | %10.3f | %12.3f | %-9s |" label (double fd) (double dv) (name verdict))))
  (shutdown-agents))
