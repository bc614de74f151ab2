;; Generated from org/body.org by lein tangle: edit the chapter, not this file.
(ns cortex.designer-test
  (:require [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.blender-test :refer [read-json]]
            [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints PhysicsJoint)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Node)))

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
    (doseq [{:keys [name mass hull-points hull-volume]} segments
            :let [w (want-segments name)]]
      (is (close? (get w "mass") mass) name)
      (is (= (get w "vertices") hull-points) name)
      (is (close? (get w "volume") hull-volume) name))
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
      (is (re-find #"joint \"knee-front-r\" is 0\.200 from lower-leg-front-r and 0\.200 from upper-leg-front-r, more than the tolerance 0\.050" m))))
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
  "Drop `creature` (not yet built) half a unit above a floor at y = 0 (its lowest
  point) for 10 s; return when every segment stayed slower than 0.05
  m/s for good, how far any segment moved between 8 and 10 s, the
  largest speed in the last second and the largest joint gap."
  [^Node creature]
  (.updateGeometricState creature)
  (let [segs (vec (body/segments creature))
        lowest (apply min (for [^Geometry g segs
                                :let [b ^com.jme3.bounding.BoundingBox (.getWorldBound g)]]
                            (- (.y (.getCenter b)) (.getYExtent b))))
        _ (.move creature 0 (float (- 0.5 lowest)) 0)
        _ (.rotate creature 0.05 0.3 0.02)
        _ (.updateGeometricState creature)
        ;; built where it was put: a RigidBodyControl takes its place
        ;; from its Geometry only when it is attached
        _ (body/body! creature)
        floor (util/box 40 1 40 :position (Vector3f. 0 -1 0) :mass 0 :name "floor")
        joints (map :physics-joint (body/joint-records creature))
        frame (atom 0) still-since (atom nil) at-8 (atom nil) last-second (atom 0.0)
        gap (atom 0.0)
        w (world/world (util/nodify [creature floor]) {}
                       #(world/set-gravity % (Vector3f. 0 -9.81 0))
                       (fn [_ _]
                         (let [f (swap! frame inc)
                               fastest (apply max (map speed segs))]
                           (swap! gap max (apply max 0.0 (map body/joint-gap joints)))
                           (if (< fastest 0.05)
                             (swap! still-since #(or % f))
                             (reset! still-since nil))
                           (when (> f 540) (swap! last-second max fastest))
                           (when (= f 480)
                             (reset! at-8 (mapv #(.clone (.getWorldTranslation ^Geometry %)) segs))))))]
    (world/run-world! w 600)
    {:still-at (some-> @still-since (/ 60.0))
     :moved (apply max (map (fn [^Vector3f a ^Geometry g] (.distance a (.getWorldTranslation g)))
                            @at-8 segs))
     :fastest-last-second @last-second
     :gap @gap}))

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

(deftest damaged-files-give-named-errors-or-bodies
  (let [original (java.nio.file.Files/readAllBytes
                  (.toPath (java.io.File. "assets/Models/test-creature/worm.blend")))
        rng (java.util.Random. 20261123)
        tmp (java.io.File/createTempFile "cortex-fuzz" ".blend")
        outcomes (frequencies
                  (for [i (range 150)]
                    (do (java.nio.file.Files/write (.toPath tmp) (mutate original rng)
                                                   ^"[Ljava.nio.file.OpenOption;" (make-array java.nio.file.OpenOption 0))
                        (let [f (future (try (body/body! (util/load-blender-model (str tmp))
                                                         {:strict? false})
                                             :built
                                             (catch clojure.lang.ExceptionInfo _ :named-error)
                                             (catch Throwable t t)))
                              r (deref f 20000 :hung)]
                          (if (keyword? r) r (class r))))))]
    (.delete tmp)
    (is (= #{} (disj (set (keys outcomes)) :built :named-error)) (str outcomes))
    (is (pos? (get outcomes :named-error 0)))
    (is (pos? (get outcomes :built 0)))))

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
