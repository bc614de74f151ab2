(require 'cortex.blender '[cortex.body :as body] '[cortex.plan :as plan] '[cortex.sim :as sim] '[cortex.drops :as drops] '[cortex.util :as util] '[cortex.proprioception :as p] '[cortex.engine :as engine])
(def opts (read-string (or (System/getenv "OPTS") "{}")))
(def sopts (read-string (or (System/getenv "SOPTS") "{}")))
(def n (Long/parseLong (or (System/getenv "N") "6")))
(def secs (Double/parseDouble (or (System/getenv "SECS") "7")))
(def file (or (System/getenv "FILE") "test/fixtures/designer/quadruped.blend"))
(when-let [e (System/getenv "ROWERP")]
  (alter-var-root #'cortex.engine/limit-rows!
    (fn [f] (fn [j spec] (f j spec) (let [[_ l] (.get ^java.util.Map @(resolve 'cortex.engine/limit-rows) j)] (clojure.lang.Reflector/setInstanceField l "erp" (float (Double/parseDouble e)))) j))))
(when (System/getenv "NOROWS") (alter-var-root #'cortex.engine/limit-rows! (fn [_] (fn [j _] j))))
(defn one [k]
  (let [c (util/load-blender-model file)
        [lo] (drops/extent c)]
    (.move c 0 (float (+ (* k 0.003) (- 1.0 (double lo)))) 0)
    (let [pl (plan/plan c opts)
          _ (body/body! c opts)
          mass (into {} (map (juxt :id :mass)) (:segments pl))
          total (reduce + (vals mass))
          s (sim/simulation c (merge {:floor {:height 0 :friction 1.0} :observe #{:segments}} sopts))
          _ (when (System/getenv "BOXBOX") (clojure.lang.Reflector/invokeStaticMethod "cortex.BoxBoxAlgorithm" "register" (object-array [(.getDispatcher ^com.bulletphysics.dynamics.DynamicsWorld (.getDynamicsWorld ^com.jme3.bullet.PhysicsSpace (:space s)))])))
          _ (when (System/getenv "BLENDERSOLVER") (cortex.engine/blender-solver-order! (:space s)))
          steps (long (* 60 secs))
          res (loop [i 0 still nil last nil]
                (if (= i steps) [last still]
                    (let [o (sim/step! s)
                          v (apply max (for [[_ {v :velocity}] (:segments o)] (Math/sqrt (reduce + (map * v v)))))]
                      (recur (inc i) (if (< v 0.1) (or still (/ (inc i) 60.0)) nil) o))))
          [o still] res
          com (/ (reduce + (for [[nm {[_ y] :position}] (:segments o)] (* (mass nm) y))) total)
          up (if-let [tt ((:segments o) "torso")] (second (p/rotate (:rotation tt) [0 1 0])) 1.0)]
      (sim/destroy! s)
      (format "%.3f/%s%s" com (if (> up 0.5) "belly" "SIDE") (if still (format "@%.1f" still) "/moving")))))
(println (System/getenv "LABEL") engine/label opts sopts (System/getenv "ROWERP") (System/getenv "NOROWS"))
(println "  " (clojure.string/join " " (map one (range n))))
(shutdown-agents)
