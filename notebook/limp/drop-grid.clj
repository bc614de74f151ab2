;; The four-legged creature (FILE) dropped by cortex.drops/drop! turned by each of HS (radians;
;; default [0.0 0.8 1.6 2.4]) on friction 0.25, 0.5 and 1; a row each, and how many were not at rest.
;; At rest = came to rest and moved under 0.02 m between 8 and 10 s. From the repository root:
;; HS="[0.2 0.6]" bin/lein run -m clojure.main notebook/limp/drop-grid.clj
(require '[cortex.blender] '[cortex.util :as util] '[cortex.drops :as drops])
(import '(com.jme3.math Quaternion))
(def f (or (System/getenv "FILE") "test/fixtures/designer/quadruped.blend"))
(def rows (for [h (read-string (or (System/getenv "HS") "[0.0 0.8 1.6 2.4]")) fr [0.25 0.5 1.0]]
  (let [c (util/load-blender-model f)]
    (.rotate c (doto (Quaternion.) (.fromAngles (float 0) (float h) (float 0))))
    (let [{:keys [fastest limit still-at moved energy-gain]} (drops/drop! c fr)]
      (format "h %.1f fr %.2f fastest %.2f/%.2f rest %s moved %.4f gain %.4f %s" h fr fastest limit still-at moved energy-gain
              (if (and still-at (< moved 0.02)) "at rest" "NOT AT REST"))))))
(doseq [r rows] (println "GRID" r))
(println "GRID not at rest:" (count (filter #(.endsWith ^String % "NOT AT REST") rows)))
(shutdown-agents) (System/exit 0)
