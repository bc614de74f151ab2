;; The limp strangers' humanoid's pelvis, waist and torso, height and vertical speed, every step
;; from 20 to 60: the landing. bin/lein run -m clojure.main notebook/limp/landing-trace.clj
;; (with-profile +native for native Bullet); MuJoCo's is landing_trace.py.
(require '[cortex.blender] '[cortex.util :as util] '[cortex.drops :as drops] '[cortex.plan :as plan] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.engine :as engine])
(let [c (util/load-blender-model "test/fixtures/strangers/humanoid.blend")]
  (drops/lift! c)
  (body/body! c)
  (let [s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{:segments}})
        obs (vec (repeatedly 60 #(sim/step! s {})))]
    (doseq [i (range 20 60)]
      (let [o (obs i) segs (:segments o)]
        (println (format "%s %d pelvis y %.4f vy %.3f | lwaist y %.4f | torso y %.4f vy %.3f" engine/name i
                         (get-in segs ["pelvis" :position 1]) (get-in segs ["pelvis" :velocity 1])
                         (get-in segs ["lwaist" :position 1])
                         (get-in segs ["torso" :position 1]) (get-in segs ["torso" :velocity 1])))))))
(shutdown-agents) (System/exit 0)
