;; Generated from org/engine.org by lein tangle: edit the chapter, not this file.
(ns cortex.engine
  "The physics engine cortex runs on, native Bullet through Minie: what
  differs between it and jBullet (see org/engine.org), behind one set of
  functions. A body's engine object (`rigid-body`) is the jME
  PhysicsRigidBody itself."
  (:refer-clojure :exclude [name])
  (:require [cortex.geometry :as geometry])
  (:import (com.jme3.bullet PhysicsSpace SolverInfo)
           (com.jme3.bullet.joints.motors MotorParam)
           (com.jme3.bullet.collision ManifoldPoints PersistentManifolds PhysicsCollisionObject
                                      PhysicsCollisionGroupListener)
           (com.jme3.bullet.collision.shapes CollisionShape CompoundCollisionShape
                                             GImpactCollisionShape HullCollisionShape
                                             MeshCollisionShape)
           (com.jme3.bullet.collision.shapes.infos ChildCollisionShape IndexedMesh)
           (com.jme3.bullet.joints PhysicsJoint Constraint)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.math Matrix3f Quaternion Vector3f)
           (com.jme3.scene Mesh VertexBuffer$Type)
           (com.jme3.scene.mesh IndexBuffer)
           (com.jme3.system NativeLibraryLoader Platform)
           (com.jme3.util BufferUtils)
           (java.lang.reflect Constructor Field Method)))

(set! *warn-on-reflection* true)

(def name
  "Which engine this is: :jbullet or :native."
  :native)

(def label
  "This engine's name as people read it, for reports."
  "native Bullet")

(defonce ^{:private true
           :doc "Minie's native library, loaded once, when this namespace is:
  jME 3.2.4's loader knows the library's name but not where Minie keeps
  it, so each platform's file is named first."}
  native-library
  (do (doseq [[platform path] [[Platform/Linux64 "native/linux/x86_64/libbulletjme.so"]
                               [Platform/Linux32 "native/linux/x86/libbulletjme.so"]
                               [Platform/Windows64 "native/windows/x86_64/bulletjme.dll"]
                               [Platform/Windows32 "native/windows/x86/bulletjme.dll"]
                               [Platform/MacOSX64 "native/osx/x86_64/libbulletjme.dylib"]]]
        (NativeLibraryLoader/registerNativeLibrary "bulletjme" platform path))
      (NativeLibraryLoader/loadNativeLibrary "bulletjme" true)
      :loaded))

(defn rigid-body
  "The engine's own object for the jME body `body`: here `body` itself."
  ^PhysicsRigidBody [^PhysicsRigidBody body]
  body)

(defn collision-object
  "What the engine's contact manifolds name `body` by (see `reduce-contacts`)."
  [^PhysicsCollisionObject body]
  body)

(defn rotation-matrix
  "How the jME body `body` is turned now, a new Matrix3f."
  ^Matrix3f [^PhysicsRigidBody body]
  (.getPhysicsRotationMatrix body (Matrix3f.)))

(defn applied-impulse
  "The impulse `joint` applied in the last step (its feedback must be
  on): its size, as jBullet's ImpulseMeter gives it (native Bullet
  keeps the signed impulse of the constraint's last row)."
  ^double [^Constraint joint]
  (Math/abs (.getAppliedImpulse joint)))

(defn- private-member
  "The declared constructor (`name` nil) or method `name` of `class`
  taking `types`, made accessible."
  [^Class class name types]
  (let [types (into-array Class types)]
    (let [^java.lang.reflect.AccessibleObject member
          (if name
            (.getDeclaredMethod class ^String name ^"[Ljava.lang.Class;" types)
            (.getDeclaredConstructor class ^"[Ljava.lang.Class;" types))]
      (.setAccessible member true)
      member)))

