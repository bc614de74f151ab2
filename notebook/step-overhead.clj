;; What cortex adds to a native Bullet step beside observing: its tick listeners (speculative hinge
;; limits, torques as impulses) and the space's lists, in this thread's CPU microseconds, for the
;; strangers' humanoid and the clipped humanoid 2 s into a drop, three rounds.
;; bin/lein with-profile +native run -m clojure.main notebook/step-overhead.clj
(require 'cortex.blender '[cortex.util :as util] '[cortex.sim :as sim] '[cortex.engine :as engine])
(import '(java.lang.management ManagementFactory))
(def ^com.sun.management.ThreadMXBean th (ManagementFactory/getThreadMXBean))
(defn us [n f] (let [c0 (.getCurrentThreadCpuTime th)] (dotimes [_ n] (f)) (/ (- (.getCurrentThreadCpuTime th) c0) 1e3 n)))
(doseq [path ["test/fixtures/strangers/humanoid.blend" "test/fixtures/humanoid/humanoid.blend"]]
  (let [s (sim/simulation (util/load-blender-model path) {:floor {:height 0 :friction 1.0} :observe #{}})
        space ^com.jme3.bullet.PhysicsSpace (:space s)
        spec (ns-resolve 'cortex.engine 'speculate!)
        tai (ns-resolve 'cortex.engine 'torques-as-impulses!)
        held (java.util.ArrayList.)]
    (dotimes [_ 120] (sim/step! s))
    (dotimes [r 3]
      (println path engine/name
               (format "step %.1f  speculate %s  torques %s  distributeEvents %.2f  jointlist %.2f  bodylist %.2f"
                       (us 2000 #(sim/step! s))
                       (when spec (format "%.2f" (us 20000 #(spec space))))
                       (when tai (format "%.2f" (us 20000 #(tai space (/ 1.0 60) held))))
                       (us 20000 #(.distributeEvents space))
                       (us 20000 #(.getJointList space))
                       (us 20000 #(.getRigidBodyList space)))))
    (sim/destroy! s)))
(shutdown-agents) (System/exit 0)
