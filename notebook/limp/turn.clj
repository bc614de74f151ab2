;; Drop a creature turned about the vertical by each of HEADINGS (radians), limp, for SECS
;; seconds, printing its centre of mass after 1 s, every 2 s and at the end; with WRITE=1 also
;; write each turned pose as MJCF to /tmp/q/TAG-HEADING.xml for mjturn.py; THR turns on jBullet's
;; split impulse with that penetration threshold (e.g. -0.04). Run from the repository root:
;; HEADINGS="[0.0 0.5]" SECS=16 WRITE=1 bin/lein run -m clojure.main notebook/limp/turn.clj
(require '[cortex.blender] '[cortex.util :as util] '[cortex.drops :as drops] '[cortex.plan :as plan] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.export :as ex] '[cortex.engine :as engine])
(import '(com.jme3.math Quaternion))
(when-let [thr (some-> (System/getenv "THR") Double/parseDouble)]
  (alter-var-root #'engine/configure-space!
    (fn [f] (fn [^com.jme3.bullet.PhysicsSpace space]
              (let [r (f space)
                    info (.getSolverInfo (.getDynamicsWorld space))]
                (set! (.splitImpulse info) true)
                (set! (.splitImpulsePenetrationThreshold info) (float thr))
                r)))))
(let [f (or (System/getenv "FILE") "test/fixtures/designer/quadruped.blend")
      tag (or (System/getenv "TAG") "q")
      secs (Double/parseDouble (or (System/getenv "SECS") "10"))
      headings (read-string (or (System/getenv "HEADINGS") "[0.0 0.1 0.2 0.4 0.5 0.6 0.7 0.8 0.9 1.1 1.2 1.4]"))]
  (doseq [h headings]
    (let [c (util/load-blender-model f)]
      (.rotate c (doto (Quaternion.) (.fromAngles (float 0) (float h) (float 0))))
      (drops/lift! c)
      (let [p (plan/plan c)
            _ (when (System/getenv "WRITE") (ex/write! p (format "/tmp/q/%s-%.2f.xml" tag h) (format "/tmp/q/%s-%.2f.urdf" tag h)))
            _ (body/body! c)
            mass (into {} (map (juxt :id :mass)) (:segments p))
            total (reduce + (vals mass))
            s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{:segments}})
            obs (vec (repeatedly (long (* 60 secs)) #(sim/step! s {})))
            hh (fn [o] (/ (reduce + (for [[n {[_ y] :position}] (:segments o)] (* (mass n) y))) total))]
        (println (format "%s %s heading %.2f: 1 s %.3f, every 2 s %s, end %.3f" engine/name tag h (hh (obs 59))
                         (mapv #(format "%.3f" (hh (obs %))) (range 119 (count obs) 120)) (hh (peek obs))))
        (sim/destroy! s)))))
(shutdown-agents) (System/exit 0)
