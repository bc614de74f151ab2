(ns cortex.test.body
  "The worlds that show a body being built, step by step: the hand as a
  hologram, the hand solid but in pieces, the hand jointed, and the worm
  that later chapters give senses to. Each is a function returning an
  unstarted world: (.start (test-worm)) opens a window,
  (world/run-world! (test-worm) 300) runs it headless."
  (:require [cortex.body :as body]
            [cortex.render :as render]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.math ColorRGBA Vector3f)
           (cortex RatchetTimer)))

(def hand-path "Models/test-creature/hand.blend")
(def worm-path "Models/test-creature/worm.blend")

(defn hand
  "The hand, as Blender describes it: a palm and five fingers."
  []
  (util/load-blender-model hand-path))

(defn worm
  "The worm: two segments and one joint."
  []
  (util/load-blender-model worm-path))

(def earth-gravity (Vector3f. 0 -9.81 0))

(def gravity-control
  "G turns gravity on, U turns it off."
  {"key-g" (fn [w pressed?] (when pressed? (world/set-gravity w earth-gravity)))
   "key-u" (fn [w pressed?] (when pressed? (world/set-gravity w Vector3f/ZERO)))})

(def debug-control
  "H shows the physics: collision shapes and joints."
  {"key-h" (fn [w pressed?] (when pressed? (world/enable-debug w)))})

(defn floor
  "A grey static slab whose top is at y = -7."
  []
  (util/box 10 3 10 :position (Vector3f. 0 -10 0) :color ColorRGBA/Gray :mass 0
            :name "floor"))

(defn setup
  "Point the camera at the creature from above and to the side, light
  the scene and fix the step at 1/60 s. Returns the world."
  [^SimpleApplication world]
  (doto (.getCamera world)
    (.setLocation (Vector3f. -6.5 7 7))
    (.lookAt (Vector3f. 0 -1 -1) Vector3f/UNIT_Y))
  (util/light-up-everything world)
  (.setTimer world (RatchetTimer. 60))
  world)

(defn- record-if-asked!
  "Record world `w` into folder `record?` when it names one, into
  out/`world-name` when it is true, not at all when it is false or nil."
  [w record? world-name]
  (when record?
    (render/record! w (if (true? record?) (str "out/" world-name) record?)))
  w)

(defn test-hand-1
  "The hand straight from Blender: it has no physical presence, and
  things pass through it. Records its frames when `record?` is a
  folder (or true, for out/test-hand-1)."
  ([] (test-hand-1 false))
  ([record?]
   (world/world (hand) world/standard-debug-controls
                #(setup (record-if-asked! % record? "test-hand-1"))
                world/no-op)))

(defn test-hand-2
  "The hand made solid, with nothing holding it together: switch on
  gravity (G) and it falls to the floor in pieces. Records its frames
  when `record?` is a folder (or true, for out/test-hand-2)."
  ([] (test-hand-2 false))
  ([record?]
   (world/world (util/nodify [(body/physical! (hand)) (floor)])
                (merge world/standard-debug-controls gravity-control)
                #(setup (world/set-gravity (record-if-asked! % record? "test-hand-2")
                                           Vector3f/ZERO))
                world/no-op)))

(defn test-hand-3
  "The hand with its joints: under gravity (G) it falls as one piece,
  fingers bending only as far as their knuckles allow. H shows the
  joints. Records its frames when `record?` is a folder (or true, for
  out/test-hand-3)."
  ([] (test-hand-3 false))
  ([record?]
   (world/world (util/nodify [(body/body! (hand)) (floor)])
                (merge world/standard-debug-controls debug-control gravity-control)
                #(setup (world/set-gravity (record-if-asked! % record? "test-hand-3")
                                           Vector3f/ZERO))
                world/no-op)))

(defn test-worm
  "The worm falls onto the floor; space fires a cannon ball at it and H
  shows its joint. Simulated and wall time are shown on screen. Records
  its frames when `record?` is a folder (or true, for out/test-worm)."
  ([] (test-worm false))
  ([record?]
   (world/world (util/nodify [(body/body! (worm)) (floor)])
                (merge world/standard-debug-controls debug-control)
                (fn [w]
                  (record-if-asked! w record? "test-worm")
                  (setup w)
                  (world/speed-up w)
                  (util/display-dilated-time w (.getTimer ^SimpleApplication w)))
                world/no-op)))
