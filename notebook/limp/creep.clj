;; The friction test's box on a slope of 10, 20 and 25 degrees (its friction 0.5: 26.6 degrees), the
;; slope turned 0, 30 and 45 degrees about the vertical: how far it moves from 1 s to 11 s, sleeping off.
;; bin/lein with-profile +test run -m clojure.main notebook/limp/creep.clj (add +native for native Bullet)
(require '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.joint-fixtures :as f] '[cortex.engine :as engine])
(defn run [deg az]
 (let [c (body/body! (f/chain 1 0.2) {:sleeping-thresholds [0 0]})
      a (Math/toRadians deg) g 9.81 az (Math/toRadians az)
      s (sim/simulation c {:observe #{:segments} :floor {:height 0 :friction 1.0}
                           :gravity [(* g (Math/sin a) (Math/cos az)) (- (* g (Math/cos a))) (* g (Math/sin a) (Math/sin az))]})
      pos (fn [steps] (get-in (last (repeatedly steps #(sim/step! s {}))) [:segments "seg-0" :position]))
      p1 (pos 60) p11 (pos 600)
      d (Math/sqrt (reduce + (map #(let [x (- %1 %2)] (* x x)) p11 p1)))]
  (println engine/name "slope" deg "azimuth" (Math/round (Math/toDegrees az)) "moved from 1 s to 11 s:" (format "%.2e m" d))
  (sim/destroy! s)))
(doseq [d [10 20 25] az [0 30 45]] (run d az))
(shutdown-agents) (System/exit 0)
