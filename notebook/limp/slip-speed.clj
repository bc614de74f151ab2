;; The cost of taking back slip: the strangers' humanoid lying (sleeping off, 3,000 steps to warm up)
;; stepped with cortex's jBullet contacts as kept (slip taken back at the contact ERP) and with the
;; same solver taking back none, in one JVM, eleven interleaved rounds of 2,000 steps: CPU
;; microseconds a step and the median ratio. bin/lein run -m clojure.main notebook/limp/slip-speed.clj
(require 'cortex.blender '[cortex.util :as util] '[cortex.sim :as sim] '[cortex.body :as body])
(import '(java.lang.management ManagementFactory))
(def ^com.sun.management.ThreadMXBean th (ManagementFactory/getThreadMXBean))
(defn make [slip]
  (let [c (util/load-blender-model "test/fixtures/strangers/humanoid.blend")
        _ (body/body! c {:sleeping-thresholds [0 0]})
        s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{}})
        w ^com.bulletphysics.dynamics.DiscreteDynamicsWorld (.getDynamicsWorld ^com.jme3.bullet.PhysicsSpace (:space s))]
    (.setConstraintSolver w (cortex.BlenderContactSolver. true (float slip)))
    (dotimes [_ 3000] (sim/step! s {}))
    s))
(let [a (make 0.1) b (make 0.0)
      us (fn [s n] (let [c0 (.getCurrentThreadCpuTime th)] (dotimes [_ n] (sim/step! s {})) (/ (- (.getCurrentThreadCpuTime th) c0) 1e3 n)))
      rounds (vec (for [_ (range 11)] [(us a 2000) (us b 2000)]))]
  (doseq [[x y] rounds] (println (format "slip taken back %.0f us/step, none %.0f, ratio %.2f" x y (/ x y))))
  (println "median ratio" (nth (sort (map (fn [[x y]] (/ x y)) rounds)) 5)))
(shutdown-agents) (System/exit 0)
