;; Generated from org/featherstone.org by lein tangle: edit the chapter, not this file.
(ns cortex.featherstone
  "A measurement, native engine only: cortex's creatures rebuilt as
  Bullet's Featherstone multibodies (Minie's MultiBody), dropped and
  timed as cortex.compare and the physics-trust drop do with rigid
  bodies. See org/featherstone.org.

  Entry point: `-main` (bin/lein with-profile +native run -m
  cortex.featherstone)."
  (:require [clojure.string :as str]
            [cortex.body :as body]
            [cortex.drops :as drops]
            [cortex.blender]
            [cortex.util :as util])
  (:import (com.jme3.bullet MultiBody MultiBodyLink MultiBodySpace PhysicsSpace$BroadphaseType)
           (com.jme3.bullet.collision.shapes BoxCollisionShape CollisionShape)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.objects MultiBodyCollider PhysicsRigidBody)
           (com.jme3.math Quaternion Transform Vector3f)
           (com.jme3.scene Geometry Node)
           (java.lang.management ManagementFactory)))

(set! *warn-on-reflection* true)

(def ^:private dt (/ 1.0 60.0))

(defn- lifted
  "`creature` (a Node, not yet built) moved up so that its lowest point
  is 1 m above the floor at 0, then given its body (sleeping off, as
  cortex.compare builds it): [creature height]."
  [^Node creature]
  (let [[lo hi] (drops/lift! creature)]
    [(body/body! creature {:sleeping-thresholds [0 0]}) (- (double hi) (double lo))]))

(defn- quat ^Quaternion [[x y z w]] (Quaternion. (float x) (float y) (float z) (float w)))

(defn- segment-data
  "What the multibody takes from segment `g`'s rigid body as body! made
  it: centre of mass, principal axes, mass, principal moments, hull."
  [^Geometry g]
  (let [^RigidBodyControl rb (.getControl g RigidBodyControl)
        ^Vector3f inv (.getInverseInertiaLocal rb (Vector3f.))]
    (when (or (zero? (.getMass rb)) (zero? (.x inv)) (zero? (.y inv)) (zero? (.z inv)))
      (throw (ex-info (str "segment " (body/segment-name g) " is static or cannot turn;"
                           " a multibody link needs a mass and an inertia")
                      {:segment (body/segment-name g)})))
    {:geom g :name (body/segment-name g)
     :position (.getPhysicsLocation rb (Vector3f.))
     :rotation (.getPhysicsRotation rb (Quaternion.))
     :mass (.getMass rb)
     :inertia (Vector3f. (/ 1.0 (.x inv)) (/ 1.0 (.y inv)) (/ 1.0 (.z inv)))
     :shape (.getCollisionShape rb)
     :friction (.getFriction rb)}))

