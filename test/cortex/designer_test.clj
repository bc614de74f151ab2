;; Generated from org/body.org by lein tangle: edit the chapter, not this file.
(ns cortex.designer-test
  (:require [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.blender-test :refer [read-json]]
            [cortex.body :as body]
            [cortex.drops :as drops]
            [cortex.engine :as engine]
            [cortex.nearest :as nearest]
            [cortex.segment :as segment]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints PhysicsJoint)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Node Spatial)))

(def ^:private dir "test/fixtures/designer/")

(def ^:private expected
  (delay (get (read-json (slurp (str dir "expected.json"))) "files")))

(defn- load-fixture ^Node [name] (util/load-blender-model (str dir name)))

(defn- build-error
  "The message of the ex-info body! throws for fixture `name`, or nil."
  [name & [opts]]
  (try (body/body! (load-fixture name) (or opts {})) nil
       (catch clojure.lang.ExceptionInfo e (ex-message e))))

(defn- close? [a b] (< (Math/abs (- (double a) (double b))) 1e-4))

(deftest the-quadruped-builds-and-reports-what-blender-holds
  (let [c (body/body! (load-fixture "quadruped.blend"))
        {:keys [segments joints warnings tolerance]} (body/report c)
        want (get @expected "quadruped.blend")
        want-segments (into {} (map (juxt #(get % "name") identity)) (get want "segments"))]
    (is (= [] warnings))
    (is (close? 0.05 tolerance) "a tenth of the median segment size, 0.5")
    (is (= (set (keys want-segments)) (set (map :name segments))))
    (doseq [{:keys [name mass shape volume]} segments
            :let [w (want-segments name)]]
      (is (close? (get w "mass") mass) name)
      ;; its segments are cubes, scaled: each is a box (see the shapes
      ;; chapter), whose volume is the mesh's
      (is (= :box shape) name)
      (is (close? (get w "volume") volume) name))
    (let [seed (body/report (body/body! (load-fixture "quadruped.blend") {:shapes :hull}))]
      (doseq [{:keys [name hull-points hull-volume shape]} (:segments seed)
              :let [w (want-segments name)]]
        (is (= :hull shape) name)
        (is (= (get w "vertices") hull-points) name)
        (is (close? (get w "volume") hull-volume) name)))
    (is (= (count (get want "joints")) (count joints)))
    (doseq [w (get want "joints")
            :let [j (first (filter #(= (get w "name") (:name %)) joints))]]
      (is (some? j) (get w "name"))
      (is (= (keyword (get w "type")) (:type j)))
      (is (= (get w "segments") (:segments j)) (str (get w "name") " joins its segments in order"))
      (is (every? true? (map close? (get w "position") (:pivot j))) (:name j))
      (doseq [{s "segment" d "cube"} (take 2 (get w "nearest"))]
        (is (< (Math/abs (- (double d) (double (get-in j [:distances s])))) 1e-4)
            (str (:name j) " to " s))))
    (testing "segments and joints are found by their Blender names"
      (is (= "torso" (body/segment-name (body/segment c "torso"))))
      (is (instance? PhysicsJoint (body/joint c "knee-front-r")))
      (is (re-find #"no joint \"knee\"; its joints are .*knee-front-r"
                   (try (body/joint c "knee") "" (catch clojure.lang.ExceptionInfo e (ex-message e))))))))

(deftest joints-out-of-place-are-refused-with-names-and-distances
  (testing "0.3 off its gap, 0.2 from both segments"
    (let [m (build-error "misplaced-joint.blend")]
      (is (re-find #"misplaced-joint.blend" m))
      (is (re-find #"joint \"knee-front-r\" is 0\.200 from lower-leg-front-r and 0\.200 from upper-leg-front-r, more than half the thinnest side of lower-leg-front-r \(0\.100\) and of upper-leg-front-r \(0\.100\)" m))))
  (testing "four units from everything: five segments tie"
    (is (re-find #"joint \"knee-back-l\" is about equally near 5 segments .*lower-leg-back-l 4\.000"
                 (build-error "far-joint.blend"))))
  (testing "inside the torso"
    (is (re-find #"joint \"knee-front-l\" is about equally near .*torso 0\.250.*upper-leg-back-l 0\.600"
                 (build-error "inside-joint.blend"))))
  (testing "equally near three"
    (is (re-find #"joint \"tail-joint-2\" is about equally near 3 segments \(tail-1 0\.210, tail-2 0\.220, torso 0\.240"
                 (build-error "ambiguous-joint.blend"))))
  (testing "two joints for one pair"
    (is (re-find #"joints \"knee-front-r\" and \"knee-front-r-2\" both join lower-leg-front-r and upper-leg-front-r"
                 (build-error "duplicate-joint.blend"))))
  (testing "every doubt of a creature is in one error"
    (is (re-find #"1 doubt about its joints" (build-error "misplaced-joint.blend")))))

(defn- doubts-of
  "[kind joint] of every doubt that stops fixture `name` from building
  (with body!'s `opts`)."
  [name & [opts]]
  (try (body/body! (load-fixture name) (or opts {})) []
       (catch clojure.lang.ExceptionInfo e
         (mapv (juxt :kind #(or (:joint %) (:joints %))) (:doubts (ex-data e))))))

(deftest each-mistake-keeps-its-joint-and-kind
  (is (= [[:far-joint "knee-front-r"]] (doubts-of "misplaced-joint.blend")))
  (is (= [[:ambiguous-joint "knee-back-l"] [:far-joint "knee-back-l"]]
         (doubts-of "far-joint.blend")))
  (is (= [[:ambiguous-joint "knee-front-l"] [:far-joint "knee-front-l"]
          [:duplicate-joint ["knee-front-l" "hip-back-l"]]]
         (doubts-of "inside-joint.blend")))
  (is (= [[:ambiguous-joint "tail-joint-2"] [:far-joint "tail-joint-2"]]
         (doubts-of "ambiguous-joint.blend")))
  (is (= [[:duplicate-joint ["knee-front-r" "knee-front-r-2"]]] (doubts-of "duplicate-joint.blend")))
  (is (= [[:misnamed-joints nil]] (doubts-of "misnamed-joints.blend"))))

(deftest the-tolerance-is-the-ambiguity-window
  (testing "narrower than the gap between the second and third nearest: the pair is clear"
    (is (= [[:far-joint "tail-joint-2"]] (doubts-of "ambiguous-joint.blend" {:tolerance 0.005}))))
  (testing "as wide as a segment: neighbours become doubtful, and the report says the window"
    (let [{:keys [tolerance warnings]} (body/report (body/body! (load-fixture "quadruped.blend")
                                                                {:tolerance 0.5 :strict? false}))]
      (is (== 0.5 tolerance))
      (is (seq (filter #(= :ambiguous-joint (:kind %)) warnings))))))

(deftest relaxed-builds-keep-the-doubts-as-warnings
  (let [c (body/body! (load-fixture "misplaced-joint.blend") {:strict? false})
        {:keys [joints warnings]} (body/report c)]
    (is (= 13 (count joints)))
    (is (= [[:far-joint "knee-front-r" true]]
           (map (juxt :kind :joint :relaxed?) warnings)))))

(deftest names-and-descriptions-that-nearly-work
  (testing "Joints for joints"
    (is (re-find #"no node named \"joints\", but there is \"Joints\"; rename it to joints"
                 (build-error "misnamed-joints.blend"))))
  (testing "a typo in a key"
    (is (re-find #"joint \"knee-front-r\": hinge joint: unknown key :axs; a hinge joint takes :axis, :kd, :kp, :limit, :strength, :type"
                 (build-error "typo-key.blend"))))
  (testing "degrees for radians"
    (is (re-find #"joint \"knee-front-r\": hinge :limit \[0 90\] is outside \[-pi, pi\]: angles are in radians"
                 (build-error "degree-limit.blend"))))
  (testing "a joint property outside joints is a warning"
    (let [{:keys [warnings joints]} (body/report (body/body! (load-fixture "stray-joint.blend")))]
      (is (= 13 (count joints)))
      (is (= [[:stray-joint "stray"]] (map (juxt :kind :object) warnings)))))
  (testing "segments overlapping at rest, unjoined"
    (let [{:keys [warnings]} (body/report (body/body! (load-fixture "overlap.blend")))]
      (is (= [[:overlap ["rock" "torso"]]] (map (juxt :kind :segments) warnings))))))

(defn- overlaps-of
  "The pairs `cortex.nearest/overlap-warnings` names among boxes given
  as [name [hx hy hz] [x y z] turn-about-y]."
  [boxes]
  (let [geoms (for [[n [hx hy hz] [x y z] turn] boxes]
                (doto ^Geometry (util/box hx hy hz :name n :physical? false
                                          :position (Vector3f. x y z))
                  (.setLocalRotation (.fromAngles (com.jme3.math.Quaternion.) 0 (float turn) 0))
                  (.updateGeometricState)))]
    (mapv :segments (cortex.nearest/overlap-warnings (cortex.nearest/index-of geoms) #{}))))

(deftest overlaps-are-judged-by-the-triangles
  (is (= [["a" "b"]] (overlaps-of [["a" [1 1 1] [0 0 0] 0] ["b" [0.2 0.2 0.2] [0.1 0 0] 0]]))
      "one wholly inside the other")
  (is (= [["a" "b"]] (overlaps-of [["a" [1 1 1] [0 0 0] 0] ["b" [1 0.2 0.2] [1.5 0 0] 0]]))
      "crossing")
  (is (= [] (overlaps-of [["a" [1 1 1] [0 0 0] 0] ["b" [1 1 1] [2 0 0] 0]]))
      "face to face")
  ;; two long thin boxes side by side, turned 45 degrees: each lies
  ;; within the other's bounds, their faces 0.2 apart (0.4 between axes)
  (is (= [] (overlaps-of [["a" [2 0.1 0.1] [0 0 0] (/ Math/PI -4)]
                          ["b" [2 0.1 0.1] [0.2828 0 -0.2828] (/ Math/PI -4)]]))
      "turned side by side, apart")
  (is (= [["a" "b"]] (overlaps-of [["a" [2 0.1 0.1] [0 0 0] (/ Math/PI -4)]
                                   ["b" [2 0.1 0.1] [0.1061 0 -0.1061] (/ Math/PI -4)]]))
      "turned side by side, 0.15 between axes: crossing"))

(defn- hand-run
  "Load the hand, turned by `angle`, build it (once `start`, a latch,
  opens: so that parallel builds overlap) and drop it for 2 s; the final
  positions and rotations of its segments."
  [angle ^java.util.concurrent.CountDownLatch start]
  (let [c (doto ^Node (util/load-blender-model "Models/test-creature/hand.blend")
            (.rotate 0.2 (float angle) 0.1))
        _ (.countDown start)
        _ (.await start)
        _ (body/body! c)
        floor (util/box 20 1 20 :position (Vector3f. 0 -3 0) :mass 0)
        w (world/world (util/nodify [c floor]) {} #(world/set-gravity % (Vector3f. 0 -9.81 0))
                       world/no-op)]
    (world/run-world! w 120)
    (vec (for [^Geometry g (body/segments c)
               :let [[p q] (body/segment-pose g)]]
           [(.x ^Vector3f p) (.y ^Vector3f p) (.z ^Vector3f p)
            (.getX ^com.jme3.math.Quaternion q) (.getW ^com.jme3.math.Quaternion q)]))))

(deftest bodies-built-on-many-threads-are-the-same
  (let [angles (map #(* 0.4 %) (range 8))
        alone (mapv #(hand-run % (java.util.concurrent.CountDownLatch. 0)) angles)
        start (java.util.concurrent.CountDownLatch. (count angles))
        together (mapv deref (mapv #(future (hand-run % start)) angles))]
    (is (= alone together))))

(defn- speed ^double [^Geometry g]
  (let [^RigidBodyControl c (.getControl g RigidBodyControl)]
    (.length (.getLinearVelocity c))))

(defn- drop-test
  "Drop `creature` (not yet built) half a unit above a floor at y = 0
  (its lowest point) for `seconds` (10 unless given); return when every
  segment stayed slower than 0.05 m/s for good, how far any segment
  moved in the last 2 s, the largest speed in the last second and the
  largest joint gap."
  [^Node creature & [seconds]]
  (.updateGeometricState creature)
  (let [segs (vec (body/segments creature))
        [lowest] (drops/extent creature)
        _ (.move creature 0 (float (- 0.5 (double lowest))) 0)
        _ (.rotate creature 0.05 0.3 0.02)
        _ (.updateGeometricState creature)
        ;; built where it was put: a RigidBodyControl takes its place
        ;; from its Geometry only when it is attached
        _ (body/body! creature)
        floor (util/box 40 1 40 :position (Vector3f. 0 -1 0) :mass 0 :name "floor")
        joints (map :physics-joint (body/joint-records creature))
        frames (* 60 (long (or seconds 10)))
        frame (atom 0) still-since (atom nil) before-end (atom nil) last-second (atom 0.0)
        gap (atom 0.0) final-gap (atom 0.0)
        w (world/world (util/nodify [creature floor]) {}
                       #(world/set-gravity % (Vector3f. 0 -9.81 0))
                       (fn [_ _]
                         (let [f (swap! frame inc)
                               fastest (apply max (map speed segs))]
                           (swap! gap max (reset! final-gap (apply max 0.0 (map body/joint-gap joints))))
                           (if (< fastest 0.05)
                             (swap! still-since #(or % f))
                             (reset! still-since nil))
                           (when (> f (- frames 60)) (swap! last-second max fastest))
                           (when (= f (- frames 120))
                             (reset! before-end (mapv #(.clone (.getWorldTranslation ^Geometry %)) segs))))))]
    (world/run-world! w frames)
    {:still-at (some-> @still-since (/ 60.0))
     :moved (apply max (map (fn [^Vector3f a ^Geometry g] (.distance a (.getWorldTranslation g)))
                            @before-end segs))
     :fastest-last-second @last-second
     :gap @gap
     :final-gap @final-gap}))

(deftest creatures-come-to-rest
  (doseq [[name creature max-gap] [["quadruped" #(load-fixture "quadruped.blend")
                                    (if (= :native engine/name) 0.08 0.06)]
                                   ["worm" #(util/load-blender-model "Models/test-creature/worm.blend") 0.02]
                                   ["hand" #(util/load-blender-model "Models/test-creature/hand.blend") 0.03]]]
    (let [{:keys [still-at moved fastest-last-second gap]} (drop-test (creature))]
      (is (some? still-at) (str name " never came to rest"))
      (is (< (double (or still-at 99)) 10.0) name)
      (is (< fastest-last-second 0.05) name)
      (is (< moved 0.02) (str name " moved " moved " between 8 s and 10 s"))
      (is (< gap max-gap) (str name "'s joints opened by " gap)))))

(def ^:private strangers "test/fixtures/strangers/")

(def ^:private strangers-expected
  (delay (get (read-json (slurp (str strangers "expected.json"))) "files")))

(defn- stranger ^Node [file] (util/load-blender-model (str strangers file)))

(deftest strangers-creatures-build-as-designed
  (doseq [file ["hand.blend" "hand-b52.blend" "humanoid.blend" "worm-eye.blend"]
          :let [want (@strangers-expected file)
                {:keys [joints warnings eyes]} (body/report (body/body! (stranger file)))]]
    (testing file
      (is (= [] (mapv :kind warnings)))
      (is (= (into {} (for [j (get want "joints")] [(get j "name") (get j "segments")]))
             (into {} (map (juxt :name :segments)) joints)))
      (is (= (into {} (for [e (get want "eyes")] [(get e "name") (get e "segment")]))
             (into {} (map (juxt :name :segment)) eyes))))))

(deftest strangers-creatures-hold-together
  (doseq [file ["hand.blend" "humanoid.blend" "worm-eye.blend"]
          :let [c (stranger file)
                {:keys [gap final-gap]} (drop-test c 3)
                median-size (* 10 (double (:tolerance (body/report c))))]]
    (is (< final-gap (* 0.05 median-size))
        (str file "'s joints are open by " final-gap " after 3 s, against a median segment size of "
             median-size))
    (is (< gap (* 0.1 median-size))
        (str file "'s joints opened by " gap " as it fell, against a median segment size of "
             median-size))))

(def ^:private mjcf-strangers
  (delay (get (read-json (slurp (str strangers "mjcf.json"))) "files")))

(deftest strangers-from-mujocos-walker
  (doseq [file ["walker2d-apart.blend" "walker2d-sloppy.blend"]
          :let [{:keys [joints warnings]} (body/report (body/body! (stranger file)))]]
    (testing file
      (is (= [] (mapv :kind warnings)))
      (is (= (into {} (for [j (get-in @mjcf-strangers [file "joints"])]
                        [(get j "name") (set (get j "segments"))]))
             (into {} (for [j joints] [(:name j) (set (:segments j))]))))))
  (let [e (try (body/body! (stranger "walker2d.blend")) nil
               (catch clojure.lang.ExceptionInfo e e))
        doubts (:doubts (ex-data e))]
    (is (some? e) "walker2d's legs are in one place: its joints are refused")
    (is (= #{"thigh_joint" "leg_joint" "foot_joint" "thigh_left_joint" "leg_left_joint" "foot_left_joint"}
           (set (keep #(when (= :ambiguous-joint (:kind %)) (:joint %)) doubts))))
    (is (re-find #"joints \"leg_joint\", \"foot_joint\", \"leg_left_joint\" and \"foot_left_joint\" all join leg and leg_left; delete one, or move it into the gap it belongs to \(turns about two or three axes at one place are one :cone joint\)"
                 (.getMessage ^Exception e)))
    (is (re-find #"joint \"thigh_joint\" is about equally near 3 segments \((thigh|torso|thigh_left) 0\.028"
                 (.getMessage ^Exception e)))))

(defn- pairs-of
  [joints]
  (into {} (for [j joints] [(get j "name" (:name j)) (set (get j "segments" (:segments j)))])))

(deftest mujocos-humanoid-with-ankles
  (doseq [file ["mujoco-humanoid.blend" "mujoco-humanoid-sloppy.blend"]
          scale (if (= file "mujoco-humanoid.blend") [1.0 0.01 100.0] [1.0])
          :let [c (doto (stranger file) (.setLocalScale (float scale)) (.updateGeometricState))
                {:keys [joints warnings]} (body/report (body/body! c))]]
    (testing (str file " at " scale)
      (is (= [] (mapv :kind warnings)))
      (is (= 12 (count joints)))
      (is (= (pairs-of (get-in @mjcf-strangers [file "joints"])) (pairs-of joints)))))
  (doseq [[what object dy] [["the foot 0.02 lower" "right_foot" -0.02]
                            ["the ankle 0.05 up inside the shin" "right_ankle_y" 0.05]]
          :let [c (stranger "mujoco-humanoid.blend")
                _ (.move (.getChild c ^String object) 0 (float dy) 0)
                e (try (body/body! c) nil (catch clojure.lang.ExceptionInfo e e))]]
    (testing what
      (is (= [[:far-joint "right_ankle_y"]] (mapv (juxt :kind :joint) (:doubts (ex-data e)))))
      (is (= "right_shin" (get-in (ex-data e) [:doubts 0 :inside :inside])))
      (is (re-find #"joint \"right_ankle_y\" lies 0\.0\d+ inside right_shin and 0\.\d+ from right_foot"
                   (str (some-> e .getMessage)))))))

(deftest strangers-from-a-urdf-robot
  (let [file "urdf-two-joint-robot.blend"
        want (get-in (read-json (slurp (str strangers "urdf.json"))) ["files" file "joints"])
        {:keys [joints warnings]} (body/report (body/body! (stranger file)))]
    (is (= [] (mapv :kind warnings)))
    (is (= (pairs-of want) (pairs-of joints))))
  (let [c (stranger "urdf-two-joint-robot.blend")
        _ (.move (.getChild c "joint_1") 0 0.05 0)
        e (try (body/body! c) nil (catch clojure.lang.ExceptionInfo e e))]
    (is (= [[:far-joint "joint_1"]] (mapv (juxt :kind :joint) (:doubts (ex-data e)))))
    (is (re-find #"joint \"joint_1\" is 0\.0250 from link_01_cyl and 0\.0750 from base_link, more than half the thinnest side of base_link \(0\.0250\): it lies outside"
                 (str (some-> e .getMessage))))))

(deftest mujocos-pendulum-keeps-pi-to-six-places
  (let [c (stranger "inverted_pendulum.blend")
        [lowest] (drops/extent c)
        _ (.move c 0 (float (- 0.01 (double lowest))) 0)
        _ (.updateGeometricState c)
        {:keys [joints warnings]} (body/report (body/body! c))
        pole (body/segment c "pole")
        before (.clone (.getWorldRotation pole))
        floor (util/box 40 1 40 :position (Vector3f. 0 -1 0) :mass 0 :name "floor")]
    (is (= [] (mapv :kind warnings)))
    (is (= [#{"cart" "pole"}] (mapv #(set (:segments %)) joints)))
    (world/run-world! (world/world (util/nodify [c floor]) {}
                                   #(world/set-gravity % (Vector3f. 0 -9.81 0)) world/no-op)
                      180)
    (let [turned (* 2.0 (Math/acos (min 1.0 (Math/abs (double (.dot before (.getWorldRotation pole)))))))]
      (is (> turned 0.5) (str "the pole turned " turned " rad in 3 s")))))

(def ^:private powers
  "How each length-like number of a report scales: the power of the scale."
  {:tolerance 1 :hull-volume 3 :volume 3 :centre-of-mass 1 :principal-moments 2 :pivot 1
   :distances 1 :distance 1 :position 1 :near 1 :far 1 :size 1})

(defn- in-units
  "`report` with its creature's name and its warnings' messages left out,
  every length divided by `k` (areas by k squared, volumes by k cubed),
  and principal moments sorted (a segment with two equal moments lists
  them in either order)."
  [report k]
  (letfn [(walk [x power]
            (cond (map? x) (into (sorted-map)
                                 (for [[key v] (-> (dissoc x :creature :message)
                                                   (cond-> (:principal-moments x)
                                                     (update :principal-moments sort)))]
                                   [key (walk v (get powers key power))]))
                  (sequential? x) (mapv #(walk % power) x)
                  (and (number? x) power) (/ (double x) (Math/pow k power))
                  :else x))]
    (walk report nil)))

(def ^:private hull-volume-tolerance
  "A thousandth: jBullet keeps a hull exactly as its points say; native
  Bullet moves its vertices a little (optimizeConvexHull), by a fraction
  that changes with the scale (MuJoCo's humanoid's lwaist: 2e-4 smaller
  at 0.01 than at 1, the hand's index-1 4e-4)."
  1e-3)

(defn- difference
  "Where `a` and `b` first differ, as [path a b], or nil when they are the
  same data, numbers within a ten-thousandth of each other (or of 1e-6),
  hull volumes within `hull-volume-tolerance`."
  ([a b] (difference a b 1e-4 []))
  ([a b tolerance path]
   (cond (map? a) (if (and (map? b) (= (set (keys a)) (set (keys b))))
                    (some #(difference (a %) (b %)
                                       (if (#{:hull-volume :volume} %) hull-volume-tolerance tolerance)
                                       (conj path %))
                          (keys a))
                    [path a b])
         (sequential? a) (if (and (sequential? b) (= (count a) (count b)))
                           (some identity (map #(difference %1 %2 tolerance (conj path %3))
                                               a b (range)))
                           [path a b])
         (and (number? a) (number? b))
         (when (> (Math/abs (- (double a) (double b)))
                  (max 1e-6 (* (double tolerance) (max (Math/abs (double a)) (Math/abs (double b))))))
           [path a b])
         :else (when (not= a b) [path a b]))))

(defn- verdict
  "What body! says of stranger `file` whose thumb joint, if `push`, is
  moved 0.3 to the side at the file's `scale`: [:built report in units]
  or [:refused [kind joint]s]."
  [file scale push]
  (let [c (stranger file)]
    (when push
      (.move ^Spatial (.getChild c "thumb-palm") 0 0 (float (* 0.3 scale))))
    (try [:built (in-units (body/report (body/body! c)) scale)]
         (catch clojure.lang.ExceptionInfo e
           [:refused (mapv (juxt :kind :joint) (:doubts (ex-data e)))]))))

(deftest strangers-creatures-at-any-scale
  (doseq [base ["hand" "humanoid" "worm-eye"]
          :let [at-1 (verdict (str base ".blend") 1.0 false)]]
    (is (= :built (first at-1)) base)
    (doseq [[suffix scale] [["-0.01" 0.01] ["-100" 100.0]]
            :let [file (str base suffix ".blend")]]
      (is (= scale (get-in @strangers-expected [file "scale"])) file)
      (is (nil? (difference at-1 (verdict file scale false))) file)))
  (doseq [[file scale] [["hand.blend" 1.0] ["hand-0.01.blend" 0.01] ["hand-100.blend" 100.0]]]
    (is (= [:refused [[:far-joint "thumb-palm"]]] (verdict file scale true)) file)))

(def ^:private flat-dir "test/fixtures/flat-strangers/")

(def ^:private flat-manifest
  (delay (into {} (for [f (get (read-json (slurp (str flat-dir "manifest.json"))) "files")]
                    [(get f "file") f]))))

(defn- flat-stranger ^Node [file] (util/load-blender-model (str flat-dir file)))

(deftest strangers-creatures-with-flat-parts-build
  (doseq [file ["fish.blend" "sloppy-fish.blend" "glider.blend" "leaf-walker.blend"
                "leaf-walker-on-plate.blend" "flat-hexagon-paddle.blend"]
          :let [want (@flat-manifest file)
                c (flat-stranger file)
                flat (set (for [s (get want "segments") :when (get s "flat")] (get s "name")))
                moving (set (for [s (get want "segments") :when (pos? (get s "mass_kg"))] (get s "name")))
                geoms (into {} (map (juxt segment/segment-name identity)) (segment/segments c))
                {:keys [joints segments warnings]} (body/report (body/body! c))]]
    (testing file
      (is (= (into {} (for [j (get want "joints")] [(get j "name") (set (get j "meant_to_join"))]))
             (into {} (map (juxt :name (comp set :segments))) joints)))
      (is (= (set (keys geoms)) (set (map :name segments))) "every part, flat or closed, is a segment")
      (is (seq flat))
      (is (= (sort (filter moving flat))
             (sort (keep #(when (= :mass-properties (:kind %)) (:segment %)) warnings)))
          "each moving flat part is massed by Bullet's guess, and warned of")
      (is (not-any? #(nearest/sheet? (geoms %)) (remove flat (keys geoms))) "no closed part is a sheet")
      (when (#{"sloppy-fish.blend" "leaf-walker.blend" "flat-hexagon-paddle.blend"} file)
        (is (every? #(nearest/sheet? (geoms %)) flat) "a plane in its own axes is a sheet")))))

(defn- moved-refusal
  "The error `body!` gives flat stranger `file` with its joint `joint`
  moved by [x y z] (jME's axes), or nil when it builds."
  [file joint [x y z]]
  (let [c (flat-stranger file)]
    (.move ^Spatial (first (filter #(= joint (.getName ^Spatial %)) (util/node-seq c)))
           (float x) (float y) (float z))
    (try (body/body! c) nil (catch clojure.lang.ExceptionInfo e (ex-message e)))))

(deftest a-far-joint-at-a-sheet-is-named
  (is (re-find #"joint \"ankle-front-l\" is 0\.0500 from foot-front-l and 0\.0500 from leg-front-l, more than half the thinnest side of leg-front-l \(0\.0400\) and a twentieth of the width of foot-front-l, a sheet \(0\.0100\)"
               (str (moved-refusal "leaf-walker.blend" "ankle-front-l" [0 -0.05 0]))))
  (is (re-find #"joint \"shoulder-left\" lies 0\.00\d+ inside body and 0\.05\d+ from fin-left, .* a twentieth of the width of fin-left, a sheet \(0\.0100\) together"
               (str (moved-refusal "sloppy-fish.blend" "shoulder-left" [0 0.05 0]))))
  (is (nil? (moved-refusal "leaf-walker.blend" "ankle-front-l" [0 -0.005 0]))
      "5 mm below its foot, the ankle is at it")
  (is (re-find #"joint \"blade-joint\": found 1 segment\(s\) near it \(hub\), a joint needs two; blade is a mesh with no faces"
               (str (try (body/body! (flat-stranger "line-blade.blend")) nil
                         (catch clojure.lang.ExceptionInfo e (ex-message e)))))))

(defn- mutate
  "`bs` damaged by seeded random `rng`: flipped bits, a run of random
  bytes, or cut short."
  ^bytes [^bytes bs ^java.util.Random rng]
  (let [out (java.util.Arrays/copyOf bs (alength bs))
        n (alength out)]
    (case (.nextInt rng 3)
      0 (dotimes [_ (inc (.nextInt rng 8))]
          (let [i (.nextInt rng n)]
            (aset-byte out i (unchecked-byte (bit-xor (aget out i) (bit-shift-left 1 (.nextInt rng 8)))))))
      1 (let [start (.nextInt rng n)]
          (dotimes [k (min 16 (- n start))]
            (aset-byte out (+ start k) (unchecked-byte (.nextInt rng 256)))))
      2 nil)
    (if (= 2 (.nextInt rng 3))
      (java.util.Arrays/copyOf out (max 1 (.nextInt rng n)))
      out)))

(defn- outcome
  "What loading and building the file `bs` (its bytes, written to
  `tmp`) comes to: :built, :named-error (an ex-info whose message names
  the file), or the class of anything else (:hung after 20 s)."
  [^bytes bs ^java.io.File tmp]
  (java.nio.file.Files/write (.toPath tmp) bs
                             ^"[Ljava.nio.file.OpenOption;" (make-array java.nio.file.OpenOption 0))
  (let [f (future (try (body/body! (util/load-blender-model (str tmp)) {:strict? false})
                       :built
                       (catch clojure.lang.ExceptionInfo e
                         (if (str/includes? (ex-message e) (.getName tmp))
                           :named-error
                           [:unnamed (ex-message e)]))
                       (catch Throwable t t)))
        r (deref f 20000 :hung)]
    (if (or (keyword? r) (vector? r)) r (class r))))

(defn- read-bytes ^bytes [path] (java.nio.file.Files/readAllBytes (.toPath (java.io.File. ^String path))))

(deftest damaged-files-give-named-errors-or-bodies
  (doseq [[path n seed] [["assets/Models/test-creature/worm.blend" 150 20261123]
                         ["test/fixtures/strangers/hand.blend" 60 20261126]
                         ["test/fixtures/strangers/hand-b52.blend" 60 20261126]
                         ["test/fixtures/strangers/humanoid.blend" 60 20261126]
                         ["test/fixtures/strangers/worm-eye.blend" 60 20261126]]]
    (let [original (read-bytes path)
          rng (java.util.Random. seed)
          tmp (java.io.File/createTempFile "cortex-fuzz" ".blend")
          outcomes (frequencies (repeatedly n #(outcome (mutate original rng) tmp)))]
      (.delete tmp)
      (is (= #{} (disj (set (keys outcomes)) :built :named-error)) (str path " " outcomes))
      (is (pos? (get outcomes :named-error 0)) path)
      (is (pos? (get outcomes :built 0)) path))))

(def ^:private escaped-damage
  "[what, file, [[offset [byte ...]] ...]]: damage that once escaped."
  [["a vertex far out: the grid's cell count" "test/fixtures/humanoid/humanoid.blend"
    [[85389 [204 222 156 145 151 94 148 14 180 114 129 197 161 221 232]]]]
   ["a parent scaled flat" "assets/Models/test-creature/worm.blend"
    [[84326 [79]] [122671 [227]] [176886 [245]]]]
   ["moments of inertia beyond a float" "assets/Models/test-creature/hand.blend"
    [[149936 [95 26 41 105 144 170 54 147 218 226 183 232 18 110 139 65]]]]])

(deftest damage-that-once-escaped
  (doseq [[what path writes] escaped-damage
          :let [bs (read-bytes path)
                tmp (java.io.File/createTempFile "cortex-damage" ".blend")]]
    (doseq [[offset values] writes
            [i v] (map-indexed vector values)]
      (aset-byte bs (+ offset i) (unchecked-byte v)))
    (is (contains? #{:built :named-error} (outcome bs tmp)) what)
    (.delete tmp)))

(deftest non-finite-numbers-are-named
  (let [seg (doto (Node. "bad") (.attachChild (Geometry. "bad" (com.jme3.scene.shape.Box. 1 1 1)))
              (.setLocalTranslation (Vector3f. Float/NaN 0 0)))]
    (is (re-find #"segment \"bad\": its position in the world is not made of finite numbers"
                 (try (body/physical! (util/nodify "c" [seg])) ""
                      (catch clojure.lang.ExceptionInfo e (ex-message e))))))
  (let [a (doto (Node. "a") (.attachChild (Geometry. "a" (com.jme3.scene.shape.Box. 1 0.25 0.25))) (.setLocalTranslation -1.02 0 0))
        b (doto (Node. "b") (.attachChild (Geometry. "b" (com.jme3.scene.shape.Box. 1 0.25 0.25))) (.setLocalTranslation 1.02 0 0))
        j (doto (Node. "j") (.setUserData "joint" "{:type :point}")
            (.setLocalRotation (com.jme3.math.Quaternion. 0 0 0 0)))
        c (util/nodify "c" [a b (util/nodify "joints" [j])])]
    (is (re-find #"creature \"c\", joint \"j\": its rotation in the world is not made of finite numbers"
                 (try (body/body! c) "" (catch clojure.lang.ExceptionInfo e (ex-message e)))))))
