;; exact energy per step of the limp paddle; print steps where it rises
(require 'cortex.blender '[cortex.util :as util] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.engine :as engine] '[cortex.segment :as segment])
(import '(com.jme3.bullet.control RigidBodyControl) '(com.jme3.scene Geometry) '(com.jme3.math Quaternion Vector3f))
(def lift (Double/parseDouble (or (System/getenv "LIFT") "0.5")))
(let [c (doto (util/load-blender-model "test/fixtures/flat-strangers/flat-hexagon-paddle.blend") (.move (float 0) (float lift) (float 0)))
      _ (body/body! c)
      rcs (vec (for [g (segment/segments c)] (.getControl ^Geometry g RigidBodyControl)))
      s (sim/simulation c {:floor {:height 0 :friction (Double/parseDouble (or (System/getenv "FR") "1.0"))} :observe #{:joints}})
      energy (fn [] (reduce + (for [^RigidBodyControl rc rcs
                                    :let [m (.getMass rc) rb (engine/rigid-body rc)
                                          [a b c3] (engine/inverse-inertia rb)
                                          v (.getLinearVelocity rc) w (.getAngularVelocity rc)
                                          q (.getPhysicsRotation rc)
                                          wl (.mult (.inverse q) w)
                                          p (.getPhysicsLocation rc)]]
                                (+ (* 0.5 m (.lengthSquared v)) (* m 9.81 (.y p))
                                   (* 0.5 (+ (/ (* (.x wl) (.x wl)) a) (/ (* (.y wl) (.y wl)) b) (/ (* (.z wl) (.z wl)) c3)))))))
      rises (atom [])]
  (try
    (loop [i 0 e0 (energy)]
      (when (< i 600)
        (let [o (sim/step! s nil) e (energy)
              {:keys [angle velocity]} (get-in o [:joints "wrist"])]
          (when (and (> i 120) (> (- e e0) 0.002))
            (println (format "step %d: E %.4f -> %.4f (+%.4f) wrist %.3f %.2f" i e0 e (- e e0) angle velocity)))
          (swap! rises conj (- e e0))
          (recur (inc i) e))))
    (println "total rise after 2 s" (reduce + (filter pos? (drop 120 @rises))) "total fall" (reduce + (filter neg? (drop 120 @rises))))
    (finally (sim/destroy! s))))
(shutdown-agents) (System/exit 0)
