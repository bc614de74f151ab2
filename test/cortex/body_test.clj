;; Generated from org/body.org by lein tangle: edit the chapter, not this file.
(ns cortex.body-test
  (:require [clojure.java.io :as io]
            [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints HingeJoint PhysicsJoint SixDofJoint ConeJoint)
           (com.jme3.math FastMath Matrix3f Quaternion Vector3f)
           (com.jme3.scene Geometry Node VertexBuffer$Type)
           (com.jme3.scene.shape Box Sphere)))

(set! *warn-on-reflection* true)

(defn- segment
  [name ^Vector3f position & {:keys [mass half] :or {half [1 0.25 0.25]}}]
  (let [[x y z] half
        geom (Geometry. name (Box. (float x) (float y) (float z)))
        object (doto (Node. name) (.attachChild geom) (.setLocalTranslation position))]
    (when mass (.setUserData object "mass" mass))
    object))

(defn- marker
  [name ^Vector3f position text & {:keys [rotation]}]
  (cond-> (doto (Node. name) (.setLocalTranslation position))
    text (doto (.setUserData "joint" text))
    rotation (doto (.setLocalRotation ^Quaternion rotation))))

(defn- creature
  [name segments markers]
  (util/nodify name (concat segments [(util/nodify "joints" markers)])))

(defn- code-worm
  "Two 2-unit segments along x with a 0.04 gap, joined at the origin."
  ([text] (code-worm text Vector3f/ZERO))
  ([text ^Vector3f offset]
   (creature "worm"
             [(segment "tail" (.add offset (Vector3f. -1.02 0 0)) :mass (float 1))
              (segment "head" (.add offset (Vector3f. 1.02 0 0)) :mass (float 2))]
             [(marker "neck" offset text)])))

