;; Generated from org/proprioception.org by lein tangle: edit the chapter, not this file.
(ns cortex.proprioception
  "Proprioception: how each joint of a creature built by
  cortex.body/body! is bent, and how fast, read from its rigid bodies.

  Entry points: `proprioception` (every joint of a creature, by name),
  `sensors` (what reading a creature's joints needs, computed once),
  `read-joints` and `joint-state` (reading with those sensors). The
  quaternion helpers (`q*`, `q-conj`, `rotate`, `swing-twist`, ...) work
  on [x y z w] and [x y z] vectors of numbers.

    hinge         {:type :hinge :angle a :velocity w}
    cone, point   {:type :cone|:point :swing [s1 s2] :twist t
                   :angular-velocity [x y z]}

  Readings are of the second segment relative to the first (body! 's
  order), in the joint empty's frame as the first carries it, Blender's
  axes; a hinge's angle is positive by the right-hand rule about its
  :axis, the angle its :limit holds; all zero in the build pose."
  (:require [cortex.body :as body]
            [cortex.engine :as engine])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints PhysicsJoint)
           (com.jme3.scene Geometry Node)))

(set! *warn-on-reflection* true)

(defn q*
  "The Hamilton product p q: rotate by q, then by p."
  [[px py pz pw] [qx qy qz qw]]
  (let [px (double px) py (double py) pz (double pz) pw (double pw)
        qx (double qx) qy (double qy) qz (double qz) qw (double qw)]
    [(+ (* pw qx) (* px qw) (* py qz) (- (* pz qy)))
     (+ (* pw qy) (- (* px qz)) (* py qw) (* pz qx))
     (+ (* pw qz) (* px qy) (- (* py qx)) (* pz qw))
     (- (* pw qw) (* px qx) (* py qy) (* pz qz))]))

(defn q-conj
  "The inverse of the unit quaternion `q`."
  [[x y z w]]
  [(- (double x)) (- (double y)) (- (double z)) (double w)])

(defn rotate
  "The vector `v` rotated by the unit quaternion `q`: v + 2w (u x v) +
  2 u x (u x v), u the vector part and w the scalar part of q."
  [q v]
  (let [ux (double (nth q 0)) uy (double (nth q 1)) uz (double (nth q 2)) w (double (nth q 3))
        x (double (nth v 0)) y (double (nth v 1)) z (double (nth v 2))
        ;; t = 2 (u x v)
        tx (* 2.0 (- (* uy z) (* uz y)))
        ty (* 2.0 (- (* uz x) (* ux z)))
        tz (* 2.0 (- (* ux y) (* uy x)))]
    [(+ x (* w tx) (- (* uy tz) (* uz ty)))
     (+ y (* w ty) (- (* uz tx) (* ux tz)))
     (+ z (* w tz) (- (* ux ty) (* uy tx)))]))

(defn dot
  "The dot product of two vectors of numbers (three-vectors, the common
  case, without a sequence)."
  ^double [a b]
  (if (and (vector? a) (vector? b) (== 3 (count a)) (== 3 (count b)))
    (let [^clojure.lang.IPersistentVector a a ^clojure.lang.IPersistentVector b b]
      (+ (* (double (.nth a 0)) (double (.nth b 0)))
         (* (double (.nth a 1)) (double (.nth b 1)))
         (* (double (.nth a 2)) (double (.nth b 2)))))
    (reduce + 0.0 (map * a b))))

