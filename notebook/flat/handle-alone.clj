;; the strangers' paddle with its blade (and wrist) taken out: the handle alone, a cylinder primitive lying on the floor, given 10 rad/s about its axis; its spin and height every half second
(require 'cortex.blender '[cortex.util :as util] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.engine :as engine] '[cortex.segment :as segment])
(import '(com.jme3.bullet.control RigidBodyControl) '(com.jme3.scene Geometry Node Spatial) '(com.jme3.math Quaternion Vector3f))
(let [c (util/load-blender-model "test/fixtures/flat-strangers/flat-hexagon-paddle.blend")
      _ (doseq [^Spatial sp (vec (.descendantMatches ^Node c Spatial))
                :when (and (#{"paddle" "wrist"} (.getName sp)) (.getParent sp))]
          (.removeFromParent sp))
      _ (.move c (float 0) (float 0.001) (float 0))
      _ (body/body! c)
      rcs (vec (for [g (segment/segments c)] (.getControl ^Geometry g RigidBodyControl)))
      _ (println "segments" (map segment/segment-name (segment/segments c)))
      s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{}})]
  (dotimes [_ 30] (sim/step! s nil))
  (.setAngularVelocity ^RigidBodyControl (first rcs) (Vector3f. 10 0 0))
  (.activate ^RigidBodyControl (first rcs))
  (doseq [i (range 600)]
    (sim/step! s nil)
    (when (zero? (mod i 30))
      (let [^RigidBodyControl rc (first rcs)] (println (format "%.1f s w %s v %s y %.4f" (/ i 60.0) (.getAngularVelocity rc) (.getLinearVelocity rc) (.y (.getPhysicsLocation rc)))))))
  (sim/destroy! s))
(shutdown-agents) (System/exit 0)
