;; Generated from org/world.org by lein tangle: edit the chapter, not this file.
(ns cortex.world-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Quaternion Vector3f)
           (cortex RatchetTimer)))

(set! *warn-on-reflection* true)

(defn- earth-gravity [w] (world/set-gravity w (Vector3f. 0 -9.81 0)))

(defn- floor [] (util/box 10 1 10 :position (Vector3f. 0 -1 0) :mass 0 :name "floor"))

(defn- live-threads [] (set (keys (Thread/getAllStackTraces))))

(deftest box-comes-to-rest-on-the-floor
  (let [b (util/box 0.5 0.25 0.5 :position (Vector3f. 0 3 0))
        w (world/world (util/nodify [b (floor)]) {} earth-gravity world/no-op)]
    (world/run-world! w 300)
    (is (= 300 (:frames @w)))
    (testing "resting height is the half-height above the floor's top (y = 0)"
      (is (< (Math/abs (- (.y (.getWorldTranslation b)) 0.25)) (* 0.01 0.25))))
    (testing "it has stopped"
      (is (< (.length (.getLinearVelocity ^RigidBodyControl (.getControl b RigidBodyControl)))
             0.01)))))

(defn- tumbling-boxes
  "Five boxes dropped, turned, onto a floor and each other."
  []
  (for [i (range 5)]
    (util/box 0.4 0.3 0.5 :name (str "box-" i)
              :position (Vector3f. (* 0.3 i) (+ 1 (* 1.1 i)) (* -0.2 i))
              :rotation (doto (Quaternion.) (.fromAngles (* 0.3 i) 0.2 (* 0.1 i))))))

(defn- run-and-record
  [frames]
  (let [boxes (tumbling-boxes)
        w (world/world (util/nodify (cons (floor) boxes)) {} earth-gravity world/no-op)]
    (world/run-world! w frames)
    (vec (for [b boxes
               :let [t (.getWorldTranslation b) r (.getWorldRotation b)]]
           [(.x t) (.y t) (.z t) (.getX r) (.getY r) (.getZ r) (.getW r)]))))