(defn tree
  "The segments of the built `creature` in breadth-first order from the
  segment named `root`, each {:segment (see `segment-data`) :parent
  index-in-this-order-or-nil :joint record :second? (whether the
  segment is the joint's second)}. A multibody is a tree: a creature
  whose joints close a loop, or leave a segment unjoined, is an error."
  [^Node creature root]
  (let [segs (vec (body/segments creature))
        records (body/joint-records creature)
        root-geom (body/segment creature root)]
    (when (not= (count records) (dec (count segs)))
      (throw (ex-info (str (count segs) " segments and " (count records) " joints: a tree of "
                           (count segs) " segments has " (dec (count segs)) " joints")
                      {:segments (count segs) :joints (count records)})))
    (loop [order [{:segment (segment-data root-geom)}]
           index {root-geom 0}
           queue [root-geom]]
      (if (empty? queue)
        (do (when (< (count order) (count segs))
              (throw (ex-info "some segments are joined to nothing the root reaches" {})))
            order)
        (let [g (first queue)
              new (for [{[a b] :geoms :as rec} records
                        :when (or (identical? a g) (identical? b g))
                        :let [other (if (identical? a g) b a)]
                        :when (not (contains? index other))]
                    {:segment (segment-data other) :parent (index g) :joint rec
                     :second? (identical? other b)})
              order' (into order new)]
          (recur order'
                 (into index (map-indexed (fn [i {s :segment}] [(:geom s) (+ (count order) i)]) new))
                 (into (subvec (vec queue) 1) (map (comp :geom :segment) new))))))))

(defn- hinge-axis
  "A hinge record's axis in the world (jME axes), unit length."
  ^Vector3f [{:keys [description rotation]}]
  (let [^Vector3f a (#'cortex.joint/axis-vector (get description :axis Vector3f/UNIT_X))]
    (.mult (quat rotation) (util/blender-to-jme (.normalize a)))))

(defn- place!
  "Give `collider` its link's place and `friction`. Bullet sets a
  multibody's colliders where their links are only at the end of a
  step; left where they are made, all at the origin, the first step's
  collision detection finds them inside one another."
  [^MultiBodyCollider collider ^Vector3f position ^Quaternion rotation friction]
  (doto collider
    (.setPhysicsLocation position)
    (.setPhysicsRotation (.toRotationMatrix rotation))
    (.setFriction (float friction))))

(defn multibody
  "A MultiBody of the segments in `order` (see `tree`), as they lie now:
  the first is the base; each hinge a revolute link about the hinge's
  axis, every other joint (cone, point) a spherical link, about the
  joint's pivot; each link's collider the segment's own hull, each
  joined pair kept from colliding, as body! keeps them. It cannot sleep."
  ^MultiBody [order]
  (let [{{:keys [^Vector3f position ^Quaternion rotation mass inertia shape friction]} :segment} (first order)
        mb (MultiBody. (int (dec (count order))) (float mass) ^Vector3f inertia false false)
        links (object-array (count order))]
    (.setBaseLocation mb position)
    ;; Bullet keeps the base's world-to-local rotation
    (.setBaseOrientation mb (.inverse rotation))
    (place! (.addBaseCollider mb shape) position rotation friction)
    (doseq [i (range 1 (count order))
            :let [{{xc :position qc :rotation :keys [mass inertia shape friction]} :segment
                   :keys [parent joint]} (nth order i)
                  {{xp :position qp :rotation} :segment} (nth order parent)
                  ^Vector3f xc xc ^Quaternion qc qc ^Vector3f xp xp ^Quaternion qp qp
                  pivot (util/vec3 (:pivot joint))
                  ;; Bullet's rotParentToThis: a vector in the parent's frame
                  ;; to the link's (q_link^-1 q_parent)
                  parent-to-this (.mult (.inverse qc) qp)
                  parent-to-pivot (.mult (.inverse qp) (.subtract pivot xp))
                  pivot-to-this (.mult (.inverse qc) (.subtract xc pivot))
                  ^MultiBodyLink up (when (pos? parent) (aget links parent))
                  ^MultiBodyLink link
                  (if (= :hinge (:type joint))
                    (.configureRevoluteLink mb (float mass) ^Vector3f inertia up parent-to-this
                                            (.mult (.inverse qc) (hinge-axis joint))
                                            parent-to-pivot pivot-to-this true)
                    (.configureSphericalLink mb (float mass) ^Vector3f inertia up parent-to-this
                                             parent-to-pivot pivot-to-this true))]]
      (aset links i link)
      (place! (.addCollider link ^CollisionShape shape) xc qc friction))
    mb))

(defn- frames
  "The world transform of each of `mb`'s parts, base first, as their
  colliders have it. (A MultiBodyLink's own worldTransform is the one
  of the step before.)"
  [^MultiBody mb]
  (mapv (fn [^MultiBodyCollider c]
          (Transform. (.getPhysicsLocation c (Vector3f.)) (.getPhysicsRotation c (Quaternion.))))
        (.listColliders mb)))

(defn- built-error
  "How far the parts of `mb` in `space` lie from the segments of
  `order` they were made of, after a step without gravity (in which
  nothing should move): [metres radians]."
  [^MultiBodySpace space ^MultiBody mb order]
  (.setGravity space (Vector3f.))
  (.update space (float dt) (int 0))
  (let [errors (map (fn [^Transform t {{:keys [^Vector3f position ^Quaternion rotation]} :segment}]
                      (let [d (.mult (.inverse rotation) (.getRotation t))]
                        [(.distance (.getTranslation t) position)
                         (* 2 (Math/acos (min 1.0 (Math/abs (.getW d)))))]))
                    (frames mb) order)]
    [(apply max (map first errors)) (apply max (map second errors))]))

(defn space
  "A MultiBodySpace holding `mb` over a static floor box (top at 0,
  friction 1.0), gravity 9.81 down."
  ^MultiBodySpace [^MultiBody mb]
  (let [s (MultiBodySpace. (Vector3f. -10000 -10000 -10000) (Vector3f. 10000 10000 10000)
                           PhysicsSpace$BroadphaseType/DBVT)
        floor (doto (PhysicsRigidBody. (BoxCollisionShape. (Vector3f. 200 0.5 200)) (float 0))
                (.setPhysicsLocation (Vector3f. 0 -0.5 0))
                (.setFriction (float 1.0)))]
    (.addCollisionObject s floor)
    (.addMultiBody s mb)
    (.setGravity s (Vector3f. 0 -9.81 0))
    s))

(defn- hinge-limiter
  "With `limits?`, a function applying to `mb`'s hinges, before a step,
  a stiff one-sided spring and damper (30 rad/s natural frequency on the
  link's own inertia about the axis through the pivot) past their
  limits: Minie 8.2.0 has no multibody joint-limit constraint. Without,
  a function that does nothing."
  [^MultiBody mb order limits?]
  (let [hinges (vec (for [i (range 1 (count order))
                          :let [{:keys [joint second?] {:keys [^Quaternion rotation ^Vector3f inertia
                                                               ^Vector3f position mass]} :segment}
                                (nth order i)]
                          :when (and limits? (= :hinge (:type joint)))
                          :let [[lo hi] (:limit (:description joint))
                                ;; the link's joint position is the second
                                ;; segment's angle when the link is it
                                [lo hi] (if second? [lo hi] [(- hi) (- lo)])
                                a (.mult (.inverse rotation) (hinge-axis joint))
                                e (.mult (.inverse rotation) (.subtract position (util/vec3 (:pivot joint))))
                                r (.cross e a)
                                moment (+ (* (.x inertia) (.x a) (.x a)) (* (.y inertia) (.y a) (.y a))
                                          (* (.z inertia) (.z a) (.z a)) (* (double mass) (.dot r r)))
                                w 30.0]]
                      [(.getLink mb (int (dec i))) (double lo) (double hi)
                       (* moment w w) (* 2.0 moment w)]))]
    (fn []
      (doseq [[^MultiBodyLink link lo hi k c] hinges
              :let [lo (double lo) hi (double hi) k (double k) c (double c)
                    q (double (.jointPosition link 0))
                    past (cond (> q hi) (- q hi) (< q lo) (- q lo) :else 0.0)]
              :when (not (zero? past))]
        (.addJointTorque link 0 (float (- (- (* k past)) (* c (.jointVelocity link 0)))))))))

(defn- joint-gauges
  "For each joint of `order`, a function of the parts' world transforms
  (see `frames`) giving [type radians-past-its-limits gap-in-metres],
  the angles read as cortex's physics-trust test reads them: a hinge's
  about its axis, a cone's as the Euler angles of its relative rotation
  in the frame body! gives the engine (cortex.body/cone-limits)."
  [order]
  (vec
   (for [i (range 1 (count order))
         :let [{:keys [joint second? parent]} (nth order i)
               [ia ib] (if second? [parent i] [i parent])
               {{^Quaternion qa0 :rotation ^Vector3f xa0 :position} :segment} (nth order ia)
               {{^Quaternion qb0 :rotation ^Vector3f xb0 :position} :segment} (nth order ib)
               j (quat (:rotation joint))
               pivot (util/vec3 (:pivot joint))
               pa (.mult (.inverse qa0) (.subtract pivot xa0))
               pb (.mult (.inverse qb0) (.subtract pivot xb0))
               fa (.mult (.inverse qa0) j)
               fb (.mult (.inverse qb0) j)
               d (:description joint)]]
     (fn [parts]
       (let [^Transform ta (nth parts ia) ^Transform tb (nth parts ib)
             qa (.getRotation ta) qb (.getRotation tb)
             rel (.mult (.inverse (.mult qa fa)) (.mult qb fb))
             gap (.distance (.add (.getTranslation ta) (.mult qa pa))
                            (.add (.getTranslation tb) (.mult qb pb)))
             past (case (:type joint)
                    :hinge (let [[lo hi] (:limit d)
                                 ^Vector3f axis (#'cortex.joint/axis-vector (get d :axis Vector3f/UNIT_X))
                                 axis (util/blender-to-jme (.normalize axis))
                                 ;; the twist of rel about the axis
                                 s (+ (* (.getX rel) (.x axis)) (* (.getY rel) (.y axis))
                                      (* (.getZ rel) (.z axis)))
                                 angle (* 2.0 (Math/atan2 s (.getW rel)))
                                 angle (cond (> angle Math/PI) (- angle (* 2 Math/PI))
                                             (< angle (- Math/PI)) (+ angle (* 2 Math/PI))
                                             :else angle)]
                             (max 0.0 (- (double lo) angle) (- angle (double hi))))
                    :cone (let [[angles limits] (body/cone-engine-angles d rel)]
                            (reduce max 0.0 (map (fn [a l] (- (Math/abs (double a)) (double l)))
                                                 angles limits)))
                    0.0)]
         [(:type joint) past gap])))))

(defn- cpu-ns ^long []
  (.getCurrentThreadCpuTime (ManagementFactory/getThreadMXBean)))

(defn- distance ^double [^Transform a ^Transform b]
  (.distance (.getTranslation a) (.getTranslation b)))

(defn- frame!
  "Advance `space` by 1/60 s in `substeps` equal steps, `limiter`
  applying its torques before each."
  [^MultiBodySpace space limiter substeps]
  (let [h (float (/ dt (long substeps)))]
    (dotimes [_ substeps]
      (limiter)
      (.update space h (int 0)))))

(defn drop!
  "Drop `make`'s creature (lowest point 1 m up) as a multibody rooted at
  segment `root`, 600 frames of 1/60 s, each of `substeps` steps; hinge
  limits as torques when `limits?`. What happened."
  [make root limits? substeps]
  (let [[creature height] (lifted (make))
        order (tree creature root)
        mb (multibody order)
        s (space mb)
        limiter (hinge-limiter mb order limits?)
        gauges (joint-gauges order)
        read (fn [parts] (mapv #(% parts) gauges))
        built (built-error s mb order)
        _ (.setGravity s (Vector3f. 0 -9.81 0))
        start (frames mb)
        start-past (read start)
        steps (loop [i 0 prev start acc []]
                (if (= i 600)
                  acc
                  (do (frame! s limiter substeps)
                      (let [now (frames mb)]
                        (recur (inc i) now
                               (conj acc {:frames now
                                          :speed (apply max (map #(/ (distance %1 %2) dt) now prev))
                                          :joints (read now)}))))))
        speeds (mapv :speed steps)
        still-from (loop [i 599] (if (and (>= i 0) (< (double (speeds i)) 0.05)) (recur (dec i)) (inc i)))
        worst (fn [type] (apply max 0.0 (for [{js :joints} steps
                                              [[t p] [_ p0]] (map vector js start-past)
                                              :when (= t type)]
                                          (- (double p) (double p0)))))]
    {:links (inc (.countConfiguredLinks mb)) :dofs (.countDofs mb)
     :built-error built
     :fastest (apply max speeds) :bound (+ 1.0 (Math/sqrt (* 2 9.81 (+ 1.0 height))))
     :hinge-past (worst :hinge) :cone-past (worst :cone)
     :gap (apply max 0.0 (for [{js :joints} steps [_ _ g] js] (double g)))
     :still-at (when (< still-from 600) (/ still-from 60.0))
     :moved (apply max (map distance (:frames (peek steps)) (:frames (steps 479))))
     :damping [(.linearDamping mb) (.angularDamping mb)]}))

(defn steps-per-second
  "`make`'s creature as a multibody rooted at `root` (hinge limits as
  torques when `limits?`), dropped, 1,000 warm-up frames of 1/60 s (of
  `substeps` steps each), then `n` frames timed in this thread's CPU
  time: frames of 1/60 s per CPU second."
  [make root limits? substeps n]
  (let [[creature _] (lifted (make))
        order (tree creature root)
        mb (multibody order)
        s (space mb)
        limiter (hinge-limiter mb order limits?)]
    (dotimes [_ 1000] (frame! s limiter substeps))
    (let [t0 (cpu-ns)]
      (dotimes [_ n] (frame! s limiter substeps))
      (/ (double n) (/ (- (cpu-ns) t0) 1e9)))))

(def cases
  "[label make root limits? substeps timed-frames]: the humanoid, hinges
  free and hinges limited by torques, at 1/60 s and in four steps of
  1/240 s; the 100-segment chain (rooted at its middle) at 1/60 s,
  timed over fewer frames, for it runs slowly."
  (let [humanoid #(util/load-blender-model "test/fixtures/humanoid/humanoid.blend")
        chain #((requiring-resolve 'cortex.bench.creatures/creature)
                ((requiring-resolve 'cortex.bench.creatures/chain) 100))]
    (concat
     (for [substeps [1 4] limits? [false true]]
       [(str "humanoid, " (if limits? "limit torques" "hinges free") (if (= 1 substeps) ", 1/60" ", 4x1/240"))
        humanoid "torso" limits? substeps 10000])
     [["chain-100, hinges free, 1/60" chain "seg-50" false 1 1000]])))

(defn -main
  "bin/lein with-profile +native run -m cortex.featherstone"
  [& _]
  (let [row (fn [& xs] (println (apply format "%-38s %5s %5s %8s %7s %8s %8s %9s %8s %8s %8s" xs)))
        damping (atom nil)]
    (row "creature (Featherstone)" "links" "dofs" "fastest" "bound" "hinge>" "cone>" "gap m"
         "rest s" "moved" "frames/s")
    (doseq [[label make root limits? substeps n] cases
            :let [{:keys [links dofs fastest bound hinge-past cone-past gap still-at moved built-error]
                   :as result} (drop! make root limits? substeps)
                  sps (steps-per-second make root limits? substeps n)]]
      (row label links dofs (format "%.2f" fastest) (format "%.2f" bound)
           (format "%.3f" hinge-past) (format "%.3f" cone-past) (format "%.1e" gap)
           (if still-at (format "%.2f" still-at) "never") (format "%.4f" moved)
           (format "%.0f" sps))
      (let [[m r] built-error]
        (when (or (> (double m) 1e-4) (> (double r) 1e-4))
          (println (format "  (built %.2e m, %.2e rad from the rigid bodies)" m r))))
      (reset! damping (:damping result)))
    (println "multibody damping (linear, angular), Bullet's default:" @damping)
    (shutdown-agents)))
