;; Generated from org/sense.org by lein tangle: edit the chapter, not this file.
(ns cortex.sense
  "What senses share: finding the marker nodes a creature's designer
  placed in Blender, and reading the data attached to them.

  Entry points: `meta-data` (an object's custom property),
  `sense-nodes` (the markers under a named parent), `camera-key`,
  `rigid-body-key`, `constraint-key`, `world-key`, `modifiers-key`,
  `modifiers-text`."
  (:import (com.jme3.scene Geometry Node Spatial)))

(set! *warn-on-reflection* true)

(defn meta-data
  "The custom property `key` that Blender gave the object `spatial`
  stands for, or nil; asked of a mesh's Geometry that has none, it
  answers for the object Node holding it."
  [^Spatial spatial key]
  (let [v (.getUserData spatial (str key))]
    (if (and (nil? v) (instance? Geometry spatial) (.getParent spatial))
      (.getUserData (.getParent spatial) (str key))
      v)))

(def camera-key
  "The user data under which a Blender camera object's Node keeps its
  settings: {:type :lens :sensor-width :sensor-height :sensor-fit
  :clip-start :clip-end :ortho-scale :shift-x :shift-y}."
  "cortex.blender.camera")

(def rigid-body-key
  "The user data under which an object's Node carries its Blender rigid
  body settings (the Physics tab; see cortex.blender.rigid-body)."
  "blender-rigid-body")

(def constraint-key
  "The user data under which an object's Node carries its Blender rigid
  body constraint."
  "blender-rigid-body-constraint")

(def world-key
  "The user data under which the scene's Node carries its Rigid Body
  World."
  "blender-rigid-body-world")

(def modifiers-key
  "The user data under which a mesh object's Node lists the modifiers
  the reader did not apply that Blender shows and that can move the
  mesh's vertices, and its shape keys in use: a vector of {:name :kind},
  with :why for a Mirror or a shape key (see cortex.blender.scene's
  unapplied)."
  "blender-modifiers")

(defn modifiers-text
  "Modifiers as listed under `modifiers-key`, as warnings name them:
  \"Mirror: Mirror, it bisects, Subdivision: Subsurf\"."
  [ms]
  (apply str (interpose ", " (map #(str (:name %) ": " (:kind %) (some->> (:why %) (str ", "))) ms))))

(defn sense-nodes
  "A function of a creature that returns the children of the creature's
  node named `parent-name`: the markers (Blender empties) for one sense,
  or for the joints. Nothing when the creature has no such node."
  [^String parent-name]
  (fn [^Node creature]
    (let [parent (.getChild creature parent-name)]
      (if (instance? Node parent)
        (seq (.getChildren ^Node parent))
        ()))))
