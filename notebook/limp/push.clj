;; The limp four-legged creature dropped turned by H (radians) on friction 1.0, pushed sideways as a
;; whole by each of PUSHES (m/s) at AT seconds, then left until SECS; prints each push's end (belly
;; or side, from the torso's up) and the torso's fastest speed during the fall onto the belly.
;; AWAKE=1 turns sleeping off; WAKE=1 turns it off at the push.
;; H=1.5708 PUSHES="[0.02 0.05 0.1 0.2 0.4]" bin/lein run -m clojure.main notebook/limp/push.clj
(require '[cortex.blender] 'cortex.segment '[cortex.util :as util] '[cortex.drops :as drops] '[cortex.plan :as plan] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.engine :as engine])
(import '(com.jme3.math Quaternion Vector3f) '(com.jme3.bullet.control RigidBodyControl) '(com.jme3.scene Node Spatial))
(let [h (Double/parseDouble (or (System/getenv "H") "1.5708"))
      at (Double/parseDouble (or (System/getenv "AT") "8"))
      secs (Double/parseDouble (or (System/getenv "SECS") "30"))]
  (doseq [push (read-string (or (System/getenv "PUSHES") "[0.02 0.05 0.1 0.2 0.4]"))]
    (let [c (util/load-blender-model "test/fixtures/designer/quadruped.blend")]
      (.rotate c (doto (Quaternion.) (.fromAngles (float 0) (float h) (float 0))))
      (drops/lift! c)
      (let [p (plan/plan c)
            _ (if (System/getenv "AWAKE") (body/body! c {:sleeping-thresholds [0 0]}) (body/body! c))
            mass (into {} (map (juxt :id :mass)) (:segments p))
            total (reduce + (vals mass))
            s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{:segments}})
            side (Vector3f. (float (Math/sin h)) 0 (float (Math/cos h)))
            controls (keep #(.getControl ^Spatial % RigidBodyControl) (cortex.segment/segments c))
            fastest (atom 0.0)
            run (fn [n] (last (repeatedly n #(let [o (sim/step! s {})
                                                   v (get-in o [:segments "torso" :velocity])]
                                               (when (< 1.2 (sim/sim-time s) at)
                                                 (swap! fastest max (Math/sqrt (reduce + (map * v v)))))
                                               o))))
            up (fn [o] (let [q (get-in o [:segments "torso" :rotation])
                             r (.mult (Quaternion. (float (q 0)) (float (q 1)) (float (q 2)) (float (q 3))) Vector3f/UNIT_Y)]
                         (.y r)))
            across (fn [o] (mapv #(/ % total) (reduce (fn [acc [n {q :position}]] (mapv + acc (map (fn [x] (* (mass n) x)) q))) [0.0 0.0 0.0] (:segments o))))
            hh (fn [o] (/ (reduce + (for [[n {[_ y] :position}] (:segments o)] (* (mass n) y))) total))
            before (run (long (* 60 at)))]
        (println "bodies pushed:" (count controls))
        (doseq [^RigidBodyControl rb controls]
          (when (System/getenv "WAKE") (.setSleepingThresholds rb 0 0))
          (.activate rb)
          (.setLinearVelocity rb (.add (.getLinearVelocity rb) (.mult side (float push)))))
        (let [o (run (long (* 60 (- secs at))))]
          (println (format "%s heading %.2f scale %s: torso fastest %.2f m/s falling; at %.0f s %.3f m up (%s); pushed %.2f m/s: at %.0f s %.3f m up (%s), moved %.3f m"
                           engine/name h (sim/scale s) @fastest at (hh before) (if (> (up before) 0.5) "belly" "side")
                           push secs (hh o) (if (> (up o) 0.5) "belly" "side")
                           (let [a (across before) b (across o)] (Math/sqrt (+ (Math/pow (- (a 0) (b 0)) 2) (Math/pow (- (a 2) (b 2)) 2)))))))
        (sim/destroy! s)))))
(shutdown-agents) (System/exit 0)