(defn normalize
  "`v` scaled to length 1."
  [v]
  (let [n (Math/sqrt (dot v v))]
    (mapv #(/ (double %) n) v)))

(defn wrap-angle
  "`a` brought into (-pi, pi]."
  ^double [^double a]
  (let [t (- a (* 2 Math/PI (Math/floor (/ (+ a Math/PI) (* 2 Math/PI)))))]
    (if (== t (- Math/PI)) Math/PI t)))

(defn jme->blender
  "A vector in jME's axes (or a quaternion, by its vector part) in
  Blender's: x, -z, y."
  [v]
  (let [x (double (nth v 0)) y (double (nth v 1)) z (double (nth v 2))]
    (if (== 4 (count v))
      [x (- z) y (double (nth v 3))]
      [x (- z) y])))

(defn blender->jme
  "The inverse of `jme->blender`."
  [v]
  (let [x (double (nth v 0)) y (double (nth v 1)) z (double (nth v 2))]
    (if (== 4 (count v))
      [x z (- y) (double (nth v 3))]
      [x z (- y)])))

(defn rotation-vector
  "The rotation `q` as its axis times its angle, the angle in [0, pi]."
  [q]
  (let [[x y z w] (if (neg? (double (peek q))) (mapv - q) (mapv double q))
        s (Math/sqrt (+ (* x x) (* y y) (* z z)))]
    (if (< s 1e-12)
      [(* 2.0 x) (* 2.0 y) (* 2.0 z)]
      (let [k (/ (* 2.0 (Math/atan2 s w)) s)]
        [(* k x) (* k y) (* k z)]))))

(defn from-rotation-vector
  "The unit quaternion of the rotation vector `r` (axis times angle)."
  [r]
  (let [a (Math/sqrt (dot r r))]
    (if (< a 1e-12)
      [0.0 0.0 0.0 1.0]
      (let [k (/ (Math/sin (/ a 2)) a)]
        (conj (mapv #(* k (double %)) r) (Math/cos (/ a 2)))))))

(defn twist-angle
  "The angle, in (-pi, pi], by which the rotation `q` turns about the
  unit axis `u` (its twist, in the swing-twist decomposition)."
  ^double [[x y z w] u]
  (wrap-angle (* 2.0 (Math/atan2 (dot [x y z] u) (double w)))))

(defn swing-twist
  "The rotation `q` (Blender's axes, in a joint's frame) split into a
  twist about X and a swing after it, q = swing * twist:
  {:twist t :swing [y z]}, the swing as its rotation vector's Y and Z."
  [q]
  (let [[x _ _ w :as q] (if (neg? (double (peek q))) (mapv - q) q)
        t (* 2.0 (Math/atan2 (double x) (double w)))
        half (/ t 2)
        swing (q* q [(- (Math/sin half)) 0.0 0.0 (Math/cos half)])
        [_ sy sz] (rotation-vector swing)]
    {:twist (wrap-angle t) :swing [sy sz]}))

(defn rigid-body
  "The engine's body of segment `geom` (see cortex.engine/rigid-body)."
  [^Geometry geom]
  (let [^RigidBodyControl c (.getControl geom RigidBodyControl)]
    (engine/rigid-body c)))

(defn orientation
  "How the engine body `rb` is turned now, [x y z w], jME's axes."
  [rb]
  (engine/orientation rb))

(defn angular-velocity
  "The engine body `rb`'s angular velocity now, [x y z], jME's axes."
  [rb]
  (engine/angular-velocity rb))

(defn- designer-axis
  "A hinge description's :axis (Blender's axes, X when absent), unit,
  in jME's axes."
  [description]
  (let [a (get description :axis [1 0 0])
        v (if (instance? com.jme3.math.Vector3f a)
            (let [^com.jme3.math.Vector3f a a] [(.x a) (.y a) (.z a)])
            a)]
    (blender->jme (normalize v))))

(defn rest-frames
  "The frame of the joint `record` (see cortex.body/joint-records) as
  each of its bodies carries it, {:frame-a q :frame-b q}, and for a
  hinge :axis, its axis in that frame (jME's axes): see the chapter for
  where each comes from."
  [{:keys [type description ^PhysicsJoint physics-joint rotation body-rotations]}]
  (let [from-empty (fn [[qa qb]]
                     {:frame-a (q* (q-conj qa) rotation) :frame-b (q* (q-conj qb) rotation)
                      :axis (when (= type :hinge) (designer-axis description))})]
    (cond
      body-rotations (from-empty body-rotations)
      :else (or (engine/joint-frames physics-joint)
                (from-empty [[0.0 0.0 0.0 1.0] [0.0 0.0 0.0 1.0]])))))

(defn sensor
  "What reading the joint `record` (see cortex.body/joint-records)
  needs: :name, :type, :segments, the bodies :rb-a and :rb-b, the
  :frame-a and :frame-b it is read in, a hinge's :axis in that frame
  (jME's axes), and the record itself."
  [{:keys [name type geoms segments] :as record}]
  (let [[a b] geoms]
    (merge {:name name :type type :segments segments :record record
            :rb-a (rigid-body a) :rb-b (rigid-body b)}
           (rest-frames record))))

(defn sensors
  "The sensors of every joint of `creature`, which body! must have
  built, in the order body! made them."
  [^Node creature]
  (mapv sensor (body/joint-records creature)))

(defn frame-now
  "The joint frame `sensor`'s first body carries, now, jME's world axes."
  [{:keys [rb-a frame-a]}]
  (q* (orientation rb-a) frame-a))

(defn relative-rotation
  "The rotation of the joint frame body B carries relative to the one
  body A carries, in the joint's frame, jME's axes: identity at rest."
  [{:keys [rb-b frame-b] :as sensor}]
  (q* (q-conj (frame-now sensor)) (q* (orientation rb-b) frame-b)))

(defn relative-angular-velocity
  "Body B's angular velocity relative to body A's, in the joint frame
  body A carries, jME's axes."
  [{:keys [rb-a rb-b] :as sensor}]
  (rotate (q-conj (frame-now sensor))
          (mapv - (angular-velocity rb-b) (angular-velocity rb-a))))

(defmacro ^:private q*-part
  "Part `i` (0 to 3: x, y, z, w) of the Hamilton product (`q*`) of the
  quaternions whose parts are the eight primitive expressions given,
  computed as `q*` computes it, to the bit."
  [i px py pz pw qx qy qz qw]
  (case (long i)
    0 `(+ (* ~pw ~qx) (* ~px ~qw) (* ~py ~qz) (- (* ~pz ~qy)))
    1 `(+ (* ~pw ~qy) (- (* ~px ~qz)) (* ~py ~qw) (* ~pz ~qx))
    2 `(+ (* ~pw ~qz) (* ~px ~qy) (- (* ~py ~qx)) (* ~pz ~qw))
    3 `(- (* ~pw ~qw) (* ~px ~qx) (* ~py ~qy) (* ~pz ~qz))))

(defn jme-swing-twist
  "(swing-twist (jme->blender [x y z w])), the same operations in the
  same order, on primitive doubles: a cone's reading without a vector
  made along the way (six times as fast)."
  [^double x ^double y ^double z ^double w]
  (let [;; in Blender's axes: x, -z, y; the sign chosen so that w >= 0
        neg (neg? w)
        qx (if neg (- x) x) qy (if neg (- (- z)) (- z)) qz (if neg (- y) y) qw (if neg (- w) w)
        t (* 2.0 (Math/atan2 qx qw))
        half (/ t 2)
        hx (- (Math/sin half)) hw (Math/cos half)
        ;; swing = (q* q [hx 0 0 hw])
        sx (q*-part 0 qx qy qz qw hx 0.0 0.0 hw)
        sy (q*-part 1 qx qy qz qw hx 0.0 0.0 hw)
        sz (q*-part 2 qx qy qz qw hx 0.0 0.0 hw)
        sw (q*-part 3 qx qy qz qw hx 0.0 0.0 hw)
        ;; its rotation vector's Y and Z, as rotation-vector
        neg (neg? sw)
        sx (if neg (- sx) sx) sy (if neg (- sy) sy) sz (if neg (- sz) sz) sw (if neg (- sw) sw)
        n (Math/sqrt (+ (* sx sx) (* sy sy) (* sz sz)))
        k (if (< n 1e-12) 2.0 (/ (* 2.0 (Math/atan2 n sw)) n))]
    {:twist (wrap-angle t) :swing [(* k sy) (* k sz)]}))

(defn joint-state-of
  "The state of the joint `sensor` reads (see the namespace doc), from
  `states` (cortex.engine/body-states) in which its two bodies are the
  `ia`th and the `ib`th."
  [{:keys [type axis frame-a frame-b]} ^doubles states ia ib]
  ;; the arithmetic of relative-rotation and relative-angular-velocity,
  ;; shared, on primitive doubles (the same operations in the same order
  ;; as q*, q-conj and rotate: the same numbers, without a vector a step)
  (let [a (* 13 (long ia)) b (* 13 (long ib))
        oax (aget states (+ a 3)) oay (aget states (+ a 4))
        oaz (aget states (+ a 5)) oaw (aget states (+ a 6))
        obx (aget states (+ b 3)) oby (aget states (+ b 4))
        obz (aget states (+ b 5)) obw (aget states (+ b 6))
        [fax fay faz faw] frame-a
        [fbx fby fbz fbw] frame-b
        fax (double fax) fay (double fay) faz (double faz) faw (double faw)
        fbx (double fbx) fby (double fby) fbz (double fbz) fbw (double fbw)
        ;; back = (q-conj (q* oa fa))
        bx (- (q*-part 0 oax oay oaz oaw fax fay faz faw))
        by (- (q*-part 1 oax oay oaz oaw fax fay faz faw))
        bz (- (q*-part 2 oax oay oaz oaw fax fay faz faw))
        bw (q*-part 3 oax oay oaz oaw fax fay faz faw)
        ;; q = (q* back (q* ob fb))
        cx (q*-part 0 obx oby obz obw fbx fby fbz fbw)
        cy (q*-part 1 obx oby obz obw fbx fby fbz fbw)
        cz (q*-part 2 obx oby obz obw fbx fby fbz fbw)
        cw (q*-part 3 obx oby obz obw fbx fby fbz fbw)
        x (q*-part 0 bx by bz bw cx cy cz cw)
        y (q*-part 1 bx by bz bw cx cy cz cw)
        z (q*-part 2 bx by bz bw cx cy cz cw)
        w (q*-part 3 bx by bz bw cx cy cz cw)
        ;; the relative angular velocity, rotated by back (as `rotate`)
        vx (- (aget states (+ b 10)) (aget states (+ a 10)))
        vy (- (aget states (+ b 11)) (aget states (+ a 11)))
        vz (- (aget states (+ b 12)) (aget states (+ a 12)))
        tx (* 2.0 (- (* by vz) (* bz vy)))
        ty (* 2.0 (- (* bz vx) (* bx vz)))
        tz (* 2.0 (- (* bx vy) (* by vx)))
        rx (+ vx (* bw tx) (- (* by tz) (* bz ty)))
        ry (+ vy (* bw ty) (- (* bz tx) (* bx tz)))
        rz (+ vz (* bw tz) (- (* bx ty) (* by tx)))]
    (if (= type :hinge)
      (let [[ux uy uz] axis
            ux (double ux) uy (double uy) uz (double uz)]
        ;; as twist-angle and dot
        {:type :hinge
         :angle (wrap-angle (* 2.0 (Math/atan2 (+ (* x ux) (* y uy) (* z uz)) w)))
         :velocity (+ (* rx ux) (* ry uy) (* rz uz))})
      ;; the keys in the order they always had, so that a printed
      ;; observation reads as it did
      (let [{:keys [swing twist]} (jme-swing-twist x y z w)]
        {:type type :swing swing :twist twist :angular-velocity [rx (- rz) ry]}))))

(defn joint-state
  "The state of the joint `sensor` reads, now (see the namespace doc)."
  [{:keys [rb-a rb-b] :as sensor}]
  (joint-state-of sensor (engine/body-states [rb-a rb-b]) 0 1))

(defn bodies-of
  "The engine bodies of `sensors`, each once (by identity), in the order
  the sensors first name them, after those of `bodies`."
  ([sensors] (bodies-of [] sensors))
  ([bodies sensors]
   (let [seen (java.util.IdentityHashMap.)]
     (doseq [rb bodies] (.put seen rb true))
     (reduce (fn [acc rb] (if (.containsKey seen rb) acc (do (.put seen rb true) (conj acc rb))))
             (vec bodies) (mapcat (juxt :rb-a :rb-b) sensors)))))

(defn indexed
  "`sensors`, each with :ia and :ib, the places of its two bodies in
  `bodies` (which holds them all: see `bodies-of`)."
  [sensors bodies]
  (let [at (java.util.IdentityHashMap.)]
    (doseq [[i rb] (map-indexed vector bodies)] (.put at rb i))
    (mapv (fn [{:keys [rb-a rb-b] :as s}] (assoc s :ia (.get at rb-a) :ib (.get at rb-b))) sensors)))

(defn read-joints
  "The state of the joint each of `sensors` reads, by joint name: now,
  or from `states` (cortex.engine/body-states of the bodies the sensors
  are `indexed` by), each body read once."
  ([sensors]
   (let [bodies (bodies-of sensors)]
     (read-joints (indexed sensors bodies) (engine/body-states bodies))))
  ([indexed-sensors states]
   (persistent! (reduce (fn [m s] (assoc! m (:name s) (joint-state-of s states (:ia s) (:ib s))))
                        (transient {}) indexed-sensors))))

(defn ^:api proprioception
  "Every joint of `creature` (built by cortex.body/body!), by the name
  of its joint empty: its state now (see the namespace doc). Radians
  and radians per second."
  [^Node creature]
  (read-joints (sensors creature)))
