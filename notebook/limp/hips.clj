(require 'cortex.blender '[cortex.body :as body] '[cortex.plan :as plan] '[cortex.sim :as sim] '[cortex.drops :as drops] '[cortex.util :as util] '[cortex.proprioception :as p] '[cortex.engine :as engine])
(def sopts (read-string (or (System/getenv "SOPTS") "{}")))
(when (System/getenv "NOROWS") (alter-var-root #'cortex.engine/limit-rows! (fn [_] (fn [j _] j))))
(def c (util/load-blender-model "test/fixtures/designer/quadruped.blend"))
(let [[lo] (drops/extent c)] (.move c 0 (float (- 1.0 (double lo))) 0))
(body/body! c {})
(def described (into {} (map (juxt :name :description)) (body/joint-records c)))
(def sensors (into {} (map (juxt :name identity)) (p/sensors c)))
(def s (sim/simulation c (merge {:floor {:height 0 :friction 1.0} :observe #{:segments}} sopts)))
(println engine/label sopts)
(def hips ["hip-front-l" "hip-back-l" "hip-front-r" "hip-back-r"])
(dotimes [i 300]
  (let [o (sim/step! s) t (/ (inc i) 60.0)]
    (when (and (>= t 2.0) (zero? (mod (inc i) 6)))
      (print (format "%4.1f up %.2f" t (second (p/rotate (:rotation ((:segments o) "torso")) [0 1 0]))))
      (doseq [h hips :let [se (sensors h) {[sy sz] :swing tw :twist} (p/joint-state se) [[ex ey ez]] (drops/cone-angles se (described h))]]
        (print (format " | %s st %5.2f %5.2f %5.2f eu %5.2f %5.2f %5.2f" (subs h 4) tw sy sz ex ey ez)))
      (println))))
(shutdown-agents)
