(ns cortex.sense
  "What senses share: finding the marker nodes a creature's designer
  placed in Blender, and reading the data attached to them."
  (:require [cortex.blender :as blender])
  (:import (com.jme3.scene Node)))

(def ^{:doc "The custom property `key` that Blender gave the object
  `spatial` stands for, or nil; asked of a mesh's Geometry, it answers
  for the object holding it. (The loader owns the convention; this is
  cortex.blender/meta-data.)"
       :arglists '([spatial key])}
  meta-data
  blender/meta-data)

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
