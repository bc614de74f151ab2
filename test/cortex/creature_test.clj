;; Generated from org/test-body.org by lein tangle: edit the chapter, not this file.
(ns cortex.creature-test
  (:require [clojure.java.io :as io]
            [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.demo :as demo]
            [cortex.test.body :as tb]
            [cortex.blender]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.app.state AbstractAppState)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Node VertexBuffer$Type)))

(set! *warn-on-reflection* true)

(defn- creature-in
  "The creature of a test world: the node loaded from a .blend file."
  [w]
  (first (filter #(re-find #"\.blend$" (.getName %)) (util/node-seq (.getRootNode w)))))

(defn- lowest-point
  "The lowest y of any vertex of `geom`, in the world."
  [^Geometry geom]
  (let [buffer (.getFloatBuffer (.getMesh geom) VertexBuffer$Type/Position)]
    (apply min (for [i (range (quot (.limit buffer) 3))
                     :let [v (Vector3f. (.get buffer (int (* 3 i)))
                                        (.get buffer (int (+ 1 (* 3 i))))
                                        (.get buffer (int (+ 2 (* 3 i)))))]]
                 (.y (.localToWorld geom v nil))))))

(defn- every-frame!
  "Run (f world frame) at the start of every frame of `w`."
  [w f]
  (let [frame (atom 0)]
    (.attach (.getStateManager w)
             (proxy [AbstractAppState] []
               (update [_] (f w (swap! frame inc)))))
    w))

(defn- seams
  "For every joint marker of `creature` (made physical), the two
  segments it joins and the marker's position in each one's frame:
  enough to measure, later, how far apart the two sides have come,
  whether or not a joint was made."
  [creature]
  (let [index (body/segment-index creature)]
    (for [j (body/joints creature)
          :let [[a b] (body/targets-near index j)
                ca (.getControl a RigidBodyControl)
                cb (.getControl b RigidBodyControl)
                p (.getWorldTranslation j)]]
      {:joint (.getName j) :a ca :b cb :pivot-a (body/pivot ca p) :pivot-b (body/pivot cb p)})))

(defn- gap
  "How far apart a seam's two sides are now."
  [{:keys [a b pivot-a pivot-b]}]
  (.distance (body/pivot-in-world a pivot-a) (body/pivot-in-world b pivot-b)))

(defn- fire-at-palm!
  "Stand low beside the palm, aim at it and press space."
  [w creature]
  (let [palm (first (filter #(= "palm" (body/segment-name %)) (body/segments creature)))
        target (.getPhysicsLocation ^RigidBodyControl (.getControl palm RigidBodyControl))]
    (doto (.getCamera w)
      (.setLocation (.add target (Vector3f. 6 0.2 0)))
      (.lookAt target Vector3f/UNIT_Y))
    ((get world/standard-debug-controls "key-space") w true)
    ((get world/standard-debug-controls "key-space") w false)))

(defn- run-hand
  "Run a hand world: gravity on at once (as key G does), a cannon ball at
  the palm once it has landed. Returns the largest gap of any seam in the
  last second, and the largest in the first."
  [w]
  (let [worst (atom {:early 0.0 :late 0.0})
        tracked (atom nil)]
    (every-frame! w (fn [w frame]
                      (when (= 1 frame)
                        (reset! tracked (seams (creature-in w)))
                        ((get demo/gravity-control "key-g") w true))
                      (when (= 120 frame) (fire-at-palm! w (creature-in w)))
                      (let [g (apply max (map gap @tracked))]
                        (cond (< frame 60) (swap! worst update :early max g)
                              (> frame 240) (swap! worst update :late max g)))))
    (world/run-world! w 300)
    @worst))

(deftest the-hand-alone-is-a-hologram
  (let [w (tb/test-hand-1)
        positions #(mapv (fn [g] (.clone (.getWorldTranslation g)))
                         (body/segments (creature-in w)))
        before (atom nil)]
    (every-frame! w (fn [w frame] (when (= 1 frame) (reset! before (positions)))))
    (world/run-world! w 30)
    (is (= 16 (count (body/segments (creature-in w)))))
    (is (not-any? #(.getControl % RigidBodyControl) (body/segments (creature-in w))))
    (is (= @before (positions)) "nothing moves it")))

(deftest the-hand-without-joints-falls-apart
  (let [{:keys [early late]} (run-hand (tb/test-hand-2))]
    (testing "the pieces start out touching"
      (is (< early 0.05)))
    (testing "and end up apart once the palm is hit"
      (is (> late 0.5)))))

(deftest the-jointed-hand-holds-together
  (let [{:keys [early late]} (run-hand (tb/test-hand-3))]
    (is (< early 0.01))
    (testing "even after the palm is hit, no seam opens more than 5% of the shortest segment"
      (is (< late 0.02)))))

(defn- run-worm
  "Run the worm world for five simulated seconds. Returns the largest
  joint gap seen, the segments' final positions, and the world."
  []
  (let [w (tb/test-worm)
        worst (atom 0.0)
        tracked (atom nil)]
    (every-frame! w (fn [w frame]
                      (when (= 1 frame) (reset! tracked (seams (creature-in w))))
                      (swap! worst max (apply max (map gap @tracked)))))
    (world/run-world! w 300)
    {:gap @worst
     :world w
     :state (vec (for [g (body/segments (creature-in w))
                       :let [t (.getWorldTranslation g) r (.getWorldRotation g)]]
                   [(.x t) (.y t) (.z t) (.getX r) (.getY r) (.getZ r) (.getW r)]))}))

(deftest the-worm-falls-onto-the-floor-and-holds
  (let [{:keys [gap world]} (run-worm)
        worm (creature-in world)]
    (is (= 2 (count (body/segments worm))))
    (testing "its joint held: the two sides stayed within 1% of a segment's length (2)"
      (is (< gap 0.02)))
    (testing "it fell from y = 0.5 and lies on the floor, whose top is at y = -7
              (hulls and boxes have no collision margin in jme3-jbullet 3.2.4:
              it rests within a few hundredths, sunk by contact softness)"
      (doseq [g (body/segments worm)]
        (is (< -7.01 (lowest-point g) -6.95) (.getName g))))))

(deftest the-worm-repeats-to-the-bit
  (is (= (:state (run-worm)) (:state (run-worm)))))

(def ^:private evil-path
  "Where the hostile joint descriptions of the broken creatures would
  write, if anything evaluated them."
  "/tmp/cortex-evil-joint-was-evaluated")

(deftest broken-creatures-fail-with-named-errors
  (io/delete-file evil-path true)
  (doseq [[file pattern]
          [["lonely" #"creature \"\S*lonely.blend\", joint \"worm-joint\": found 1 segment"]
           ["evil-joint" #"joint \"worm-joint\": not an allowed operation: \(spit "]
           ["read-eval" #"joint \"worm-joint\": cannot read \"#=\(clojure.core/spit"]
           ["bad-mass" #"object \"worm-2\": mass must be a non-negative number, not \"heavy\""]
           ["unknown-type" #"joint \"worm-joint\": unknown joint type :rubber; known types: "]]]
    (let [path (str "test/fixtures/creatures/" file ".blend")
          message (try (body/body! (util/load-blender-model path)) nil
                       (catch clojure.lang.ExceptionInfo e (ex-message e)))]
      (is (and message (re-find pattern message)) (str file ": " message))))
  (testing "and nothing in them was evaluated"
    (is (not (.exists (io/file evil-path))))))
