;; The friction test's box (cortex.physics-trust-test/friction-is-coulombs) at each of DEGS degrees:
;; its acceleration from 1 s to 3 s and its centre's lowest height (0.2 at rest); HALF sets the
;; floor's half width (cortex's: 200). DEGS="[30 35 45]" bin/lein with-profile +test run -m clojure.main notebook/limp/friction-box.clj
(require '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.joint-fixtures :as f] '[cortex.util :as util])
(import '(com.jme3.math Vector3f ColorRGBA))

(def half (Double/parseDouble (or (System/getenv "HALF") "200")))
(alter-var-root #'sim/floor (fn [_] (fn [spec] (let [{:keys [height friction] :or {friction 0.5}} (if (map? spec) spec {:height spec})]
    (util/box half 0.5 half :position (Vector3f. 0 (- (float height) 0.5) 0) :color ColorRGBA/Gray :mass 0 :name "floor" :friction friction)))))
(defn run [deg]
 (let [c (body/body! (f/chain 1 0.2) {:sleeping-thresholds [0 0]})
      a (Math/toRadians deg) g 9.81
      s (sim/simulation c {:observe #{:segments} :floor {:height 0 :friction 1.0}
                           :gravity [(* g (Math/sin a)) (- (* g (Math/cos a))) 0]})
      ys (atom [])
      speed (fn [steps] (get-in (last (repeatedly steps #(let [o (sim/step! s {})] (swap! ys conj (get-in o [:segments "seg-0" :position 1])) o))) [:segments "seg-0" :velocity 0]))
      v1 (speed 60) v3 (speed 120)]
  (println "half" half deg v1 v3 (/ (- v3 v1) 2.0) "lowest y" (apply min @ys))))
(doseq [d (read-string (System/getenv "DEGS"))] (run d))
(shutdown-agents) (System/exit 0)