(deftest runs-repeat-to-the-bit
  (let [a (run-and-record 300)
        b (run-and-record 300)]
    (is (= a b))
    (testing "the boxes really moved and collided"
      (is (every? #(< (second %) 3) a)))))

(deftest fixed-step-time
  (let [timer (RatchetTimer. 60)
        seen (atom [])
        w (world/world (util/nodify []) {}
                       (fn [w] (.setTimer w timer))
                       (fn [_ tpf]
                         (swap! seen conj [tpf (.getTime timer) (.getTimeInSeconds timer)])
                         (Thread/sleep 20)))
        start (System/nanoTime)]
    (world/run-world! w 12)
    (testing "12 slow frames are exactly 12/60 simulated seconds, 1/60 each"
      (is (= (repeat 12 (float (/ 1 60))) (map first @seen)))
      (is (= (range 1 13) (map second @seen)))
      (is (= (float (/ 12 60)) (last (map last @seen)))))
    (testing "while the wall clock went further"
      (is (> (/ (- (System/nanoTime) start) 1e9) 0.24)))))

(deftest headless-runs-leave-no-threads
  (let [before (live-threads)]
    (world/run-world! (world/world (util/nodify [(floor)]) {} world/no-op world/no-op) 10)
    (is (empty? (remove before (filter #(.isAlive %) (live-threads)))))))

(deftest failures-end-the-run
  (testing "an update function that throws stops the world with an ex-info"
    (let [w (world/world (util/nodify []) {} world/no-op
                         (fn [w _] (when (= 3 (:frames @w)) (throw (ex-info "boom" {})))))
          e (try (world/run-world! w 100) nil (catch clojure.lang.ExceptionInfo e e))]
      (is (re-find #"boom" (ex-message e)))
      (is (< (:frames @w) 100))))
  (testing "so does a setup function that throws"
    (let [e (try (world/run-world! (world/world (util/nodify []) {}
                                                (fn [_] (throw (IllegalStateException. "bad setup")))
                                                world/no-op)
                                   10)
                 nil
                 (catch clojure.lang.ExceptionInfo e e))]
      (is (re-find #"bad setup" (ex-message e)))))
  (testing "a frame count that is not a positive integer"
    (is (thrown? clojure.lang.ExceptionInfo
                 (world/run-world! (world/world (util/nodify []) {} world/no-op world/no-op) 0)))))

(deftest gravity-can-be-switched-off
  (let [b (util/box 0.5 0.5 0.5 :position (Vector3f. 0 5 0))
        w (world/world (util/nodify [b]) {}
                       (fn [w] (world/set-gravity w Vector3f/ZERO)) world/no-op)]
    (world/run-world! w 60)
    (is (= 5.0 (double (.y (.getWorldTranslation b)))))))

(deftest key-bindings
  (is (= "KeyTrigger" (.getSimpleName (class (world/trigger "key-space")))))
  (is (thrown-with-msg? clojure.lang.ExceptionInfo #"key-nope"
                        (world/trigger "key-nope")))
  (testing "space fires a cannon ball into the world"
    (let [bodies (atom nil)
          w (world/world (util/nodify []) world/standard-debug-controls world/no-op
                         (fn [w _]
                           (when (= 2 (:frames @w))
                             ((get world/standard-debug-controls "key-space") w false))
                           (reset! bodies (count (.getRigidBodyList (world/physics-space w))))))]
      (world/run-world! w 30)
      (let [balls (filter #(= "cannon-ball" (.getName %)) (util/node-seq (.getRootNode w)))]
        (is (= 1 (count balls)))
        (is (= 1 @bodies))
        (testing "and it flies away from the camera"
          (is (> (.distance (.getWorldTranslation (first balls))
                            (.getLocation (.getCamera w)))
                 5)))))))

(defn- seconds-taken
  "[the value of (f), the seconds it took]."
  [f]
  (let [start (System/nanoTime)
        v (f)]
    [v (/ (- (System/nanoTime) start) 1e9)]))

(defn- wait-for-frames
  "Wait until `w` has run `n` frames in its current run, or 10 s."
  [w n]
  (let [deadline (+ (System/currentTimeMillis) 10000)]
    (while (and (< (:frames @w) n) (< (System/currentTimeMillis) deadline))
      (Thread/sleep 5))))

(deftest start-stop-start-stop
  (let [b (util/box 0.5 0.5 0.5 :position (Vector3f. 0 20 0) :name "box")
        w (world/world (util/nodify [b (floor)]) {} earth-gravity world/no-op)
        height #(.y (.getWorldTranslation b))]
    (testing "start! returns at once; the world runs on a thread of its own"
      (let [[v s] (seconds-taken #(world/start! w))]
        (is (identical? w v))
        (is (< s 1.0) (str "start! took " s " s")))
      (is (world/running? w))
      (wait-for-frames w 20)
      (is (<= 20 (:frames @w)))
      (is (not= (Thread/currentThread) (:thread @w)))
      (is (thrown-with-msg? clojure.lang.ExceptionInfo #"already running" (world/start! w))))
    (testing "stop! stops it and waits until its thread has ended"
      (let [[_ s] (seconds-taken #(world/stop! w))]
        (is (< s 1.0) (str "stop! took " s " s")))
      (is (not (world/running? w)))
      (is (not (.isAlive ^Thread (:thread @w))))
      (is (nil? (:error @w))))
    (let [stopped-at (height)]
      (is (< stopped-at 20) "it fell while it ran")
      (testing "started again, it goes on from where it stopped, with its physics"
        (let [[_ s] (seconds-taken #(world/start! w))]
          (is (< s 1.0) (str "the second start! took " s " s")))
        (wait-for-frames w 20)
        (is (< (height) stopped-at))
        (is (= 2 (world/enqueue! w #(count (.getRigidBodyList (world/physics-space w)))))))
      (testing "and stopped again"
        (let [[_ s] (seconds-taken #(world/stop! w))]
          (is (< s 1.0) (str "the second stop! took " s " s")))
        (is (not (world/running? w)))
        (is (nil? (:error @w)))))
    (testing "a stopped world also runs again blocking, for an exact number of frames"
      (world/run-world! w 10)
      (is (= 10 (:frames @w))))))

(deftest changing-a-running-world
  (let [b (util/box 0.5 0.5 0.5 :position (Vector3f. 0 0 0) :name "box")
        w (world/world (util/nodify [b]) {} (fn [w] (world/set-gravity w Vector3f/ZERO))
                       world/no-op)]
    (world/start! w)
    (try
      (is (= :hello (world/enqueue! w (constantly :hello))))
      (is (identical? (:thread @w) (world/enqueue! w #(Thread/currentThread))))
      (is (thrown-with-msg? clojure.lang.ExceptionInfo #"thrown inside"
                            (world/enqueue! w #(throw (ex-info "thrown inside" {})))))
      (wait-for-frames w 5)
      (is (= 0.0 (double (.y (.getWorldTranslation b)))) "weightless, it stays put")
      (world/enqueue! w #(world/set-gravity w (Vector3f. 0 9.81 0)))
      (let [frames (:frames @w)]
        (wait-for-frames w (+ frames 30)))
      (is (< 0.5 (.y (.getWorldTranslation b))) "with gravity upside down, it rises")
      (finally (world/stop! w)))
    (is (= :after (world/enqueue! w (constantly :after))) "a stopped world just calls f")))

(deftest a-world-stops-itself
  (let [w (world/world (util/nodify []) {} world/no-op
                       (fn [w _] (when (= 10 (:frames @w)) (world/stop! w))))]
    (world/start! w {:fps 600})
    (is (identical? w (world/await! w 10000)))
    (is (<= 10 (:frames @w) 12))
    (is (not (.isAlive ^Thread (:thread @w))))))

(deftest interrupting-a-run-stops-its-world
  (let [w (world/world (util/nodify [(floor)]) {} world/no-op (fn [_ _] (Thread/sleep 1)))
        result (promise)
        runner (Thread. ^Runnable #(deliver result (try (world/run-world! w 1000000)
                                                         (catch Throwable t t))))]
    (.start runner)
    (wait-for-frames w 10)
    (.interrupt runner)
    (let [e (deref result 5000 :still-running)]
      (is (instance? clojure.lang.ExceptionInfo e))
      (is (re-find #"interrupted" (str (ex-message e)))))
    (is (not (world/running? w)))
    (is (not (.isAlive ^Thread (:thread @w))))
    (is (< (:frames @w) 1000000))))

(deftest a-world-prints-where-it-was-started
  (let [out (java.io.StringWriter.)
        err (java.io.StringWriter.)
        w (world/world (util/nodify []) {} world/no-op
                       (fn [w _]
                         (case (long (:frames @w))
                           3 (println "hello from frame 3")
                           6 (throw (ex-info "trouble in frame 6" {}))
                           nil)))]
    (binding [*out* out *err* err]
      (world/start! w {:fps 600}))
    (is (thrown-with-msg? clojure.lang.ExceptionInfo #"trouble in frame 6" (world/await! w 10000)))
    (is (re-find #"hello from frame 3" (str out)))
    (is (re-find #"world failed after \d+ frames: trouble in frame 6" (str err)))))
