;; Generated from org/engine.org by lein tangle: edit the chapter, not this file.
(ns cortex.engine
  "The physics engine cortex runs on, jBullet (jme3-jbullet 3.2.4): what
  differs between it and native Bullet (see org/engine.org), behind one
  set of functions. A body's engine object (`rigid-body`) is jBullet's
  own RigidBody, read without going through jME."
  (:refer-clojure :exclude [name])
  (:require [cortex.geometry :as geometry])
  (:import (com.bulletphysics.collision.broadphase Dispatcher)
           (com.bulletphysics.collision.narrowphase ManifoldPoint PersistentManifold)
           (com.bulletphysics.collision.dispatch CollisionObject)
           (com.bulletphysics.collision.shapes CompoundShape ConvexHullShape)
           (com.bulletphysics.dynamics DynamicsWorld RigidBody)
           (com.bulletphysics.dynamics.constraintsolver ConeTwistConstraint HingeConstraint SolverMode
                                                        TypedConstraint)
           (com.bulletphysics.linearmath MatrixUtil ScalarUtil Transform)
           (com.jme3.bullet PhysicsSpace)
           (com.jme3.bullet.collision PhysicsCollisionObject)
           (com.jme3.bullet.collision.shapes CollisionShape GImpactCollisionShape
                                             MeshCollisionShape)
           (com.jme3.bullet.joints PhysicsJoint)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (cortex JointLimit JointSpring MeteredSixDofJoint)
           (com.jme3.math Matrix3f Vector3f)
           (com.jme3.scene Mesh)
           (javax.vecmath Quat4f)))

(set! *warn-on-reflection* true)

(def name
  "Which engine this is: :jbullet or :native."
  :jbullet)

(def label
  "This engine's name as people read it, for reports."
  "jBullet")

(defn rigid-body
  "The engine's own object for the jME body `body` (a RigidBodyControl
  or PhysicsRigidBody): here jBullet's RigidBody."
  ^RigidBody [^PhysicsRigidBody body]
  (.getObjectId body))

(defn collision-object
  "What the engine's contact manifolds name `body` by (see `reduce-contacts`)."
  [^PhysicsRigidBody body]
  (.getObjectId body))

(defn rotation-matrix
  "How the jME body `body` is turned now, a new Matrix3f."
  ^Matrix3f [^PhysicsRigidBody body]
  (.getPhysicsRotationMatrix body))

(defn applied-impulse
  "The impulse `joint` applied in the last step (see ImpulseMeter)."
  ^double [^PhysicsJoint joint]
  (.getAppliedImpulse joint))

(defn gimpact-shape
  "A GImpact (moving triangle mesh) collision shape of `mesh`."
  ^CollisionShape [^Mesh mesh]
  (GImpactCollisionShape. mesh))

(defn mesh-shape
  "A static triangle mesh (BVH) collision shape of `mesh`."
  ^CollisionShape [^Mesh mesh]
  (MeshCollisionShape. mesh))

(defn orientation
  "How the engine body `rb` is turned now, [x y z w], jME's axes."
  [^RigidBody rb]
  (let [q (.getOrientation rb (Quat4f.))]
    [(double (.x q)) (double (.y q)) (double (.z q)) (double (.w q))]))

(defn- triple [^javax.vecmath.Vector3f v] [(double (.x v)) (double (.y v)) (double (.z v))])

(defn position
  "Where the engine body `rb`'s centre of mass is now, [x y z]."
  [^RigidBody rb]
  (triple (.getCenterOfMassPosition rb (javax.vecmath.Vector3f.))))

(defn linear-velocity
  "`rb`'s velocity now, [x y z]."
  [^RigidBody rb]
  (triple (.getLinearVelocity rb (javax.vecmath.Vector3f.))))

(defn angular-velocity
  "`rb`'s angular velocity now, [x y z], jME's axes."
  [^RigidBody rb]
  (triple (.getAngularVelocity rb (javax.vecmath.Vector3f.))))

