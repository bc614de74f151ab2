;; Generated from org/proprioception.org by lein tangle: edit the chapter, not this file.
(ns cortex.joint-fixtures
  "Creatures made in code for the proprioception, muscle and simulation
  tests: the scene graph the Blender loader would make."
  (:require [cortex.util :as util])
  (:import (com.jme3.math FastMath Quaternion Vector3f)
           (com.jme3.scene Geometry Node)
           (com.jme3.scene.shape Box)))

(set! *warn-on-reflection* true)

(def worm-path "Models/test-creature/worm.blend")
(def hand-path "Models/test-creature/hand.blend")

(defn segment-node
  "An object node `name` holding one box of half-extents `half` at
  `center`, of `mass`."
  ^Node [name center half mass]
  (let [[x y z] half [cx cy cz] center]
    (doto (Node. ^String name)
      (.attachChild (Geometry. ^String name (Box. (float x) (float y) (float z))))
      (.setLocalTranslation (Vector3f. (float cx) (float cy) (float cz)))
      (.setUserData "mass" (float mass)))))

(defn joint-node
  "A joint empty `name` at `position`, turned by `rotation`, described
  by `description`."
  ^Node [name position ^Quaternion rotation ^String description]
  (let [[x y z] position]
    (doto (Node. ^String name)
      (.setLocalTranslation (Vector3f. (float x) (float y) (float z)))
      (.setLocalRotation rotation)
      (.setUserData "joint" description))))

(defn two-segments
  "Two 1.9 x 0.4 x 0.4 boxes along x, \"upper\" at x = -1 and \"lower\"
  at x = 1 (height `y`), joined at x = 0 by \"elbow\", described by
  `description`, its empty turned by `rotation`; masses [upper lower],
  0 for a static one."
  ([description] (two-segments description Quaternion/IDENTITY))
  ([description rotation] (two-segments description rotation [1 1] 0))
  ([description rotation [m-upper m-lower] y]
   (util/nodify "two-segments"
                [(segment-node "upper" [-1 y 0] [0.95 0.2 0.2] m-upper)
                 (segment-node "lower" [1 y 0] [0.95 0.2 0.2] m-lower)
                 (util/nodify "joints" [(joint-node "elbow" [0 y 0] rotation description)])])))

(defn turned
  "A rotation of `angle` about the jME axis [x y z]."
  ^Quaternion [angle [x y z]]
  (doto (Quaternion.) (.fromAngleAxis (float angle) (.normalize (Vector3f. (float x) (float y) (float z))))))

(def half-turn-about-blender-z
  "Turns a joint empty half round about Blender's Z (jME's Y): the two
  segments then swap order."
  (turned FastMath/PI [0 1 0]))

(def chain-joints
  ["{:type :point}"
   "{:type :hinge :limit [-0.5 0.5] :axis (Vector3f. 0 0 1)}"
   "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.2}"])

(defn chain
  "`n` 1 x 0.4 x 0.4 boxes of mass 1 along x, 0.1 apart, centred on the
  origin at `height`, joints cycling point, hinge, cone."
  ^Node [n height]
  (let [pitch 1.1
        x0 (- (/ (* pitch (dec n)) 2))]
    (doto ^Node (util/nodify (str "chain-" n)
                             (concat
                              (for [i (range n)]
                                (segment-node (str "seg-" i) [(+ x0 (* pitch i)) 0 0] [0.5 0.2 0.2] 1))
                              [(util/nodify "joints"
                                            (for [i (range 1 n)]
                                              (joint-node (str "joint-seg-" i)
                                                          [(+ x0 (* pitch i) -0.55) 0 0]
                                                          Quaternion/IDENTITY
                                                          (chain-joints (mod (dec i) 3)))))]))
      (.setLocalTranslation 0 (float height) 0))))