(defn- indexed-mesh
  "Minie's IndexedMesh (the triangles a mesh shape is made of) of the
  triangles of `mesh`. Every public way to build one (from a Mesh,
  from positions and indices, from a saved file) calls jME 3.6's
  IndexBuffer.getFormat or put(int, int), which jME 3.2.4 lacks; so
  the mesh is made as its own constructor makes it (32-bit indices),
  its fields set and its native mesh created through reflection."
  ^IndexedMesh [^Mesh mesh]
  (let [positions (.getFloatBuffer mesh VertexBuffer$Type/Position)
        n-vertices (quot (.limit positions) 3)
        ^IndexBuffer is (.getIndicesAsList mesh)
        indices (int-array (.size is))
        _ (dotimes [i (alength indices)] (aset indices i (.get is (int i))))
        ^Constructor make (private-member IndexedMesh nil [])
        im ^IndexedMesh (.newInstance make (object-array 0))
        field! (fn [^String name value]
                 (let [f (.getDeclaredField IndexedMesh name)]
                   (.setAccessible f true)
                   (.set f im value)))]
    (field! "vertexPositions" (doto (BufferUtils/createFloatBuffer (* 3 n-vertices))
                                (.put (doto (.duplicate positions) (.rewind)))
                                (.flip)))
    (field! "vertexStride" (int 12))
    (field! "numVertices" (int n-vertices))
    (field! "indices" (IndexBuffer/wrapIndexBuffer (BufferUtils/createIntBuffer indices)))
    (field! "indexStride" (int 12))
    (field! "numTriangles" (int (quot (alength indices) 3)))
    (.invoke ^Method (private-member IndexedMesh "createMesh" []) im (object-array 0))
    im))

(defn gimpact-shape
  "A GImpact (moving triangle mesh) collision shape of `mesh`."
  ^CollisionShape [^Mesh mesh]
  (GImpactCollisionShape. ^"[Lcom.jme3.bullet.collision.shapes.infos.IndexedMesh;"
                          (into-array IndexedMesh [(indexed-mesh mesh)])))

(defn mesh-shape
  "A static triangle mesh (BVH, quantized as jme3-jbullet's) collision
  shape of `mesh`."
  ^CollisionShape [^Mesh mesh]
  (MeshCollisionShape. true ^"[Lcom.jme3.bullet.collision.shapes.infos.IndexedMesh;"
                       (into-array IndexedMesh [(indexed-mesh mesh)])))

(defn orientation
  "How the engine body `rb` is turned now, [x y z w], jME's axes."
  [^PhysicsRigidBody rb]
  (let [q (.getPhysicsRotation rb (Quaternion.))]
    [(double (.getX q)) (double (.getY q)) (double (.getZ q)) (double (.getW q))]))

(defn- triple [^Vector3f v] [(double (.x v)) (double (.y v)) (double (.z v))])

(defn position
  "Where the engine body `rb`'s centre of mass is now, [x y z]."
  [^PhysicsRigidBody rb]
  (triple (.getPhysicsLocation rb (Vector3f.))))

(defn linear-velocity
  "`rb`'s velocity now, [x y z]."
  [^PhysicsRigidBody rb]
  (triple (.getLinearVelocity rb (Vector3f.))))

(defn angular-velocity
  "`rb`'s angular velocity now, [x y z], jME's axes."
  [^PhysicsRigidBody rb]
  (triple (.getAngularVelocity rb (Vector3f.))))

