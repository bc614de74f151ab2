(ns cortex.sense
  "What senses share: finding the marker nodes a creature's designer
  placed in Blender, and reading the data attached to them."
  (:import (com.jme3.scene Geometry Node Spatial)))

(defn meta-data
  "The custom property `key` that Blender gave the object `spatial`
  stands for, or nil. Asked of a mesh's Geometry, it answers for the
  object that holds the Geometry."
  [^Spatial spatial ^String key]
  (let [value (.getUserData spatial key)]
    (if (and (nil? value) (instance? Geometry spatial) (.getParent spatial))
      (.getUserData (.getParent spatial) key)
      value)))

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