(defn- names [spatials] (map #(.getName %) spatials))

(defn- y-turn [angle] (doto (Quaternion.) (.fromAngleAxis (float angle) Vector3f/UNIT_Y)))

(deftest segments-become-rigid-bodies
  (let [c (doto (creature "c" [(segment "a" (Vector3f. 0 0 0) :mass (float 2.5))
                               (segment "b" (Vector3f. 3 0 0))
                               (segment "ground" (Vector3f. 6 0 0) :mass 0)]
                          [])
            (body/physical!))
        mass-of #(.getMass ^RigidBodyControl (.getControl ^Geometry % RigidBodyControl))]
    (is (= {"a" 2.5 "b" 1.0 "ground" 0.0}
           (into {} (for [g (body/segments c)] [(.getName g) (double (mass-of g))]))))
    (testing "calling it again adds no second body"
      (body/physical! c)
      (is (every? #(= 1 (.getNumControls ^Geometry %)) (body/segments c))))))

(deftest big-hulls-are-simplified
  (let [points (body/mesh-points (Sphere. 32 32 1) (Vector3f. 1 1 1))
        hull (body/simplify-hull points body/max-hull-points)]
    (is (> (count points) 900))
    (is (<= (count hull) body/max-hull-points))
    (testing "every point kept is a vertex of the mesh"
      (is (every? (set points) hull)))
    (testing "the simplified hull still reaches out in every direction"
      (doseq [d (body/sphere-directions 37)]
        (is (> (apply max (map #(.dot ^Vector3f d ^Vector3f %) hull)) 0.93))))
    (testing "small hulls are kept whole"
      (is (= 8 (count (body/simplify-hull (body/mesh-points (Box. 1 1 1) (Vector3f. 1 1 1)) 100)))))))

(deftest a-segment-needs-a-solid-mesh
  (let [flat (Geometry. "flat" (doto (com.jme3.scene.Mesh.)
                                 (.setBuffer VertexBuffer$Type/Position 3
                                             (float-array [0 0 0 1 0 0 0 1 0]))
                                 (.updateBound)))
        empty (Geometry. "empty" (com.jme3.scene.Mesh.))]
    (doseq [[g n] [[flat 3] [empty 0]]]
      (is (re-find (re-pattern (str "segment \"" (.getName g) "\" has " n " distinct vertices"))
                   (try (body/physical! (util/nodify [g])) ""
                        (catch clojure.lang.ExceptionInfo e (ex-message e))))))))

(defn- off-centre-box
  "A 2 x 1 x 0.5 box of mass 3 whose origin is on the middle of its -x
  face (its mesh shifted by +1 in x), turned 0.3 about z, at `at`."
  [^Vector3f at]
  (let [mesh (doto (Box. (Vector3f. 0 -0.5 -0.25) (Vector3f. 2 0.5 0.25)))
        geom (Geometry. "lopsided" mesh)]
    (doto (Node. "lopsided") (.attachChild geom) (.setUserData "mass" (float 3))
      (.setLocalTranslation at)
      (.setLocalRotation (doto (Quaternion.) (.fromAngleAxis 0.3 Vector3f/UNIT_Z))))))

(deftest true-mass-properties
  (let [c (body/physical! (util/nodify "c" [(off-centre-box (Vector3f. 1 2 3))]))
        g ^Geometry (first (body/segments c))
        control ^RigidBodyControl (.getControl g RigidBodyControl)
        inv (engine/inverse-inertia (engine/rigid-body control))
        centre-in-world (.localToWorld g (Vector3f. 1 0 0) nil)]
    (testing "the body sits at the centre of the mesh, the segment stays at its origin"
      (is (< (.distance (.getPhysicsLocation control) centre-in-world) 1e-5))
      (is (< (.distance (first (body/segment-pose g)) (Vector3f. 1 2 3)) 1e-5)))
    (testing "the principal moments of the box, m (b^2 + c^2) / 12 ..."
      (is (= [0.3125 1.0625 1.25]
             (sort (map #(/ (Math/round (/ 1e4 (double %))) 1e4) inv)))))
    (testing "spun with nothing else acting, it turns about the centre of its mesh"
      (.setAngularVelocity control (Vector3f. 0 2 0))
      (let [w (world/world (util/nodify [c]) {} #(world/set-gravity % Vector3f/ZERO) world/no-op)]
        (world/run-world! w 60)
        ;; jME places spatials before it steps the physics: bring the
        ;; Geometry up to the last step
        (.update control (float 0))
        (.updateGeometricState c)
        (is (< (.distance (.localToWorld g (Vector3f. 1 0 0) nil) centre-in-world) 1e-3))
        (is (> (.distance (.getWorldTranslation g) (Vector3f. 1 2 3)) 0.5)
            "while its origin swings round it")
        (is (< (.distance (.getWorldTranslation g) (first (body/segment-pose g))) 1e-5)
            "and the Geometry is where segment-pose says")))
    (testing "the seed's approximation, when asked for"
      (let [c (body/physical! (util/nodify "c" [(off-centre-box (Vector3f. 1 2 3))]) {:mass-properties :box})
            control ^RigidBodyControl (.getControl ^Geometry (first (body/segments c)) RigidBodyControl)]
        (is (< (.distance (.getPhysicsLocation control) (Vector3f. 1 2 3)) 1e-6))))))

(deftest friction-and-restitution-from-the-designer
  (let [c (doto (creature "c" [(doto (segment "grippy" Vector3f/ZERO)
                                 (.setUserData "friction" (float 1.2))
                                 (.setUserData "restitution" (float 0.3)))
                               (segment "plain" (Vector3f. 3 0 0))] [])
            (body/physical!))
        [g p] (map #(.getControl ^Geometry % RigidBodyControl) (body/segments c))]
    (is (= [(float 1.2) (float 0.3)] [(.getFriction ^RigidBodyControl g) (.getRestitution ^RigidBodyControl g)]))
    (is (= [(float 0.5) (float 0)] [(.getFriction ^RigidBodyControl p) (.getRestitution ^RigidBodyControl p)])))
  (is (re-find #"object \"slick\": friction must be a non-negative number, not -1"
               (try (body/physical! (creature "c" [(doto (segment "slick" Vector3f/ZERO)
                                                     (.setUserData "friction" -1))] []))
                    "" (catch clojure.lang.ExceptionInfo e (ex-message e))))))

(deftest hull-points-carry-world-scale
  (let [points (body/mesh-points (Box. 1 1 1) (Vector3f. 2 3 4))
        extent (fn [axis] (set (map #(Math/abs (double (.get ^Vector3f % (int axis)))) points)))]
    (is (= [#{2.0} #{3.0} #{4.0}] (map extent [0 1 2])))))

(deftest finding-joint-targets
  (let [c (doto (code-worm "{:type :point}") (body/physical!))
        joint (first (body/joints c))]
    (is (= ["neck"] (names (body/joints c))))
    (is (= ["tail" "head"] (names (body/joint-targets c joint))))
    (testing "a joint turned half way round sees the segments the other way"
      (.setLocalRotation joint (y-turn FastMath/PI))
      (is (= ["head" "tail"] (names (body/joint-targets c joint)))))
    (testing "a creature without a joints node has no joints"
      (is (empty? (body/joints (util/nodify [(segment "x" Vector3f/ZERO)])))))))

(deftest targets-under-turned-scaled-parents
  (let [;; the segments hang under a parent turned a quarter round Y and
        ;; scaled by 2: in the world they line up along z, 4 units long
        holder (doto (Node. "holder")
                 (.setLocalRotation (y-turn FastMath/HALF_PI))
                 (.setLocalScale 2.0)
                 (.setLocalTranslation 5 0 0))
        _ (doseq [s [(segment "near" (Vector3f. -1.02 0 0)) (segment "far" (Vector3f. 1.02 0 0))
                     (segment "other" (Vector3f. 5 0 0))]]
            (.attachChild holder s))
        c (doto (creature "turned" [holder] [(marker "j" (Vector3f. 5 0 0) "{:type :point}")])
            (body/physical!))
        [a b] (body/joint-targets c (first (body/joints c)))]
    (is (= #{"near" "far"} (set (names [a b]))))
    (testing "ordered by world position: Blender's (1,1,1) weighs jME z by -1"
      (is (> (.z (.getWorldTranslation a)) (.z (.getWorldTranslation b)))))))

(deftest every-joint-of-a-long-chain-finds-its-neighbours
  ;; forty segments in a row, 0.04 apart, lying on a huge slab (kept out
  ;; of the index's grid because of its size) that every joint is near
  (let [n 40
        links (for [i (range n)] (segment (str "link-" i) (Vector3f. (* i 2.04) 0.3 0)))
        slab (segment "slab" (Vector3f. 40 -5.03 0) :half [200 5 200])
        markers (for [i (range (dec n))]
                  (marker (str "j" i) (Vector3f. (+ 1.02 (* i 2.04)) 0.3 0) "{:type :point}"))
        c (doto (creature "chain" (cons slab links) markers) (body/physical!))
        index (body/segment-index c)]
    (is (= 1 (count (:big index))))
    (doseq [[i j] (map-indexed vector (body/joints c))]
      (is (= [(str "link-" i) (str "link-" (inc i))] (names (body/targets-near index j))))
      (is (= (names (body/joint-targets c j)) (names (body/targets-near index j)))))))

(deftest a-joint-needs-two-segments
  (let [c (doto (creature "lonely" [(segment "only" (Vector3f. -1.02 0 0))]
                          [(marker "j" Vector3f/ZERO "{:type :point}")])
            (body/physical!))
        e (try (body/joints! c) nil (catch clojure.lang.ExceptionInfo e e))]
    (is (some? e))
    (is (re-find #"joint \"j\"" (ex-message e)))
    (is (re-find #"creature \"lonely\"" (ex-message e)))
    (is (re-find #"found 1 segment" (ex-message e)))))

(deftest joint-descriptions-are-data
  (is (= {:type :hinge :limit [0 (/ Math/PI 2)]}
         (body/read-joint "{:type :hinge :limit [0 (/ Math/PI 2)]}")))
  (is (= (Vector3f. 0 1 0) (:axis (body/read-joint "{:type :hinge :axis (Vector3f. 0 1 0)}"))))
  (is (= [6 -1 (* 2 Math/E)] (:v (body/read-joint "{:type :x :v [(+ 1 2 3) (- 1) (* 2 Math/E)]}")))))

(defn- message-of [f] (try (f) nil (catch clojure.lang.ExceptionInfo e (ex-message e))))

(deftest bad-descriptions-are-named-errors
  (doseq [[text pattern]
          [["#=(java.lang.System/exit 1)" #"cannot read"]
           ["{:type :point :x (System/exit 1)}" #"not an allowed operation.*System/exit"]
           ["{:type :point :x foo}" #"unknown symbol: foo"]
           ["{:type :point :x \"text\"}" #"not allowed"]
           ["{:type :point" #"cannot read"]
           ["[:point]" #"map with a :type"]
           ["{:type :hinge :limit [0 (/ 1 0)]}" #"(?i)divide by zero"]
           ["{:type :hinge :axis (Vector3f. 1 2)}" #"three numbers"]
           ["#inst \"2020\"" #"not allowed in a joint description"]
           ["#object[java.io.File 0 \"/\"]" #"cannot read"]]]
    (let [m (message-of #(body/read-joint text))]
      (is (and m (re-find pattern m)) (str text " -> " m)))))

(defn- connect-message
  [text]
  (message-of #(body/body! (code-worm text))))

(deftest bad-joints-name-the-joint
  (testing "unknown types list the known ones"
    (let [m (connect-message "{:type :rubber}")]
      (is (re-find #"joint \"neck\": unknown joint type :rubber; known types: :cone, :hinge, :point, :spring" m))))
  (testing "a hinge needs limits"
    (is (re-find #"joint \"neck\": hinge needs :limit" (connect-message "{:type :hinge}"))))
  (testing "a cone needs its three angles"
    (is (re-find #"joint \"neck\": cone joint needs a finite number for :twist"
                 (connect-message "{:type :cone :limit-xz 1 :limit-xy 1}"))))
  (testing "a spring needs its stiffness, and no negative damping"
    (is (re-find #"joint \"neck\": spring joint needs a number >= 0 for :stiffness, not nil"
                 (connect-message "{:type :spring :damping 2}")))
    (is (re-find #"joint \"neck\": spring joint needs a number >= 0 for :damping, not -2"
                 (connect-message "{:type :spring :stiffness 10 :damping -2}")))
    (is (re-find #"joint \"neck\": spring joint: unknown key :stifness; a spring joint takes :damping, :kd"
                 (connect-message "{:type :spring :stifness 10}"))))
  (testing "a joint empty with no description"
    (is (re-find #"joint \"neck\": it has no joint property" (connect-message nil))))
  (testing "a mass that is not a number names the object"
    (let [c (creature "c" [(segment "heavy" Vector3f/ZERO :mass "lots")] [])]
      (is (re-find #"object \"heavy\": mass must be a non-negative number, not \"lots\""
                   (message-of #(body/physical! c)))))))

(deftest descriptions-never-run-code
  (let [f (io/file (System/getProperty "java.io.tmpdir") (str "cortex-pwned-" (System/nanoTime)))
        path (.getPath f)]
    (doseq [text [(str "#=(clojure.core/spit \"" path "\" \"x\")")
                  (str "{:type :point :x (spit \"" path "\" \"x\")}")
                  (str "{:type :point :x (clojure.core/spit \"" path "\" \"x\")}")
                  (str "{:type (do (spit \"" path "\" \"x\") :point)}")]]
      (is (some? (connect-message text)))
      (is (not (.exists f)) text))))

(def ^:private earth (Vector3f. 0 -9.81 0))

(defn- floor [] (util/box 20 1 20 :position (Vector3f. 0 -1 0) :mass 0 :name "floor"))

(defn- all-joints [creature]
  (distinct (mapcat #(engine/joints (.getControl ^Geometry % RigidBodyControl))
                    (body/segments creature))))

(defn- simulate
  "Run `creature` on a floor for `frames`; return the largest joint gap
  seen and the creature."
  [creature frames & {:keys [setup] :or {setup #(world/set-gravity % earth)}}]
  (let [worst (atom 0.0)
        w (world/world (util/nodify [creature (floor)]) {} setup
                       (fn [_ _] (doseq [j (all-joints creature)]
                                   (swap! worst max (body/joint-gap j)))))]
    (world/run-world! w frames)
    @worst))

(deftest the-code-worm-falls-and-holds-together
  (let [c (doto (code-worm "{:type :hinge :limit [-0.7 0.7] :axis (Vector3f. 0 1 0)}"
                           (Vector3f. 0 3 0))
            (body/body!))
        gap (simulate c 300)
        [tail head] (body/segments c)]
    (is (= 1 (count (all-joints c))))
    (is (instance? HingeJoint (first (all-joints c))))
    (testing "the joint's two ends stay within 1% of a segment's length (2) of each other"
      (is (< gap 0.02)))
    (testing "it landed: both segments rest on the floor"
      (doseq [s [tail head]]
        (is (< (Math/abs (- (.y (.getWorldTranslation s)) 0.25)) 0.05))))))

(deftest hinges-keep-their-limits
  ;; a cantilever: a static post, and a beam hinged to it that gravity
  ;; pulls down; the hinge lets it droop by at most 0.3 radians
  (let [c (creature "cantilever"
                    [(segment "post" (Vector3f. -1.02 2 0) :mass 0)
                     (segment "beam" (Vector3f. 1.02 2 0) :mass (float 5))]
                    [(marker "elbow" (Vector3f. 0 2 0)
                             "{:type :hinge :limit [-0.3 0.3] :axis (Vector3f. 0 1 0)}")])
        _ (body/body! c)
        angles (atom [])
        w (world/world (util/nodify [c]) {} #(world/set-gravity % earth)
                       (fn [_ _]
                         (let [beam (second (body/segments c))]
                           (swap! angles conj (.toAngleAxis (.getWorldRotation ^Geometry beam)
                                                            (Vector3f.))))))]
    (world/run-world! w 300)
    (testing "the beam swung down to its limit"
      (is (> (apply max (map #(Math/abs (double %)) @angles)) 0.25)))
    (testing "and never far past it"
      (is (every? #(<= (Math/abs (double %)) 0.33) @angles)))))

(defn- spring-droop
  "How far (radians) the beam of a spring-jointed cantilever of
  `stiffness` hangs after 5 s, and its largest speed in the last second;
  the beam of 5 kg and the spring's damping 20 unless given."
  [stiffness & {:keys [mass damping] :or {mass 5 damping 20}}]
  (let [c (creature "sprung"
                    [(segment "post" (Vector3f. -1.02 2 0) :mass 0)
                     (segment "beam" (Vector3f. 1.02 2 0) :mass (float mass))]
                    [(marker "elbow" (Vector3f. 0 2 0)
                             (str "{:type :spring :stiffness " stiffness " :damping " damping "}"))])
        ;; never asleep: cortex's thresholds would stop the beam wherever
        ;; it swings slowly two seconds in, short of where it hangs
        _ (body/body! c {:sleeping-thresholds [0 0]})
        beam (second (body/segments c))
        fastest (atom 0.0) frame (atom 0)
        w (world/world (util/nodify [c]) {} #(world/set-gravity % earth)
                       (fn [_ _]
                         (when (> (swap! frame inc) 240)
                           (swap! fastest max (.length (.getLinearVelocity
                                                        ^RigidBodyControl
                                                        (.getControl ^Geometry beam RigidBodyControl)))))))]
    (world/run-world! w 300)
    [(.toAngleAxis (.getWorldRotation ^Geometry beam) (Vector3f.)) @fastest]))

(defn- hanging-angle
  "The angle a at which a beam of `m` kg whose centre is `l` from a
  spring of stiffness `k` hangs: k a = m g l cos a."
  [k m l]
  (nth (iterate #(/ (* m 9.81 l (Math/cos %)) k) 0.0) 200))

(deftest spring-joints
  (doseq [k [1000 100]
          :let [[droop speed] (spring-droop k)
                want (hanging-angle k 5.0 1.02)]]
    (testing (str "a spring of " k " N m/rad holds the beam where k a = m g l cos a")
      (println (format "%s: beam on a spring of %d N m/rad hangs at %.4f rad, k a = m g l cos a at %.4f"
                       engine/name k droop want))
      (is (< (Math/abs (- droop want)) (* 0.01 want)) (str "droop " droop ", wanted " want))
      (is (< speed 0.01) (str "still moving at " speed " m/s"))))
  (testing "a stiff spring on a light beam, undamped, gains no energy on jBullet"
    ;; 1000 N m/rad on a beam of 10 g, whose moment about its joint is
    ;; 0.014 kg m^2: k dt^2 is 20 times that
    (let [[droop speed] (spring-droop 1000 :mass 0.01 :damping 0)]
      (println (format "%s: a 10 g beam on an undamped spring of 1000 N m/rad: %.4f rad, %.3f m/s"
                       engine/name droop speed))
      (when (= :jbullet engine/name)
        (is (< droop 0.001) (str "droop " droop))
        (is (< speed 0.01) (str "moving at " speed " m/s"))))))

(deftest other-joint-kinds-hold
  (doseq [[text kind] [["{:type :point}" engine/six-dof-class]
                       ["{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.2}" engine/six-dof-class]]]
    (let [c (doto (code-worm text (Vector3f. 0 3 0)) (body/body!))
          gap (simulate c 300)]
      (is (instance? kind (first (all-joints c))))
      (is (< gap 0.02) text))))

(defn- final-state [creature frames]
  (simulate creature frames)
  (vec (for [g (body/segments creature)
             :let [t (.getWorldTranslation g) r (.getWorldRotation g)]]
         [(.x t) (.y t) (.z t) (.getX r) (.getY r) (.getZ r) (.getW r)])))

(deftest jointed-runs-repeat-to-the-bit
  (let [make #(doto (code-worm "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.2}"
                               (Vector3f. 0.1 3 -0.2))
                (.setLocalRotation (doto (Quaternion.) (.fromAngles 0.3 0.2 0.1)))
                (body/body!))]
    (is (= (final-state (make) 240) (final-state (make) 240)))))

(deftest hinges-read-zero-where-built
  (let [tipped (doto (Quaternion.) (.fromAngleAxis (float 0.2) Vector3f/UNIT_Z))
        beam-node (doto ^Node (segment "beam" (Vector3f. 1.02 2.2 0) :mass (float 5) :half [1 0.25 0.2])
                    (.setLocalRotation tipped))
        c (creature "tipped-cantilever"
                    [(segment "post" (Vector3f. -1.02 2 0) :mass 0) beam-node]
                    [(marker "elbow" (Vector3f. 0 2 0)
                             "{:type :hinge :limit [-0.3 0.3] :axis (Vector3f. 0 1 0)}")])
        _ (body/body! c)
        beam (second (body/segments c))
        built (.clone (.getWorldRotation ^Geometry beam))
        turned #(.toAngleAxis (.mult (.inverse built) (.getWorldRotation ^Geometry beam)) (Vector3f.))]
    (when (= :jbullet engine/name)
      ;; native Bullet keeps its own zero and gives limits about it
      (is (< (Math/abs (.getHingeAngle ^HingeJoint (body/joint c "elbow"))) 1e-4)
          "jBullet reads the hinge's angle as 0 where it was built"))
    (simulate c 300)
    (is (< (Math/abs (- (double (turned)) 0.3)) 0.03)
        (str "the beam droops by its limit, 0.3, from where it was built, not " (turned)))))

(defn- hang
  "How far (radians below level) an arm hanging from a fixed post by
  the cone `text`, its empty turned by `rotation`, has swung after 4 s."
  [text rotation]
  (let [c (body/body! (creature "pendulum"
                                [(segment "post" (Vector3f. -1.02 5 0) :mass (float 0))
                                 (segment "arm" (Vector3f. 1.02 5 0) :mass (float 1))]
                                [(marker "joint" (Vector3f. 0 5 0) text :rotation rotation)]))
        _ (simulate c 240)
        arm (first (filter #(= "arm" (.getName ^Geometry %)) (body/segments c)))
        x (.mult (.getWorldRotation ^Geometry arm) Vector3f/UNIT_X)]
    (Math/asin (- (.y x)))))

(deftest cone-limits-are-on-their-named-axes
  (let [quarter-about-x (doto (Quaternion.) (.fromAngleAxis (/ FastMath/PI 2) Vector3f/UNIT_X))]
    ;; the last: both swings wide, so that on jBullet the twist goes
    ;; in the middle
    (doseq [[xz xy] [[0.9 0.3] [0.3 0.9] [1.3 1.25]]
            :let [text (format "{:type :cone :limit-xz %s :limit-xy %s :twist 0.1}" xz xy)]]
      (testing text
        (is (< (Math/abs (- (hang text Quaternion/IDENTITY) (double xz))) 0.05) "swung about Blender's Y")
        (is (< (Math/abs (- (hang text quarter-about-x) (double xy))) 0.05) "swung about Blender's Z")))))

(deftest wide-cones-keep-their-twist-in-the-middle
  (let [[turn limits] (#'cortex.joint/cone-limits 1.48 1.48 0.0)
        x (.mult ^Matrix3f turn Vector3f/UNIT_Y)]
    (if (< (double engine/six-dof-safe-middle) 1.48)
      (do (is (= [1.48 1.0E-4 1.48] limits))
          (is (< (.distance x Vector3f/UNIT_X) 1e-6) "the engine's middle axis is the twist's"))
      (is (= [1.0E-4 1.48 1.48] limits))))
  (testing "a cone whose narrower swing is safe in the middle keeps it there"
    (is (= [0.3 0.6 0.6] (second (#'cortex.joint/cone-limits 0.6 0.6 0.3))))))