(defn body-states
  "The state of each engine body of `rbs` now, in one new double array,
  13 numbers a body in their order: centre of mass x y z, orientation
  x y z w, velocity x y z, angular velocity x y z (jME's axes); each
  number is the float the getters above read."
  ^doubles [rbs]
  (let [out (double-array (* 13 (count rbs)))
        q (Quaternion.) v (Vector3f.)
        put3 (fn [^long i ^Vector3f v]
               (aset out i (double (.x v))) (aset out (+ i 1) (double (.y v)))
               (aset out (+ i 2) (double (.z v))))]
    (reduce (fn [^long i ^PhysicsRigidBody rb]
              (put3 i (.getPhysicsLocation rb v))
              (.getPhysicsRotation rb q)
              (aset out (+ i 3) (double (.getX q))) (aset out (+ i 4) (double (.getY q)))
              (aset out (+ i 5) (double (.getZ q))) (aset out (+ i 6) (double (.getW q)))
              (put3 (+ i 7) (.getLinearVelocity rb v))
              (put3 (+ i 10) (.getAngularVelocity rb v))
              (+ i 13))
            0 rbs)
    out))

(defn inverse-mass
  "1/m of the engine body `rb`, 0 for a static one."
  ^double [^PhysicsRigidBody rb]
  (let [m (.getMass rb)]
    (if (pos? m) (/ 1.0 m) 0.0)))

(defn inverse-inertia
  "The inverse principal moments of `rb`, in its own frame, [x y z]."
  [^PhysicsRigidBody rb]
  (triple (.getInverseInertiaLocal rb (Vector3f.))))

(def ^:private torqued
  "A body's application data while it holds a torque from
  `apply-torques!`: `configure-space!`'s listener hands that torque to
  the body as impulses, substep by substep (see `torques-as-impulses!`)."
  (Object.))

(defn apply-torques!
  "Torque `t` ([x y z], world) on the engine body `rb-b` and -t on `rb-a`,
  for the next step; both woken, and marked as `torqued`."
  [^PhysicsRigidBody rb-a ^PhysicsRigidBody rb-b [x y z]]
  (let [t (Vector3f. (float x) (float y) (float z))]
    (when (pos? (.getMass rb-b))
      (.applyTorque rb-b t)
      (.setApplicationData rb-b torqued)
      (.activate rb-b))
    (.negateLocal t)
    (when (pos? (.getMass rb-a))
      (.applyTorque rb-a t)
      (.setApplicationData rb-a torqued)
      (.activate rb-a))))

(defn set-inertia!
  "Give `body` mass `mass` and the principal moments [ix iy iz]."
  [^PhysicsRigidBody body mass [ix iy iz]]
  (.setMass body (float mass))
  (.setInverseInertiaLocal body (Vector3f. (float (/ 1.0 (double ix))) (float (/ 1.0 (double iy)))
                                           (float (/ 1.0 (double iz))))))

(defn clear-inertia!
  "Make `body` unable to turn: inverse inertia 0."
  [^PhysicsRigidBody body]
  (.setInverseInertiaLocal body (Vector3f.)))

(def ^:private ^Method activation-state!
  "PhysicsCollisionObject's own setActivationState(long id, int state),
  which Minie keeps protected."
  (private-member PhysicsCollisionObject "setActivationState" [Long/TYPE Integer/TYPE]))

(defn set-sleep!
  "`:start-asleep` (it sleeps until something wakes it) or `:never`
  (it never sleeps) for `body`. Minie's setEnableSleep knows only
  ACTIVE_TAG and DISABLE_DEACTIVATION; a body starts asleep as Blender
  starts it, in Bullet's WANTS_DEACTIVATION (3), set natively."
  [^PhysicsRigidBody body how]
  (case how
    :start-asleep (.invoke activation-state! nil (object-array [(.nativeId body) (int 3)]))
    :never (.setEnableSleep body false)))

(def ^:private blender-group
  "The collision group of every body in Blender's collision collections
  (see `set-collections!`): the bit above Blender's twenty."
  (bit-shift-left 1 20))

(defn set-collections!
  "Put `body` in Blender's collision collections `mask` (20 bits): it
  collides with a body that shares one of them, and with what is in
  jME's first collision group (a floor, say) when `mask` has the
  first. Minie wants a body's group to be one bit, so the body is in
  `blender-group` and collides with `mask` and that group; the space's
  listener (see `configure-space!`) then lets two such bodies collide
  only when their masks meet."
  [^PhysicsCollisionObject body mask]
  (let [m (bit-and (long mask) 0xfffff)]
    (.setCollisionGroup body (int blender-group))
    (.setCollideWithGroups body (int (bit-or m blender-group)))))

(def ^:private collections-listener
  "Whether two bodies of `blender-group` collide: when their
  collections (the collide-with masks less that group) meet. Any other
  pair has passed jME's test of groups already."
  (reify PhysicsCollisionGroupListener
    (collide [_ a b]
      (or (not= (.getCollisionGroup a) (.getCollisionGroup b))
          (not (zero? (bit-and (.getCollideWithGroups a) (.getCollideWithGroups b) 0xfffff)))))))

(defn breaking-threshold!
  "Make `joint` breakable at `threshold`: native Bullet clamps each of
  its rows at it and disables it when one reaches it."
  [^Constraint joint threshold]
  (.setBreakingImpulseThreshold joint (float threshold)))

(defn broken?
  "Whether the breakable `joint` broke in the last substep: native
  Bullet disabled it."
  [^Constraint joint _threshold]
  (not (.isEnabled joint)))

(defn blender-solver-order!
  "Have `space`'s solver visit constraints as Blender's world does: in
  a fixed order (Bullet's default mode, warm starting and SIMD, which
  Blender keeps), not the random one `configure-space!` gives cortex's
  own creatures. Measured on the Physics tab's rig-chain (five GENERIC
  joints with limits): 0.3% and 0.5% of its size from Blender's at 1
  and 2 s in the fixed order, 5.0% and 3.6% in the random one."
  [^PhysicsSpace space]
  (.setMode ^SolverInfo (.getSolverInfo space) (int (bit-or 4 256))))

