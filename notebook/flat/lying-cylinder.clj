;; Lying X-axis cylinders (radius r, half length LEN x r, 0.5 kg, angular damping 0.5) put at rest on a floor
;; of friction 1, or given 10 rad/s about their axis: the fastest spin in 10 s, the fastest in the last
;; second, and the lowest centre as a fraction of r.
;; bin/lein [with-profile +native] run -m clojure.main notebook/flat/lying-cylinder.clj
;; env: RS radii ("0.03 0.1 0.3"), LEN (10), SHAPES of cyl (cortex.shapes' cylinder), prism6, prism16, prism32
;; (hulls), box (cortex.shapes' box, 2r square); SUBS substeps (1); PLANE=1 a plane for the floor; FW a floor box of that half width made as
;; cortex.shapes makes a box, or with FBOX=m a Bullet box of margin m (default: cortex.sim/floor);
;; ISO=k each inverse moment at most k times the smallest.
(require '[cortex.engine :as engine] '[cortex.shapes :as shapes] '[cortex.sim :as sim])
(import '(com.jme3.bullet PhysicsSpace PhysicsSpace$BroadphaseType) '(com.jme3.bullet.collision.shapes HullCollisionShape CollisionShape)
        '(com.jme3.bullet.objects PhysicsRigidBody) '(com.jme3.math Vector3f) '(com.jme3.bullet.control RigidBodyControl) '(com.jme3.scene Geometry))
(defn env [k d] (or (System/getenv k) d))
(doseq [r (map #(Double/parseDouble %) (clojure.string/split (env "RS" "0.03 0.1 0.3") #" ")) kind (clojure.string/split (env "SHAPES" "cyl prism16 prism32") #" ")
        spin [0.0 10.0]]
  (let [space (sim/physics-space)
        subs (Long/parseLong (env "SUBS" "1"))
        _ (.setAccuracy space (float (/ 1.0 60 subs)))
        _ (if (System/getenv "PLANE")
            (.add space (doto (PhysicsRigidBody. (com.jme3.bullet.collision.shapes.PlaneCollisionShape. (com.jme3.math.Plane. Vector3f/UNIT_Y 0.0)) (float 0)) (.setFriction 1.0)))
            (if-let [fw (some-> (System/getenv "FW") Double/parseDouble)]
              (.add space (doto (PhysicsRigidBody. ^CollisionShape (if (System/getenv "FBOX")
                                                                   (doto (com.jme3.bullet.collision.shapes.BoxCollisionShape. (Vector3f. (float fw) 0.5 (float fw))) (.setMargin (float (Double/parseDouble (env "FBOX" "0.04")))))
                                                                   (shapes/collision-shape {:type :box :half-extents [fw 0.5 fw]})) (float 0))
                            (.setPhysicsLocation (Vector3f. 0 -0.5 0)) (.setFriction 1.0)))
              (engine/add-all! space (sim/floor {:height 0 :friction 1.0}))))
        data {:type :cylinder :axis 0 :half-extents [(* (Double/parseDouble (env "LEN" "10")) r) r r]}
        m (shapes/margin data)
        shape (case kind
                "cyl" (shapes/collision-shape data)
                "prism16" (doto (HullCollisionShape. (float-array (mapcat identity (shapes/prism-points data m 16)))) (.setMargin (float m)))
                "prism6" (doto (HullCollisionShape. (float-array (mapcat identity (shapes/prism-points data m 6)))) (.setMargin (float m)))
                "box" (shapes/collision-shape {:type :box :half-extents [(* (Double/parseDouble (env "LEN" "10")) r) r r]})
                "prism32" (doto (HullCollisionShape. (float-array (mapcat identity (shapes/prism-points data m 32)))) (.setMargin (float m))))
        body (doto (PhysicsRigidBody. ^CollisionShape shape (float 0.5))
               (.setPhysicsLocation (Vector3f. 0 (float (* 1.001 r)) 0)) (.setFriction 0.5)
               (.setDamping 0 0.5) (.setSleepingThresholds 0.8 1.0))
        _ (when-let [k (System/getenv "ISO")] (let [i (.getInverseInertiaLocal body nil)] (.setInverseInertiaLocal body (let [mn (* (Double/parseDouble k) (min (.x i) (.y i) (.z i)))] (Vector3f. (float (min (.x i) mn)) (float (min (.y i) mn)) (float (min (.z i) mn)))))))
        _ (.add space body)
        _ (when (pos? spin) (.setAngularVelocity body (Vector3f. (float spin) 0 0)))
        stats (loop [i 0 fast 0.0 low 10.0 late 0.0]
                (if (= i 600) [fast low late]
                    (do (.update space (float (/ 1.0 60)) (int subs))
                        (let [w (.length (.getAngularVelocity body)) y (/ (.y (.getPhysicsLocation body)) r)]
                          (recur (inc i) (max fast w) (min low y) (if (>= i 540) (max late w) late))))))]
    (println (format "%s r %.2f %s spin %4.1f: fastest %.2f rad/s, in the last second %.2f, lowest centre %.3f r" engine/label r kind spin (stats 0) (stats 2) (stats 1)))))
(shutdown-agents) (System/exit 0)
