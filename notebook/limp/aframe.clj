;; Two limp legs hinged at the top, standing on the floor as an A: each leg's foot needs a sideways
;; friction of (m g / 2) tan a, against mu m g, so it stands while tan a <= 2 mu (mu = 0.5 here:
;; a segment's friction times the floor's 1.0). Prints how far the feet moved apart from 1 s to
;; SECS (20) at each half-angle of DEGS (degrees). Sleeping is off.
;; DEGS="[30 40 44 46 50]" bin/lein with-profile +test run -m clojure.main notebook/limp/aframe.clj
(require '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.joint-fixtures :as f] '[cortex.util :as util] '[cortex.engine :as engine])
(import '(com.jme3.math Quaternion Vector3f))
(defn a-frame [deg]
  (let [a (Math/toRadians deg)
        up (+ (* 0.5 (Math/cos a)) (* 0.05 (Math/sin a)))
        apex (+ 0.002 up (* 0.5 (Math/cos a)))
        leg (fn [nm s] (doto (f/segment-node nm [(* s 0.5 (Math/sin a)) (- apex (* 0.5 (Math/cos a))) 0] [0.05 0.5 0.05] 1)
                         (.setLocalRotation (f/turned (* s a) [0 0 1]))))]
    (util/nodify "a-frame" [(leg "left" -1) (leg "right" 1)
                            (util/nodify "joints" [(f/joint-node "apex" [0 apex 0] Quaternion/IDENTITY
                                                                 "{:type :hinge :limit [-1.5 1.5] :axis (Vector3f. 0 1 0)}")])])))
(doseq [deg (read-string (or (System/getenv "DEGS") "[30 40 44 46 50]"))]
  (let [c (body/body! (a-frame deg) {:sleeping-thresholds [0 0]})
        s (sim/simulation c {:observe #{:segments} :floor {:height 0 :friction 1.0}})
        gap (fn [o] (- (get-in o [:segments "right" :position 0]) (get-in o [:segments "left" :position 0])))
        o1 (last (repeatedly 60 #(sim/step! s {})))
        secs (Double/parseDouble (or (System/getenv "SECS") "20"))
        o2 (last (repeatedly (long (* 60 (- secs 1))) #(sim/step! s {})))]
    (println (format "%s half-angle %d (tan %.3f, stands while <= 1): legs' centres %.4f m apart at 1 s, %.4f at %.0f s, apart by %.2e m more, apex at %.3f m"
                     engine/name deg (Math/tan (Math/toRadians deg)) (gap o1) (gap o2) secs (- (gap o2) (gap o1))
                     (double (get-in o2 [:segments "left" :position 1]))))
    (sim/destroy! s)))
(shutdown-agents) (System/exit 0)