(defn blender-velocities!
  "Before a substep: nothing here; native Bullet's bodies already take
  the implicit gyroscopic term (BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY,
  its default) and are damped before gravity is added, as Blender's."
  [_space _dt]
  nil)

(defn hull-points
  "The points of `shape`'s hull (or of its first child's, for a compound
  shape), [[x y z] ...], or nil when it is no hull."
  [^CollisionShape shape]
  (let [s (if (instance? CompoundCollisionShape shape)
            (.getShape ^ChildCollisionShape (first (.listChildren ^CompoundCollisionShape shape)))
            shape)]
    (when (instance? HullCollisionShape s)
      (mapv vec (partition 3 (map double (.copyHullVertices ^HullCollisionShape s)))))))

(def ^{:arglists '([points])
       :doc "The volume of the convex hull of `points` ([[x y z] ...]): see
  cortex.geometry/hull-volume."}
  hull-volume geometry/hull-volume)

(def ^{:doc "The thickness below which a body is small: cortex.geometry/thin."}
  thin geometry/thin)

(defn hull-margin
  "The collision margin cortex gives hull shapes: 0.001, as near
  jme3-jbullet's 0 as Minie allows (it refuses 0; native Bullet's
  default is 0.04)."
  ^double []
  0.001)

(defn thickness
  "How thick `shape` counts as (of a compound, its thinnest child): its
  smallest extent along its own axes, or for a sheet a tenth of the next
  (cortex.geometry/sheet-thickness): a hull's points', a box's or
  cylinder's, a sphere's or capsule's diameter, a cone's smaller of
  diameter and height; nil for any other shape. Read from the shape's
  own figures: Minie's bounding box recalculates the shape's cached one,
  which moves the pinned drops."
  [^CollisionShape shape]
  (letfn [(t [^CollisionShape s]
            (condp instance? s
              CompoundCollisionShape
              (reduce min ##Inf (map #(t (.getShape ^ChildCollisionShape %))
                                     (.listChildren ^CompoundCollisionShape s)))
              HullCollisionShape
              (geometry/sheet-thickness
               (geometry/points-sides (partition 3 (.copyHullVertices ^HullCollisionShape s))))
              com.jme3.bullet.collision.shapes.BoxCollisionShape
              (let [e (.getHalfExtents ^com.jme3.bullet.collision.shapes.BoxCollisionShape s nil)]
                (geometry/sheet-thickness [(* 2.0 (.x e)) (* 2.0 (.y e)) (* 2.0 (.z e))]))
              com.jme3.bullet.collision.shapes.CylinderCollisionShape
              (let [e (.getHalfExtents ^com.jme3.bullet.collision.shapes.CylinderCollisionShape s nil)]
                (geometry/sheet-thickness [(* 2.0 (.x e)) (* 2.0 (.y e)) (* 2.0 (.z e))]))
              com.jme3.bullet.collision.shapes.SphereCollisionShape
              (* 2.0 (.getRadius ^com.jme3.bullet.collision.shapes.SphereCollisionShape s))
              com.jme3.bullet.collision.shapes.CapsuleCollisionShape
              (* 2.0 (.getRadius ^com.jme3.bullet.collision.shapes.CapsuleCollisionShape s))
              com.jme3.bullet.collision.shapes.ConeCollisionShape
              (let [c ^com.jme3.bullet.collision.shapes.ConeCollisionShape s]
                (min (* 2.0 (.getRadius c)) (.getHeight c)))
              ##Inf))]
    (let [d (double (t shape))]
      (when (< d ##Inf) d))))

(defn hinge-limits
  "The [low high] to give a jME HingeJoint (made from two axes) so that
  the designer's limits [lo hi] (radians, right-hand rule about the
  designer's axis, second segment relative to the first) hold: native
  Bullet's angle is minus the designer's, exactly."
  [[lo hi]]
  [(- (double hi)) (- (double lo))])

(defn frame-hinge-limit
  "The limit to give a FrameHingeJoint so that it stops at `angle`: the
  angle itself."
  [angle]
  (float angle))

(defn collide-linked!
  "Whether the two bodies `joint` links collide with each other."
  [^Constraint joint collide?]
  (.setCollisionBetweenLinkedBodies joint (boolean collide?))
  joint)

(defn collide-linked?
  "Do the two bodies `joint` links collide with each other?"
  [^Constraint joint]
  (.isCollisionBetweenLinkedBodies joint))

(defn pivots
  "[pivot-a pivot-b] of `joint`: its point in each body's frame."
  [^Constraint joint]
  [(.getPivotA joint (Vector3f.)) (.getPivotB joint (Vector3f.))])

(defn joints
  "The joints attached to the jME body `body`, a seq."
  [^PhysicsRigidBody body]
  (seq (.listJoints body)))

(defn joint-frames
  "The frames a joint is read in, when the engine keeps them: for a
  hinge given whole frames (a FrameHingeJoint), {:frame-a q :frame-b q
  :axis [0 0 1]}, its frame in each body, the axis its Z; nil for any
  other joint."
  [^PhysicsJoint joint]
  (when (instance? cortex.FrameHingeJoint joint)
    (let [^cortex.FrameHingeJoint j joint
          q (fn [m] (let [q (doto (Quaternion.) (.fromRotationMatrix ^com.jme3.math.Matrix3f m))]
                      [(double (.getX q)) (double (.getY q)) (double (.getZ q)) (double (.getW q))]))]
      {:frame-a (q (.getRotA j)) :frame-b (q (.getRotB j)) :axis [0.0 0.0 1.0]})))

(def ^:private ^java.util.Map limited-hinges
  "Each hinge cortex limits (weakly held) -> a double array [low high
  angle seen? zero low-now high-now]: its limits, its angle (about its
  zero) before the last step and whether there was one, the engine's
  angle where it was built, and the limits it has now."
  (java.util.Collections/synchronizedMap (java.util.WeakHashMap.)))

(def ^:private ^java.util.Map hinge-zeros
  "Each hinge `zero-hinge!` saw (weakly held) -> the engine's angle then."
  (java.util.Collections/synchronizedMap (java.util.WeakHashMap.)))

(defn zero-hinge!
  "Make the HingeJoint `joint`'s angle 0 where its two bodies are now:
  Minie cannot set a hinge's frames, so the engine's angle now is kept
  and every limit is given about it (see `limit-hinge!`)."
  [^com.jme3.bullet.joints.HingeJoint joint]
  (.put hinge-zeros joint (double (.getHingeAngle joint)))
  joint)

(defn- wrap ^double [^double a]
  (- a (* 2.0 Math/PI (Math/floor (/ (+ a Math/PI) (* 2.0 Math/PI))))))

(defn- set-limits!
  "Give the hinge `joint` the limits [low high] about its zero `zero`
  (native Bullet keeps a limit as a centre and a half range, so one
  that crosses a half turn is fine)."
  [^com.jme3.bullet.joints.HingeJoint joint ^double zero ^double low ^double high]
  (.setLimit joint (float (+ zero low)) (float (+ zero high))
             (float 0.9) (float 1.0) (float 0.0)))

(defn limit-hinge!
  "Limit the HingeJoint `joint` to [low high], in the engine's sense of
  its angle (see `hinge-limits`) about the zero `zero-hinge!` kept,
  speculatively: see above."
  [^com.jme3.bullet.joints.HingeJoint joint low high]
  (let [zero (double (or (.get hinge-zeros joint) 0.0))]
    (set-limits! joint zero low high)
    ;; [low high angle-before seen? zero limits-now-low limits-now-high]
    (.put limited-hinges joint (double-array [low high 0.0 0.0 zero low high]))
    joint))

(defn- speculate!
  "Before a step: stop each limited hinge of `space` that would pass a
  limit in it, and give back their limits to the others. Runs every
  substep, so it boxes nothing: the limits are two primitive doubles,
  not a pair."
  [^PhysicsSpace space]
  (let [it (.iterator (.getJointList space))]
    (while (.hasNext it)
      (let [j (.next it)
            ^doubles state (.get limited-hinges j)]
        (when state
          (let [^com.jme3.bullet.joints.HingeJoint h j
                lo (aget state 0) hi (aget state 1) zero (aget state 4)
                angle (double (wrap (- (double (.getHingeAngle h)) zero)))
                next-angle (if (pos? (aget state 3)) (- (* 2.0 angle) (aget state 2)) angle)
                margin 1e-4
                ;; about to pass the upper limit: stop just short of it;
                ;; else the lower; else the limits as they are
                up? (and (<= angle hi) (> next-angle hi))
                down? (and (not up?) (>= angle lo) (< next-angle lo))
                l (if down? (min hi (+ angle margin)) lo)
                u (if up? (max lo (- angle margin)) hi)]
            (when (or (not (== l (aget state 5))) (not (== u (aget state 6))))
              (set-limits! h zero l u)
              (aset state 5 l)
              (aset state 6 u))
            (aset state 2 angle)
            (aset state 3 1.0)))))))

(def six-dof-class
  "The class of the joint `six-dof-joint` makes."
  com.jme3.bullet.joints.New6Dof)

(def six-dof-safe-middle
  "The widest limit cortex gives a six-DOF joint's middle angle when it
  has the choice (see the body chapter's cones): Bullet's New6Dof
  normalises its axes, so the cap of 1.5 is enough."
  1.5)

(defn six-dof-angles
  "The three angles [x y z] the six-DOF `joint` (see `six-dof-joint`)
  reads between its bodies as they are now, the ones its limits hold."
  [^com.jme3.bullet.joints.New6Dof joint]
  (let [v (.getAngles joint (Vector3f.))]
    [(double (.x v)) (double (.y v)) (double (.z v))]))

(defn six-dof-joint
  "A joint between the bodies of `control-a` and `control-b` at
  `pivot-a`, `pivot-b` whose translation is locked and whose three
  angles (Euler XYZ in the joint's frame) keep within [-t t], [-y y],
  [-z z] of `limits` [t y z], or turn freely when `limits` is nil; the
  joint's frame is `frame-a`, `frame-b` (Matrix3f, each in its body's
  frame), or the bodies' own when nil. Here a New6Dof (Bullet's
  btGeneric6DofSpring2Constraint), whose rows hold a locked axis from
  the first step: Bullet's older 6-DOF (Minie's SixDofJoint) makes a
  locked axis's rows only once it is off, so a joint lets go for a step
  whenever one of its bodies is stopped dead (the hand's thumb opened
  0.073 as its palm hit the floor)."
  [control-a control-b ^Vector3f pivot-a ^Vector3f pivot-b frame-a frame-b limits]
  (let [j (com.jme3.bullet.joints.New6Dof. ^PhysicsRigidBody control-a ^PhysicsRigidBody control-b
                                            pivot-a pivot-b
                                            ^Matrix3f (or frame-a (Matrix3f.)) ^Matrix3f (or frame-b (Matrix3f.))
                                            com.jme3.bullet.RotationOrder/XYZ)
        tm (.getTranslationMotor j)]
    (.set tm MotorParam/LowerLimit (Vector3f.))
    (.set tm MotorParam/UpperLimit (Vector3f.))
    (doseq [[i lim] (map-indexed vector (or limits [nil nil nil]))
            :let [m (.getRotationMotor j (int i))]]
      (if lim
        (do (.set m MotorParam/LowerLimit (float (- (double lim))))
            (.set m MotorParam/UpperLimit (float lim)))
        (do (.set m MotorParam/LowerLimit (float 1))
            (.set m MotorParam/UpperLimit (float -1)))))
    j))

(defn spring-joint
  "A spring joint (see the body chapter): `six-dof-joint`'s joint of
  these bodies, pivots, frames and `limits` [t y z], its three angles
  each sprung towards 0 with `stiffness` (N m/rad) and `damping`
  (N m s/rad)."
  [control-a control-b pivot-a pivot-b frame-a frame-b limits stiffness damping]
  (let [^com.jme3.bullet.joints.New6Dof j
        (six-dof-joint control-a control-b pivot-a pivot-b frame-a frame-b limits)]
    (doseq [dof (range 3 6) :let [dof (int dof)]]
      (.enableSpring j dof true)
      (.setStiffness j dof (float stiffness) false)
      (.setDamping j dof (float damping) false)
      (.setEquilibriumPoint j dof (float 0)))
    j))

(defn limit-rows!
  "Nothing: native Bullet runs no constraint written in Java (on jBullet
  this adds cortex.JointLimit's rows; here hinges are limited
  speculatively, see `limit-hinge!`)."
  [joint _spec]
  joint)

(defn- torques-as-impulses!
  "Before a substep of `h` seconds: each body of `space` marked
  `torqued` that holds a torque t is given the impulse t h on its spin,
  and t is taken off it for the substep and added to `held` (body, then
  t) for `restore-torques!`; a body holding none is unmarked."
  [^PhysicsSpace space h ^java.util.ArrayList held]
  (let [it (.iterator (.getRigidBodyList space))
        t (Vector3f.)]
    (while (.hasNext it)
      (let [^PhysicsRigidBody b (.next it)]
        (when (identical? torqued (.getApplicationData b))
          (.totalAppliedTorque b t)
          (if (and (zero? (.x t)) (zero? (.y t)) (zero? (.z t)))
            (.setApplicationData b nil)
            (let [kept (.clone t)]
              (.applyTorqueImpulse b (.mult t (float h)))
              (.applyTorque b (.negate kept))
              (.add held b)
              (.add held kept))))))))

(defn- restore-torques!
  "After a substep: give back the torques `torques-as-impulses!` took
  off, and empty `held`."
  [^java.util.ArrayList held]
  (loop [i 0]
    (when (< i (.size held))
      (.applyTorque ^PhysicsRigidBody (.get held i) ^Vector3f (.get held (inc i)))
      (recur (+ i 2))))
  (.clear held))

(def solver-iterations
  "The constraint solver's passes per Bullet step that cortex's spaces
  take: 20, twice Bullet's default (see the physics-trust chapter)."
  20)

(defn configure-space!
  "Set `space` up as cortex simulates: `solver-iterations`; split
  impulse off, as in jBullet; hinges limited speculatively; torques
  handed over as impulses (`torques-as-impulses!`); Blender's collision
  collections decide which of its bodies collide (see
  `set-collections!`)."
  ^PhysicsSpace [^PhysicsSpace space]
  (.setSolverNumIterations space (int solver-iterations))
  (doto ^SolverInfo (.getSolverInfo space)
    (.setSplitImpulseEnabled false)
    ;; constraints in a (seeded) random order and warm starting, the
    ;; mode jBullet's own solver has (cortex's jBullet worlds solve
    ;; contacts in a fixed order since), and SIMD, native Bullet's default;
    ;; one friction direction a point (two, mode 277, fail other checks:
    ;; the physics-trust chapter's A-frame)
    (.setMode (int (bit-or 1 4 256))))
  (.addCollisionGroupListener space collections-listener (int blender-group))
  (let [held (java.util.ArrayList.)]
    (.addTickListener space (reify com.jme3.bullet.PhysicsTickListener
                              (prePhysicsTick [_ s h]
                                (speculate! s)
                                (torques-as-impulses! s h held))
                              (physicsTick [_ _ _] (restore-torques! held)))))
  space)

(defn- scene-bodies
  "The rigid bodies controlling `spatial` and its descendants, depth
  first, in the order of the scene graph."
  [^com.jme3.scene.Spatial spatial]
  (concat (for [i (range (.getNumControls spatial))
                :let [c (.getControl spatial (int i))]
                :when (instance? PhysicsRigidBody c)]
            c)
          (when (instance? com.jme3.scene.Node spatial)
            (mapcat scene-bodies (.getChildren ^com.jme3.scene.Node spatial)))))

(defn add-all!
  "Add the bodies under `spatial`, and their joints, to `space`: Minie's
  addAll adds only the bodies (jme3-jbullet's adds their joints too).
  The joints are added in the scene graph's order, body by body, as
  jme3-jbullet adds them: Minie's lists of a space's bodies and joints
  are in the order of their native addresses, which change from run to
  run, and the solver's results depend on the order of its joints."
  [^PhysicsSpace space ^com.jme3.scene.Spatial spatial]
  (.addAll space spatial)
  (let [present (java.util.IdentityHashMap.)]
    (doseq [j (.getJointList space)] (.put present j true))
    (doseq [^PhysicsRigidBody b (scene-bodies spatial)
            ^PhysicsJoint j (.listJoints b)
            :when (not (.containsKey present j))]
      (.put present j true)
      (.addJoint space j))))

(defn reduce-contacts
  "Fold `f` over the contact manifolds of `space`'s last step: (f acc o0
  o1 touching? impulse), o0 and o1 the two collision objects (as
  `collision-object` names bodies), touching? when a point lies within
  `touch-distance` or carried an impulse, impulse the summed normal
  impulse of the points in contact. `wanted?` (of a collision object)
  picks the manifolds worth reading; the others, and those holding no
  point, are skipped. Every point's impulse counts: native Bullet's
  resting points lie a hair apart (within its contact threshold) and
  still carry the weight."
  [^PhysicsSpace space touch-distance wanted? f init]
  (let [d (double touch-distance)]
    (reduce (fn [acc ^long m]
              (let [n (PersistentManifolds/countPoints m)]
                (if (zero? n)
                  acc
                  (let [b0 (PhysicsCollisionObject/findInstance (PersistentManifolds/getBodyAId m))
                        b1 (PhysicsCollisionObject/findInstance (PersistentManifolds/getBodyBId m))]
                    (if (or (wanted? b0) (wanted? b1))
                      (let [[touching? impulse]
                            (loop [i 0 touching? false impulse 0.0]
                              (if (< i n)
                                (let [p (PersistentManifolds/getPointId m i)
                                      dist (double (ManifoldPoints/getDistance1 p))
                                      imp (double (ManifoldPoints/getAppliedImpulse p))]
                                  (recur (inc i) (or touching? (<= dist d) (pos? imp)) (+ impulse imp)))
                                [touching? impulse]))]
                        (f acc b0 b1 touching? impulse))
                      acc)))))
            init
            (.listManifoldIds space))))
