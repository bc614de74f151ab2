;; The exporter's held drops (every hinge and cone told 0) for 7 s: steps after the first 2 s with a
;; segment over 0.05 m/s, the fastest then, and the fastest in the last half second.
;; bin/lein with-profile +test run -m clojure.main notebook/limp/held-jolts.clj
(require 'cortex.export-test '[cortex.engine :as engine])
(doseq [f ["hand" "worm" "quadruped" "humanoid"]]
  (let [[c plan] (#'cortex.export-test/placed f)
        held (#'cortex.export-test/held plan)
        mass (into {} (map (juxt :id :mass)) (:segments plan))
        s (cortex.sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{:segments}})
        speeds (vec (for [_ (range 420)]
                      (let [o (cortex.sim/step! s held)]
                        (apply max (for [[_ {v :velocity}] (:segments o)] (Math/sqrt (reduce + (map * v v))))))))]
    (println "HELD" engine/name f "steps over 0.05 after 2 s:" (count (filter #(> % 0.05) (subvec speeds 120)))
             "fastest after 2 s" (format "%.3f" (apply max (subvec speeds 120))) "last 0.5 s" (format "%.3f" (apply max (subvec speeds 390))))))
(shutdown-agents) (System/exit 0)
