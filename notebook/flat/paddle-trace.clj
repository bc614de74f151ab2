(require 'cortex.blender '[cortex.util :as util] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.engine :as engine])
(let [c (doto (util/load-blender-model "test/fixtures/flat-strangers/flat-hexagon-paddle.blend") (.move (float 0) (float 0.5) (float 0)))
      _ (body/body! c)
      s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{:segments :joints}})
      obs (try (vec (repeatedly 600 #(sim/step! s nil))) (finally (sim/destroy! s)))]
  (doseq [i (range 300 600 20) :let [o (obs i)]]
    (println (format "%.2f s" (/ i 60.0))
             (for [[n {p :position v :velocity w :angular-velocity}] (:segments o)]
               (format "%s p(%.3f %.3f %.3f) v %.3f w(%.2f %.2f %.2f)" n (p 0) (p 1) (p 2) (Math/sqrt (reduce + (map * v v))) (w 0) (w 1) (w 2)))
             (pr-str (get-in o [:joints "wrist"])))))
(shutdown-agents) (System/exit 0)
