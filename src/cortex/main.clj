(ns cortex.main
  "What `lein run` does."
  (:require [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.math Vector3f)))

(defn -main
  "Drop a box onto a floor in a headless world for two simulated
  seconds and say where it came to rest."
  [& _]
  (let [b (util/box 0.5 0.5 0.5 :position (Vector3f. 0 4 0) :name "box")
        floor (util/box 10 1 10 :position (Vector3f. 0 -1 0) :mass 0 :name "floor")
        w (world/world (util/nodify [b floor]) {}
                       #(world/set-gravity % (Vector3f. 0 -9.81 0))
                       world/no-op)]
    (world/run-world! w 120)
    (println "ran" (:frames @w) "frames (2 simulated seconds) headless;"
             "the box fell from y = 4 to y =" (.y (.getWorldTranslation b)))
    (shutdown-agents)))
