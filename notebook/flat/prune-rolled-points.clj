;; Experiment (not kept): the lying cylinders of lying-cylinder.clj, with PRUNE=alpha (rad): before every physics tick, a
;; contact point whose spot on the cylinder has turned more than alpha from facing along the contact normal leaves the
;; manifold (jBullet: removed; native Bullet: its local point moved far off, so that the refresh drops it). RS radii.
(require '[cortex.engine :as engine] '[cortex.shapes :as shapes] '[cortex.sim :as sim])
(import '(com.jme3.bullet.objects PhysicsRigidBody) '(com.jme3.math Vector3f Quaternion) '(com.jme3.bullet.collision.shapes CollisionShape)
        '(com.jme3.bullet PhysicsTickListener))
(defn env [k d] (or (System/getenv k) d))
(def native? (= :native engine/name))
(defn facing-cos
  "cos of the angle between the contact normal n (world) and the cylinder's surface normal at local point lp (X axis cylinder)"
  ^double [^Quaternion q ^Vector3f lp ^Vector3f n]
  (let [radial (Vector3f. 0 (.y lp) (.z lp))]
    (if (< (.length radial) 1e-9) 1.0
        (Math/abs (.dot (.mult q (.normalize radial)) n)))))
(def prune-native
  (when native?
    (eval '(fn [space ^com.jme3.bullet.objects.PhysicsRigidBody body cosa]
    (doseq [m (seq (.listManifoldIds space))
            :let [a (com.jme3.bullet.collision.PersistentManifolds/getBodyAId m)
                  b (com.jme3.bullet.collision.PersistentManifolds/getBodyBId m)
                  mine-a? (= a (.nativeId body)) mine-b? (= b (.nativeId body))]
            :when (or mine-a? mine-b?)
            p (seq (com.jme3.bullet.collision.PersistentManifolds/listPointIds m))]
      (let [lp (Vector3f.) n (Vector3f.)]
        (if mine-a? (com.jme3.bullet.collision.ManifoldPoints/getLocalPointA p lp) (com.jme3.bullet.collision.ManifoldPoints/getLocalPointB p lp))
        (com.jme3.bullet.collision.ManifoldPoints/getNormalWorldOnB p n)
        (when (< (user/facing-cos (.getPhysicsRotation body) lp n) cosa)
          ;; moved far off: the manifold's refresh drops it
          (let [far (Vector3f. 1000 1000 1000)]
            (if mine-a? (com.jme3.bullet.collision.ManifoldPoints/setLocalPointA p far) (com.jme3.bullet.collision.ManifoldPoints/setLocalPointB p far))))))))))
(def prune-jbullet
  (when-not native?
    (eval '(fn [space ^com.jme3.bullet.objects.PhysicsRigidBody body cosa]
    (let [disp (.getDispatcher (.getDynamicsWorld space)) rb (engine/rigid-body body)]
      (dotimes [i (.getNumManifolds disp)]
        (let [mf (.getManifoldByIndexInternal disp i)
              mine-a? (identical? (.getBody0 mf) rb) mine-b? (identical? (.getBody1 mf) rb)]
          (when (or mine-a? mine-b?)
            (doseq [k (reverse (range (.getNumContacts mf)))]
              (let [pt (.getContactPoint mf k)
                    l (if mine-a? (.-localPointA pt) (.-localPointB pt))
                    nn (.-normalWorldOnB pt)]
                (when (< (user/facing-cos (.getPhysicsRotation body) (Vector3f. (.x l) (.y l) (.z l)) (Vector3f. (.x nn) (.y nn) (.z nn))) cosa)
                  (.removeContactPoint mf k))))))))))))
(defn prune! [space body cosa] (if native? (prune-native space body cosa) (prune-jbullet space body cosa)))
(doseq [r (map #(Double/parseDouble %) (clojure.string/split (env "RS" "0.03 0.1 0.3") #" ")) spin [0.0 10.0]]
  (let [space (sim/physics-space)
        _ (engine/add-all! space (sim/floor {:height 0 :friction 1.0}))
        data {:type :cylinder :axis 0 :half-extents [(* 10 r) r r]}
        shape (shapes/collision-shape data)
        body (doto (PhysicsRigidBody. ^CollisionShape shape (float 0.5))
               (.setPhysicsLocation (Vector3f. 0 (float (* 1.001 r)) 0)) (.setFriction 0.5)
               (.setDamping 0 0.5) (.setSleepingThresholds 0.8 1.0))
        _ (.add space body)
        _ (when (pos? spin) (.setAngularVelocity body (Vector3f. (float spin) 0 0)))
        cosa (when-let [a (System/getenv "PRUNE")] (Math/cos (Double/parseDouble a)))
        _ (when cosa (.addTickListener space (reify PhysicsTickListener (prePhysicsTick [_ s _] (prune! s body cosa)) (physicsTick [_ _ _]))))
        stats (loop [i 0 fast 0.0 low 10.0 late 0.0]
                (if (= i 600) [fast low late]
                    (do (.update space (float (/ 1.0 60)) 1)
                        (let [w (.length (.getAngularVelocity body)) y (/ (.y (.getPhysicsLocation body)) r)]
                          (recur (inc i) (max fast w) (min low y) (if (>= i 540) (max late w) late))))))]
    (println (format "%s prune %s r %.2f spin %4.1f: fastest %.2f rad/s, in the last second %.2f, lowest centre %.3f r" engine/label (env "PRUNE" "-") r spin (stats 0) (stats 2) (stats 1)))))
(shutdown-agents) (System/exit 0)
