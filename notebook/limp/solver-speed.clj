;; The strangers' humanoid lying (sleeping off, 3,000 steps to warm up) stepped with cortex's jBullet
;; contact setting and with jBullet's own solver (ERP 0.2), in one JVM, eleven interleaved rounds of
;; 2,000 steps: CPU microseconds a step and the median ratio. bin/lein run -m clojure.main notebook/limp/solver-speed.clj
(require 'cortex.blender '[cortex.util :as util] '[cortex.sim :as sim] '[cortex.body :as body])
(import '(java.lang.management ManagementFactory))
(def ^com.sun.management.ThreadMXBean th (ManagementFactory/getThreadMXBean))
(defn make [own?]
  (let [c (util/load-blender-model "test/fixtures/strangers/humanoid.blend")
        _ (body/body! c {:sleeping-thresholds [0 0]})
        s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{}})
        w ^com.bulletphysics.dynamics.DiscreteDynamicsWorld (.getDynamicsWorld ^com.jme3.bullet.PhysicsSpace (:space s))]
    (when own?
      (.setConstraintSolver w (com.bulletphysics.dynamics.constraintsolver.SequentialImpulseConstraintSolver.))
      (set! (.erp (.getSolverInfo w)) (float 0.2)))
    (dotimes [_ 3000] (sim/step! s {}))
    s))
(let [a (make false) b (make true)
      us (fn [s n] (let [c0 (.getCurrentThreadCpuTime th)] (dotimes [_ n] (sim/step! s {})) (/ (- (.getCurrentThreadCpuTime th) c0) 1e3 n)))
      rounds (vec (for [_ (range 11)] [(us a 2000) (us b 2000)]))]
  (doseq [[x y] rounds] (println (format "kept setting %.0f us/step, jBullet's own solver %.0f, ratio %.2f" x y (/ x y))))
  (println "median ratio" (nth (sort (map (fn [[x y]] (/ x y)) rounds)) 5)))
(shutdown-agents) (System/exit 0)
