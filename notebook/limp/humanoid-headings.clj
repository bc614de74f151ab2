;; The limp strangers' humanoid dropped turned by each of HEADINGS (radians; default 12 of 30
;; degrees): its centre of mass after 1 s and at SECS (5). THR turns on jBullet's split impulse with
;; that threshold. bin/lein run -m clojure.main notebook/limp/humanoid-headings.clj
(require '[cortex.blender] '[cortex.util :as util] '[cortex.drops :as drops] '[cortex.plan :as plan] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.engine :as engine])
(import '(com.jme3.math Quaternion))
(def thr (some-> (System/getenv "THR") Double/parseDouble))
(when thr
  (alter-var-root #'engine/configure-space!
    (fn [f] (fn [^com.jme3.bullet.PhysicsSpace space]
              (let [r (f space)
                    info (.getSolverInfo (.getDynamicsWorld space))]
                (set! (.splitImpulse info) true)
                (set! (.splitImpulsePenetrationThreshold info) (float thr))
                r)))))
(let [f (or (System/getenv "FILE") "test/fixtures/strangers/humanoid.blend")
      secs (Double/parseDouble (or (System/getenv "SECS") "5"))
      headings (read-string (or (System/getenv "HEADINGS") "[0.0 0.5236 1.0472 1.5708 2.0944 2.618 3.1416 3.6652 4.1888 4.7124 5.236 5.7596]"))]
  (doseq [h headings]
    (let [c (util/load-blender-model f)]
      (.rotate c (doto (Quaternion.) (.fromAngles (float 0) (float h) (float 0))))
      (drops/lift! c)
      (let [p (plan/plan c)
            _ (body/body! c)
            mass (into {} (map (juxt :id :mass)) (:segments p))
            total (reduce + (vals mass))
            s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{:segments}})
            obs (vec (repeatedly (long (* 60 secs)) #(sim/step! s {})))
            hh (fn [o] (/ (reduce + (for [[n {[_ y] :position}] (:segments o)] (* (mass n) y))) total))]
        (println (format "%s thr %s heading %.2f: 1 s %.3f, end %.3f" engine/name thr h (hh (obs 59)) (hh (peek obs))))
        (sim/destroy! s)))))
(shutdown-agents) (System/exit 0)
