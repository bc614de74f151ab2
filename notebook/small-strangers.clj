;; The strangers at 1 and at 0.01 dropped from 5% of their height, limp, 10 s: the mean centre of
;; their segments and the fastest segment, times k (100 for the small ones); SUBS sets the substeps.
;; bin/lein run -m clojure.main notebook/small-strangers.clj (each at its own size, :scale 1)
(require 'cortex.blender '[cortex.util :as util] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.drops :as drops] '[cortex.engine :as engine])
(def subs (some-> (System/getenv "SUBS") Long/parseLong))
(doseq [[f k] [["worm-eye" 1] ["worm-eye-0.01" 100] ["hand" 1] ["hand-0.01" 100] ["humanoid" 1] ["humanoid-0.01" 100]]]
  (let [c (util/load-blender-model (str "test/fixtures/strangers/" f ".blend"))
        [lo hi] (drops/extent c)
        _ (.move c 0 (float (+ (- lo) (* 0.05 (- hi lo)))) 0)
        _ (body/body! c)
        s (sim/simulation c (cond-> {:floor {:height 0 :friction 1.0} :observe #{:segments} :scale 1} subs (assoc :solver {:substeps subs})))
        obs (vec (repeatedly 600 #(sim/step! s {})))
        fast (fn [os] (apply max (for [o os [n {v :velocity}] (:segments o)] (Math/sqrt (reduce + (map * v v))))))
        segs (:segments (peek obs))
        com (/ (reduce + (for [[_ {[_ y] :position}] segs] y)) (count segs))]
    (println "TINY" engine/name f "substeps" (:substeps (sim/solver s)) (format "mean centre x k %.5f  fastest 9-10 s x k %.4f  fastest 5-10 s x k %.4f" (* k com) (* k (fast (subvec obs 540))) (* k (fast (subvec obs 300)))))
    (sim/destroy! s)))
(shutdown-agents) (System/exit 0)
