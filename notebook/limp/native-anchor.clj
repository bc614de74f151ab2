;; The four-legged creature dropped limp (unturned by default; HEADINGS, radians) on native Bullet for
;; SECS (10) seconds: its centre of mass every second. MODE sets the solver mode (cortex's is 261;
;; 277 adds a second friction direction), ANCHOR=1 gives every body Bullet's friction anchor
;; (CF_HAS_FRICTION_ANCHOR). Run from the repository root:
;; MODE=277 ANCHOR=1 bin/lein with-profile +native run -m clojure.main notebook/limp/native-anchor.clj
(require '[cortex.blender] '[cortex.util :as util] '[cortex.drops :as drops] '[cortex.plan :as plan] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.export :as ex] '[cortex.engine :as engine])
(import '(com.jme3.math Quaternion))
(def set-flags (doto (.getDeclaredMethod com.jme3.bullet.collision.PhysicsCollisionObject "setCollisionFlags" (into-array Class [Long/TYPE Integer/TYPE])) (.setAccessible true)))
(when (System/getenv "ANCHOR")
  (alter-var-root #'engine/add-all!
    (fn [f] (fn [space spatial]
              (f space spatial)
              (doseq [^com.jme3.bullet.objects.PhysicsRigidBody b (.getRigidBodyList ^com.jme3.bullet.PhysicsSpace space)]
                (.invoke set-flags nil (object-array [(.nativeId b) (int (bit-or (.collisionFlags b) 512))])))))))
(when-let [m (System/getenv "MODE")]
  (alter-var-root #'engine/configure-space!
    (fn [f] (fn [^com.jme3.bullet.PhysicsSpace space] (let [r (f space)] (.setMode (.getSolverInfo space) (int (Long/parseLong m))) r)))))
(let [f (or (System/getenv "FILE") "test/fixtures/designer/quadruped.blend")
      secs (Double/parseDouble (or (System/getenv "SECS") "10"))
      headings (read-string (or (System/getenv "HEADINGS") "[0.0]"))]
  (doseq [h headings]
    (let [c (util/load-blender-model f)]
      (.rotate c (doto (Quaternion.) (.fromAngles (float 0) (float h) (float 0))))
      (drops/lift! c)
      (let [p (plan/plan c)
            _ (when (System/getenv "WRITE") (ex/write! p (format "/tmp/q/q-%.2f.xml" h) (format "/tmp/q/q-%.2f.urdf" h)))
            _ (body/body! c)
            mass (into {} (map (juxt :id :mass)) (:segments p))
            total (reduce + (vals mass))
            s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{:segments}})
            obs (vec (repeatedly (long (* 60 secs)) #(sim/step! s {})))
            hh (fn [o] (/ (reduce + (for [[n {[_ y] :position}] (:segments o)] (* (mass n) y))) total))
            sp (fn [o] (apply max (for [[_ {v :velocity}] (:segments o)] (Math/sqrt (reduce + (map * v v))))))]
        (println (format "%s anchor=%s heading %.2f: 1 s %.3f, every s %s, end %.3f speed %.3f" engine/name (boolean (System/getenv "ANCHOR")) h (hh (obs 59))
                         (mapv #(format "%.3f" (hh (obs %))) (range 59 (count obs) 60)) (hh (peek obs)) (sp (peek obs))))
        (sim/destroy! s)))))
(shutdown-agents) (System/exit 0)
