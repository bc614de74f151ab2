(ns cortex.demo
  "The scene cortex's demos share: the reference creatures, a floor, a
  camera, lights and keys.

  Entry points: `hand`, `worm` (load the reference creatures), `floor`,
  `setup` (camera, light, fixed step), `gravity-control` and
  `debug-control` (key maps for cortex.world/world)."
  (:require [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.math ColorRGBA Vector3f)
           (cortex RatchetTimer)))

(set! *warn-on-reflection* true)

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
