(require 'cortex.blender '[cortex.util :as util] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.engine :as engine])
(doseq [f ["leaf-walker" "flat-hexagon-paddle"] dy [0.5 0.8 1.0 1.003 1.006 1.2]]
  (let [c (doto (util/load-blender-model (str "test/fixtures/flat-strangers/" f ".blend")) (.move (float 0) (float dy) (float 0)))
        _ (body/body! c)
        s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{:segments}})
        obs (try (vec (repeatedly 600 #(sim/step! s nil))) (finally (sim/destroy! s)))
        fast (fn [a b] (apply max (for [o (subvec obs a b) [_ {v :velocity}] (:segments o)] (Math/sqrt (reduce + (map * v v))))))]
    (println engine/label f dy (format "fastest in 4.5-5 s %.3f, 9.5-10 s %.3f" (fast 270 300) (fast 570 600)))))
(shutdown-agents) (System/exit 0)