(defn body-states
  "The state of each engine body of `rbs` now, in one new double array,
  13 numbers a body in their order: centre of mass x y z, orientation
  x y z w, velocity x y z, angular velocity x y z (jME's axes); each
  number is the float the getters above read."
  ^doubles [rbs]
  (let [out (double-array (* 13 (count rbs)))
        q (Quat4f.) v (javax.vecmath.Vector3f.)
        put3 (fn [^long i ^javax.vecmath.Vector3f v]
               (aset out i (double (.x v))) (aset out (+ i 1) (double (.y v)))
               (aset out (+ i 2) (double (.z v))))]
    (reduce (fn [^long i ^RigidBody rb]
              (put3 i (.getCenterOfMassPosition rb v))
              (.getOrientation rb q)
              (aset out (+ i 3) (double (.x q))) (aset out (+ i 4) (double (.y q)))
              (aset out (+ i 5) (double (.z q))) (aset out (+ i 6) (double (.w q)))
              (put3 (+ i 7) (.getLinearVelocity rb v))
              (put3 (+ i 10) (.getAngularVelocity rb v))
              (+ i 13))
            0 rbs)
    out))

(defn inverse-mass
  "1/m of the engine body `rb`, 0 for a static one."
  ^double [^RigidBody rb]
  (.getInvMass rb))

(defn inverse-inertia
  "The inverse principal moments of `rb`, in its own frame, [x y z]."
  [^RigidBody rb]
  (triple (.getInvInertiaDiagLocal rb (javax.vecmath.Vector3f.))))

(defn apply-torques!
  "Torque `t` ([x y z], world) on the engine body `rb-b` and -t on `rb-a`,
  for the next step; both woken."
  [^RigidBody rb-a ^RigidBody rb-b [x y z]]
  (let [t (javax.vecmath.Vector3f. (float x) (float y) (float z))]
    (.applyTorque rb-b t)
    (.activate rb-b)
    (.negate t)
    (.applyTorque rb-a t)
    (.activate rb-a)))

(defn set-inertia!
  "Give `body` (a jME PhysicsRigidBody) mass `mass` and the principal
  moments [ix iy iz] (Bullet keeps the inverse of each)."
  [^PhysicsRigidBody body mass [ix iy iz]]
  (doto (.getObjectId body)
    (.setMassProps (float mass) (javax.vecmath.Vector3f. (float ix) (float iy) (float iz)))
    (.updateInertiaTensor)))

(defn clear-inertia!
  "Make `body` unable to turn: inverse inertia 0."
  [^PhysicsRigidBody body]
  (doto (.getObjectId body)
    (.setInvInertiaDiagLocal (javax.vecmath.Vector3f.))
    (.updateInertiaTensor)))

(defn set-sleep!
  "`:start-asleep` (it sleeps until something wakes it) or `:never`
  (it never sleeps) for `body`."
  [^PhysicsRigidBody body how]
  (.setActivationState (.getObjectId body)
                       (case how
                         :start-asleep CollisionObject/WANTS_DEACTIVATION
                         :never CollisionObject/DISABLE_DEACTIVATION)))

(defn set-collections!
  "Put `body` in Blender's collision collections `mask` (20 bits): it
  collides with a body that shares one of them, and with what is in
  jME's first collision group (a floor, say) when `mask` has the
  first. jME's groups do it here: a body's group and the groups it
  collides with are both `mask`."
  [^PhysicsCollisionObject body mask]
  (let [m (int (bit-and (long mask) 0xfffff))]
    (.setCollisionGroup body m)
    (.setCollideWithGroups body m)))

(defn breaking-threshold!
  "Make `joint` breakable at `threshold`: here a 6-DOF joint clamps its
  rows at it (see MeteredSixDofJoint); every joint measures its impulse
  (see `broken?`)."
  [^PhysicsJoint joint threshold]
  (when (instance? MeteredSixDofJoint joint)
    (.setBreakingThreshold ^MeteredSixDofJoint joint (float threshold))))

(defn broken?
  "Whether the breakable `joint` broke in the last substep: its applied
  impulse reached `threshold`."
  [^PhysicsJoint joint threshold]
  (>= (.getAppliedImpulse joint) (double threshold)))

(defn blender-solver-order!
  "Have `space` solve contacts as Blender's world does, as far as jBullet
  goes: two boxes meet through cortex.BoxBoxAlgorithm, all their contact
  points at once, as through Blender's box-box algorithm, which jBullet
  lacks (a ragdoll's shin no longer sinks through a ground plane); and
  cortex.BlenderContactSolver solves the contacts as Bullet 2.8 does
  (one friction row a point along its sliding, in a fixed order, warm
  started; jBullet's own shuffles them every step and gives each point
  two friction rows kept from step to step). Joints are solved as
  jBullet solves them, in the order they were added. Full-size pairs
  keep jBullet's own algorithm, no contact slop, one friction row and
  Bullet's ERP of 0.2, unlike cortex's own worlds (see
  `configure-space!`). See the Physics tab chapter for what
  each changed."
  [^PhysicsSpace space]
  (let [^DynamicsWorld w (.getDynamicsWorld space)
        d ^com.bulletphysics.collision.dispatch.CollisionDispatcher (.getDispatcher w)]
    ;; full-size pairs meet through jBullet's own algorithm
    (cortex.SmallConvexAlgorithm/register d (float geometry/thin) false (.getSolverInfo w))
    (cortex.BoxBoxAlgorithm/register d)
    (.setConstraintSolver ^com.bulletphysics.dynamics.DiscreteDynamicsWorld w (cortex.BlenderContactSolver.))
    (set! (.solverMode (.getSolverInfo w))
          (int (bit-or SolverMode/SOLVER_USE_WARMSTARTING SolverMode/SOLVER_CACHE_FRIENDLY)))
    ;; and Bullet 2.8's contacts have no slop, and Bullet's ERP of 0.2
    (set! (.linearSlop (.getSolverInfo w)) (float 0))
    (set! (.erp (.getSolverInfo w)) (float 0.2))))

(defn- skew
  "The cross-product matrix of [x y z], rows."
  [[x y z]]
  [[0.0 (- z) y] [z 0.0 (- x)] [(- y) x 0.0]])

(defn- m*v [m v] (mapv (fn [row] (reduce + (map * row v))) m))
(defn- cross3 [[ax ay az] [bx by bz]]
  [(- (* ay bz) (* az by)) (- (* az bx) (* ax bz)) (- (* ax by) (* ay bx))])

(defn- solve3
  "x with m x = b, m a 3x3 (rows), by Cramer's rule."
  [m b]
  (let [det (fn [[[a b c] [d e f] [g h i]]]
              (+ (* a (- (* e i) (* f h))) (- (* b (- (* d i) (* f g)))) (* c (- (* d h) (* e g)))))
        d (det m)
        col (fn [k] (mapv (fn [row bi] (assoc row k bi)) m b))]
    (mapv #(/ (det (col %)) d) (range 3))))

(defn- gyroscopic
  "Body `rb`'s angular velocity `w` after one Newton step of Bullet 2.8's
  implicit gyroscopic term over `dt`, in the body's frame: I w' = I w -
  dt w' x I w'. [x y z] doubles; `w` itself for a body that cannot turn
  about some axis."
  [^RigidBody rb w dt]
  (let [inv (.getInvInertiaDiagLocal rb (javax.vecmath.Vector3f.))
        inertia (mapv #(/ 1.0 (double %)) [(.x inv) (.y inv) (.z inv)])]
    (if-not (every? #(Double/isFinite %) inertia)
      w
      (let [basis (.basis (.getWorldTransform rb (Transform.)))
            r (vec (for [i (range 3)] (vec (for [j (range 3)] (double (.getElement basis (int i) (int j)))))))
            wb (m*v (apply mapv vector r) w)
            ib (mapv * inertia wb)
            f (mapv #(* dt %) (cross3 wb ib))
            s0 (skew wb) s1 (skew ib)
            ;; the Jacobian of the residual: I + dt (skew(w) I - skew(I w))
            jac (vec (for [i (range 3)]
                       (vec (for [j (range 3)]
                              (+ (if (= i j) (inertia i) 0.0)
                                 (* dt (- (* (get-in s0 [i j]) (inertia j)) (get-in s1 [i j]))))))))]
        (m*v r (mapv - wb (solve3 jac f)))))))

(defn blender-velocities!
  "Before a substep of `dt`: give each moving body of `space` the
  velocities Bullet 2.8 and later give it before their solver, where
  jBullet (Bullet 2.72) gives others. Bullet 2.8 damps the velocities
  first, then adds gravity (in its solver) and turns the body by its
  implicit gyroscopic term (BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY,
  on by default; jBullet has none): one Newton step of I w' = I w - dt
  w' x I w', in the body's frame. jBullet adds gravity first and damps
  the sum. So the damping and the gyroscopic step are taken here, and
  the velocities set so that jBullet's own gravity and damping, which
  follow, end where Bullet 2.8's do: the linear velocity v + g dt
  ((1 - d)^-dt - 1), the angular one divided by jBullet's (1 - d)^dt.
  (Forces other than gravity are damped as jBullet damps them.)"
  [^PhysicsSpace space dt]
  (let [dt (double dt)]
    (doseq [^PhysicsRigidBody b (.getRigidBodyList space)
            :when (pos? (.getMass b))
            :let [^RigidBody rb (.getObjectId b)]
            :when (.isActive rb)]
      (let [keep-lin (Math/pow (- 1.0 (double (.getLinearDamping rb))) dt)
            keep-ang (Math/pow (- 1.0 (double (.getAngularDamping rb))) dt)
            w (.getAngularVelocity rb (javax.vecmath.Vector3f.))
            [x y z] (gyroscopic rb (mapv #(* keep-ang (double %)) [(.x w) (.y w) (.z w)]) dt)
            ;; jBullet damps what follows by keep-ang; nothing to undo at 0
            undo (if (pos? keep-ang) (/ 1.0 keep-ang) 1.0)]
        (.setAngularVelocity rb (javax.vecmath.Vector3f. (float (* undo x)) (float (* undo y)) (float (* undo z))))
        (when (pos? keep-lin)
          (let [v (.getLinearVelocity rb (javax.vecmath.Vector3f.))
                g (.getGravity rb (javax.vecmath.Vector3f.))
                k (* (double (.getInvMass rb)) dt (- (/ 1.0 keep-lin) 1.0))]
            (.setLinearVelocity rb (javax.vecmath.Vector3f. (float (+ (.x v) (* k (.x g))))
                                                            (float (+ (.y v) (* k (.y g))))
                                                            (float (+ (.z v) (* k (.z g))))))))))))

(defn hull-points
  "The points of `shape`'s hull (or of its first child's, for a compound
  shape), [[x y z] ...], or nil when it is no hull."
  [^CollisionShape shape]
  (let [s (.getCShape shape)
        s (if (instance? CompoundShape s) (.getChildShape ^CompoundShape s 0) s)]
    (when (instance? ConvexHullShape s)
      (mapv triple (.getPoints ^ConvexHullShape s)))))

(def ^{:arglists '([points])
       :doc "The volume of the convex hull of `points` ([[x y z] ...]): see
  cortex.geometry/hull-volume."}
  hull-volume geometry/hull-volume)

(defn hull-margin
  "The collision margin cortex gives hull shapes: jme3-jbullet's own, 0."
  ^double []
  0.0)

(def ^{:doc "The thickness below which a body is small: cortex.geometry/thin."}
  thin geometry/thin)

(defn thickness
  "How thick `shape` counts as (of a compound, its thinnest child): its
  smallest extent along its own axes, or for a sheet a tenth of the next
  (as cortex.geometry/sheet-thickness), read by the shape's supporting
  points; nil for a shape that is not convex."
  [^CollisionShape shape]
  (letfn [(t [^com.bulletphysics.collision.shapes.CollisionShape s]
            (cond (instance? CompoundShape s)
                  (reduce min ##Inf (map #(t (.childShape ^com.bulletphysics.collision.shapes.CompoundShapeChild %))
                                         (.getChildList ^CompoundShape s)))
                  (.isConvex s) (double (cortex.SmallConvexAlgorithm/thickness s))
                  :else ##Inf))]
    (let [d (double (t (.getCShape shape)))]
      (when (< d ##Inf) d))))

(defn atan2-fast
  "jBullet's ScalarUtil.atan2Fast, by which its hinge measures the angle
  its limits hold: exact at multiples of pi/4, monotonic."
  ^double [^double y ^double x]
  (let [c1 (/ Math/PI 4) c2 (* 3 c1) ay (Math/abs y)
        angle (if (>= x 0)
                (- c1 (* c1 (/ (- x ay) (+ x ay))))
                (- c2 (* c1 (/ (+ x ay) (- ay x)))))]
    (if (neg? y) (- angle) angle)))

(defn hinge-limits
  "The [low high] to give a jME HingeJoint (made from two axes) so that
  the designer's limits [lo hi] (radians, right-hand rule about the
  designer's axis, second segment relative to the first) hold exactly:
  jBullet's angle is -atan2Fast of the designer's."
  [[lo hi]]
  (let [fast (fn [a] (atan2-fast (Math/sin a) (Math/cos a)))]
    [(- (fast (double hi))) (- (fast (double lo)))]))

(defn frame-hinge-limit
  "The limit to give a FrameHingeJoint so that it stops at `angle`:
  jBullet compares its limits with atan2Fast of the angle."
  [angle]
  (ScalarUtil/atan2Fast (float (Math/sin angle)) (float (Math/cos angle))))

(defn collide-linked!
  "Whether the two bodies `joint` links collide with each other."
  [^PhysicsJoint joint collide?]
  (.setCollisionBetweenLinkedBodys joint (boolean collide?))
  joint)

(defn collide-linked?
  "Do the two bodies `joint` links collide with each other?"
  [^PhysicsJoint joint]
  (.isCollisionBetweenLinkedBodys joint))

(defn pivots
  "[pivot-a pivot-b] of `joint`: its point in each body's frame."
  [^PhysicsJoint joint]
  [(.getPivotA joint) (.getPivotB joint)])

(defn joints
  "The joints attached to the jME body `body`, a seq."
  [^PhysicsRigidBody body]
  (seq (.getJoints body)))

(defn- basis-rotation
  "The rotation of a jBullet Transform's basis, [x y z w]. A hinge's
  second frame is left-handed (its third column is minus the axis, as in
  Bullet's C++ original); its third column is turned round first."
  [^Transform t]
  (let [q (Quat4f.)
        m (javax.vecmath.Matrix3f. (.basis t))]
    (when (neg? (.determinant m))
      (dotimes [i 3] (.setElement m i 2 (- (.getElement m i 2)))))
    (MatrixUtil/getRotation m q)
    [(double (.x q)) (double (.y q)) (double (.z q)) (double (.w q))]))

(defn joint-frames
  "The frames a joint is read in, when the engine keeps them: for a
  hinge given whole frames (a FrameHingeJoint), {:frame-a q :frame-b q
  :axis [0 0 1]}, its frame in each body, the axis its Z; for jBullet's
  cone joint {:frame-a q :frame-b q}; nil for any other joint."
  [^PhysicsJoint joint]
  (let [c (.getObjectId joint)]
    (cond
      (instance? HingeConstraint c)
      {:frame-a (basis-rotation (.getAFrame ^HingeConstraint c (Transform.)))
       :frame-b (basis-rotation (.getBFrame ^HingeConstraint c (Transform.)))
       :axis [0.0 0.0 1.0]}
      (instance? ConeTwistConstraint c)
      {:frame-a (basis-rotation (.getAFrame ^ConeTwistConstraint c (Transform.)))
       :frame-b (basis-rotation (.getBFrame ^ConeTwistConstraint c (Transform.)))})))

(def ^:private ^java.lang.reflect.Field hinge-frame-b
  (doto (.getDeclaredField HingeConstraint "rbBFrame") (.setAccessible true)))

(defn zero-hinge!
  "Make the HingeJoint `joint`'s angle 0 where its two bodies are now."
  [^com.jme3.bullet.joints.HingeJoint joint]
  (let [^HingeConstraint c (.getObjectId joint)
        ^Transform fb (.get hinge-frame-b c)
        fa (.getAFrame c (Transform.))
        ta (.getCenterOfMassTransform (.getRigidBodyA c) (Transform.))
        tb (.getCenterOfMassTransform (.getRigidBodyB c) (Transform.))
        m (javax.vecmath.Matrix3f. (.basis tb))]
    ;; B's frame = B's rotation^-1 * A's rotation * A's frame, third
    ;; column negated; a hinge that reads 0 already is left as built
    (when-not (< (Math/abs (.getHingeAngle c)) 1e-6)
      (.transpose m)
      (.mul m (.basis ta))
      (.mul m (.basis fa))
      (dotimes [i 3] (.setElement m i 2 (- (.getElement m i 2))))
      (.set (.basis fb) m))
    joint))

(defn limit-hinge!
  "Limit the HingeJoint `joint` to [low high], in the engine's sense of
  its angle (see `hinge-limits`), about the zero `zero-hinge!` set."
  [^com.jme3.bullet.joints.HingeJoint joint low high]
  (.setLimit joint (float low) (float high))
  joint)

(def six-dof-class
  "The class of the joint `six-dof-joint` makes."
  com.jme3.bullet.joints.SixDofJoint)

(def six-dof-safe-middle
  "The widest limit cortex gives a six-DOF joint's middle angle when it
  has the choice (see the body chapter's cones): jBullet does not
  normalise the joint's axes, which near a right angle push its limits
  by 1/cos of the angle."
  1.2)

(defn six-dof-angles
  "The three angles [x y z] the six-DOF `joint` (see `six-dof-joint`)
  reads between its bodies as they are now, the ones its limits hold."
  [^com.jme3.bullet.joints.SixDofJoint joint]
  (let [^com.bulletphysics.dynamics.constraintsolver.Generic6DofConstraint c (.getObjectId joint)]
    (.calculateTransforms c)
    (mapv #(double (.getAngle c (int %))) (range 3))))

(defn six-dof-joint
  "A joint between the bodies of `control-a` and `control-b` at
  `pivot-a`, `pivot-b` whose translation is locked and whose three
  angles (Euler XYZ in the joint's frame) keep within [-t t], [-y y],
  [-z z] of `limits` [t y z], or turn freely when `limits` is nil; the
  joint's frame is `frame-a`, `frame-b` (Matrix3f, each in its body's
  frame), or the bodies' own when nil. Here jBullet's SixDofJoint."
  [control-a control-b ^Vector3f pivot-a ^Vector3f pivot-b frame-a frame-b limits]
  (let [j (if frame-a
            (com.jme3.bullet.joints.SixDofJoint. ^PhysicsRigidBody control-a ^PhysicsRigidBody control-b
                                                 pivot-a pivot-b ^Matrix3f frame-a ^Matrix3f frame-b true)
            (com.jme3.bullet.joints.SixDofJoint. ^PhysicsRigidBody control-a ^PhysicsRigidBody control-b
                                                 pivot-a pivot-b false))]
    (.setLinearLowerLimit j Vector3f/ZERO)
    (.setLinearUpperLimit j Vector3f/ZERO)
    (when-let [[t y z] limits]
      (.setAngularLowerLimit j (Vector3f. (float (- (double t))) (float (- (double y))) (float (- (double z)))))
      (.setAngularUpperLimit j (Vector3f. (float t) (float y) (float z))))
    j))

(def ^:private ^java.util.Map limit-rows
  "Each joint given rows of cortex's own (`limit-rows!`, `spring-joint`;
  weakly held) -> [sequence [constraint ...]], the sequence the order
  the joints were given them in."
  (java.util.Collections/synchronizedMap (java.util.WeakHashMap.)))

(def ^:private ^java.util.concurrent.atomic.AtomicLong limit-sequence
  (java.util.concurrent.atomic.AtomicLong.))

(defn- add-rows!
  "Keep jBullet constraint `c` beside `joint`, after any it has, to join
  whatever space `joint` is in (see `place-limit-rows!`)."
  [joint c]
  (locking limit-rows
    (let [[n cs] (.get limit-rows joint)]
      (.put limit-rows joint [(or n (.incrementAndGet limit-sequence)) (conj (or cs []) c)]))))

(defn limit-rows!
  "Give the hinge or cone `joint` rows of its own that hold its limits
  as proprioception reads them (cortex.JointLimit), added to whatever
  space `joint` is in before each step. `spec`: :frame-a and :frame-b,
  the joint's frame in each body ([x y z w], jME's axes), and for a
  hinge its :axis in that frame and :limit [lo hi], for a cone its
  :twist, :limit-xz and :limit-xy."
  [^PhysicsJoint joint {:keys [frame-a frame-b axis limit twist limit-xz limit-xy]}]
  (let [^RigidBody a (.getObjectId (.getBodyA joint))
        ^RigidBody b (.getObjectId (.getBodyB joint))
        da #(double-array (map double %))
        l (if axis
            (let [[lo hi] limit]
              (JointLimit. a b ^doubles (da frame-a) ^doubles (da frame-b) ^doubles (da axis)
                           (double lo) (double hi)))
            (JointLimit. a b ^doubles (da frame-a) ^doubles (da frame-b)
                         (double twist) (double limit-xz) (double limit-xy)))]
    (let [^JointLimit l l
          vec (fn [^Vector3f v] (javax.vecmath.Vector3f. (.x v) (.y v) (.z v)))]
      (set! (.pivotA l) (vec (.getPivotA joint)))
      (set! (.pivotB l) (vec (.getPivotB joint))))
    (add-rows! joint l)
    joint))

(defn- place-limit-rows!
  "Before a step of `space`: when its joints have changed since the last
  step (`seen`, an IdentityHashMap of them), add the limit rows of its
  joints that are not in its dynamics world yet, in the order they were
  given, and take out those whose joints have left it. `placed` (an
  IdentityHashMap, JointLimit -> joint) is what this space has."
  [^PhysicsSpace space ^java.util.Map seen ^java.util.Map placed]
  (let [joints (.getJointList space)]
    (when-not (and (== (count joints) (.size seen)) (every? #(.containsKey seen %) joints))
      (let [^DynamicsWorld world (.getDynamicsWorld space)]
        (.clear seen)
        (doseq [j joints] (.put seen j true))
        (doseq [[l j] (vec placed)
                :when (not (.containsKey seen j))]
          (.removeConstraint world l)
          (.remove placed l))
        (doseq [[_ ^TypedConstraint l j] (sort-by first (mapcat (fn [j] (when-let [[n cs] (.get limit-rows j)]
                                                                          (for [c cs] [n c j])))
                                                                joints))
                :when (not (.containsKey placed l))]
          (.addConstraint world l true)
          (.put placed l j))))))

(defn- frame-array
  "The rotation `m` (Matrix3f; none: no turn) as a quaternion [x y z w]."
  ^doubles [m]
  (let [q (com.jme3.math.Quaternion.)]
    (when m (.fromRotationMatrix q ^Matrix3f m))
    (double-array [(.getX q) (.getY q) (.getZ q) (.getW q)])))

(defn spring-joint
  "A spring joint (see the body chapter): `six-dof-joint`'s joint of
  these bodies, pivots, frames and `limits` [t y z], its three angles
  each sprung towards 0 with `stiffness` (N m/rad) and `damping`
  (N m s/rad). jBullet has no spring constraint, so the springs are
  cortex.JointSpring, placed with the joint (`add-rows!`)."
  [control-a control-b pivot-a pivot-b frame-a frame-b limits stiffness damping]
  (let [^PhysicsJoint j (six-dof-joint control-a control-b pivot-a pivot-b frame-a frame-b limits)]
    (add-rows! j (JointSpring. ^RigidBody (.getObjectId (.getBodyA j))
                               ^RigidBody (.getObjectId (.getBodyB j))
                               (frame-array frame-a) (frame-array frame-b)
                               (double stiffness) (double damping)))
    j))

(def ^:private ^java.lang.reflect.Field local-time
  "jBullet's DiscreteDynamicsWorld.localTime, made writable."
  (doto (.getDeclaredField com.bulletphysics.dynamics.DiscreteDynamicsWorld "localTime")
    (.setAccessible true)))

(defn- start-clock!
  "Start `space`'s world with no time handed to it, as Bullet's C++
  world starts: jBullet's starts at 1/60 s, one step ahead."
  [^PhysicsSpace space]
  (.setFloat local-time (.getDynamicsWorld space) (float 0)))

(def solver-iterations
  "The constraint solver's passes per Bullet step that cortex's spaces
  take: 20, twice Bullet's default (see the physics-trust chapter)."
  20)

(def contact-slop
  "How far a resting contact is left inside what it rests on, on
  jBullet: 0.001 m (see the physics-trust chapter, \"Resting
  contacts\")."
  0.001)

(def contact-erp
  "The share of a contact point's depth that cortex's jBullet worlds push
  out in a Bullet step: 0.1, half of Bullet's 0.2, which threw a limp
  humanoid back up from its landing (see the text above)."
  0.1)

(defn configure-space!
  "Set `space` up as cortex simulates: its clock at 0 (`start-clock!`),
  jBullet's defaults but for `solver-iterations` and `contact-slop` (0
  once a body thinner than `thin` touches anything), the limit rows of
  its joints (see `limit-rows!`) added before each step, two convex
  shapes of which one is thinner than `thin`, or neither has a margin of
  its own, meeting through cortex.SmallConvexAlgorithm (see the shapes
  chapter), a box meeting the floor through cortex.FloorBoxes, and
  contacts solved by cortex.BlenderContactSolver with two friction rows
  a point, at `contact-erp`, which also takes back that share of what a
  point whose friction held has slid."
  ^PhysicsSpace [^PhysicsSpace space]
  (start-clock! space)
  (.setSolverNumIterations space (int solver-iterations))
  (let [^DynamicsWorld w (.getDynamicsWorld space)
        d ^com.bulletphysics.collision.dispatch.CollisionDispatcher (.getDispatcher w)]
    (set! (.linearSlop (.getSolverInfo w)) (float contact-slop))
    (set! (.erp (.getSolverInfo w)) (float contact-erp))
    (.setConstraintSolver ^com.bulletphysics.dynamics.DiscreteDynamicsWorld w
                          (cortex.BlenderContactSolver. true (float contact-erp)))
    (cortex.SmallConvexAlgorithm/register d (float geometry/thin) true (.getSolverInfo w))
    (cortex.FloorBoxes/register d (float geometry/thin) (.getSolverInfo w)))
  (let [seen (java.util.IdentityHashMap.)
        placed (java.util.IdentityHashMap.)]
    (.addTickListener space (reify com.jme3.bullet.PhysicsTickListener
                              (prePhysicsTick [_ s _] (place-limit-rows! s seen placed))
                              (physicsTick [_ _ _]))))
  space)

(defn add-all!
  "Add the bodies under `spatial`, and their joints, to `space`."
  [^PhysicsSpace space ^com.jme3.scene.Spatial spatial]
  (.addAll space spatial))

(defn- manifold-contact
  "[touching? summed-normal-impulse] of the points of manifold `m`."
  [^PersistentManifold m ^double touch-distance]
  (let [n (.getNumContacts m)]
    (loop [i 0 touching? false impulse 0.0]
      (if (< i n)
        (let [^ManifoldPoint p (.getContactPoint m i)
              d (.getDistance p)
              imp (if (<= d 0.0) (double (.appliedImpulse p)) 0.0)]
          (recur (inc i)
                 (or touching? (<= d touch-distance) (pos? imp))
                 (+ impulse imp)))
        [touching? impulse]))))

(defn reduce-contacts
  "Fold `f` over the contact manifolds of `space`'s last step: (f acc o0
  o1 touching? impulse), o0 and o1 the two collision objects (as
  `collision-object` names bodies), touching? when a point lies within
  `touch-distance` or carried an impulse, impulse the summed normal
  impulse of the points in contact. `wanted?` (of a collision object)
  picks the manifolds worth reading; the others are skipped."
  [^PhysicsSpace space touch-distance wanted? f init]
  (let [^DynamicsWorld world (.getDynamicsWorld space)
        ^Dispatcher dispatcher (.getDispatcher world)
        n (.getNumManifolds dispatcher)
        d (double touch-distance)]
    (loop [i 0 acc init]
      (if (< i n)
        (let [^PersistentManifold m (.getManifoldByIndexInternal dispatcher i)
              b0 (.getBody0 m) b1 (.getBody1 m)]
          (recur (inc i)
                 (if (or (wanted? b0) (wanted? b1))
                   (let [[touching? impulse] (manifold-contact m d)]
                     (f acc b0 b1 touching? impulse))
                   acc)))
        acc))))
