;; Generated from org/bench.org by lein tangle: edit the chapter, not this file.
(ns cortex.bench.creatures
  "Creatures of any size, made in code for benchmarks: chains and
  branching trees of boxes with a joint in every gap, first as plain
  data (segments and joints), then as the scene graph the Blender
  loader would have made."
  (:require [cortex.util :as util])
  (:import (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Node)
           (com.jme3.scene.shape Box)))

(set! *warn-on-reflection* true)

(def segment-length
  "How long a generated segment is, along the direction it grows in."
  1.0)

(def segment-width
  "How wide a generated segment is across its length."
  0.4)

(def gap
  "The space between two joined segments, so joined neighbours at rest
  do not touch (jme3-jbullet's hull shapes have no collision margin to
  fill it)."
  0.1)

(def joint-descriptions
  "The joint property text of each kind of generated joint."
  {:point "{:type :point}"
   :hinge "{:type :hinge :limit [-0.5 0.5] :axis (Vector3f. 0 0 1)}"
   :cone "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.2}"})

(def joint-kinds
  "The kinds of joint, in the order generated joints cycle through them."
  [:point :hinge :cone])

(defn- v+ [a b] (mapv + a b))
(defn- v* [k v] (mapv #(* k %) v))

(defn- half-extents
  "Half-extents of a segment that is long along the axis of `direction`."
  [direction]
  (mapv #(if (zero? %) (/ segment-width 2) (/ segment-length 2)) direction))

(defn- reach-along
  "How far `segment`'s face in `direction` lies from its centre."
  [segment direction]
  (reduce + (map #(* (Math/abs (double %1)) %2) direction (:half segment))))

(defn grow
  "A new segment named `name`, attached to `parent` on its face in
  `direction` (an axis vector such as [1 0 0]), and the joint of `kind`
  between them: [segment joint]."
  [parent direction name kind]
  (let [face (reach-along parent direction)
        joint-at (v+ (:center parent) (v* (+ face (/ gap 2)) direction))
        center (v+ (:center parent) (v* (+ face gap (/ segment-length 2)) direction))]
    [{:name name :center center :half (half-extents direction)}
     {:name (str "joint-" name) :position joint-at :kind kind
      :between [(:name parent) name]}]))

(defn from-plan
  "A creature description from `plan`, a sequence of [parent-index
  direction] for segments 1, 2, ...; segment 0 is a root along x at the
  origin. Joint i (for segment i + 1) is of kind (joint-kinds (mod i 3))."
  [creature-name plan]
  (let [root {:name "seg-0" :center [0.0 0.0 0.0] :half (half-extents [1 0 0])}]
    (loop [segments [root] joints [] [[parent direction] & more :as plan] plan]
      (if (empty? plan)
        {:name creature-name :segments segments :joints joints}
        (let [i (count segments)
              kind (joint-kinds (mod (count joints) (count joint-kinds)))
              [s j] (grow (segments parent) direction (str "seg-" i) kind)]
          (recur (conj segments s) (conj joints j) more))))))

(defn chain
  "The description of a chain of `n` segments along x."
  [n]
  (from-plan (str "chain-" n) (for [i (range 1 n)] [(dec i) [1 0 0]])))

(def rib-length
  "Segments in each rib of a generated tree."
  3)

(defn tree-plan
  "The growth plan of a tree: spine segment k (along x), then its rib of
  `rib-length` segments along +z for even k and -z for odd k, and so on,
  cut off after `n` segments in all."
  [n]
  (let [per (inc rib-length)]
    (for [i (range 1 n)
          :let [k (quot i per) r (mod i per)]]
      (if (zero? r)
        [(* per (dec k)) [1 0 0]]
        [(dec i) [0 0 (if (even? k) 1 -1)]]))))

(defn tree
  "The description of a branching tree of `n` segments: a spine along x
  with a rib of `rib-length` segments off every spine segment."
  [n]
  (from-plan (str "tree-" n) (tree-plan n)))

(defn- vec3 ^Vector3f [[x y z]] (Vector3f. (float x) (float y) (float z)))

(defn- segment-node
  "A Blender-style object node for one segment: a Node holding a box
  Geometry, with mass 1 as user data."
  ^Node [{:keys [name center half]}]
  (let [[x y z] half]
    (doto (Node. ^String name)
      (.attachChild (Geometry. ^String name (Box. (float x) (float y) (float z))))
      (.setLocalTranslation (vec3 center))
      (.setUserData "mass" (float 1)))))

(defn- joint-node
  "A joint marker: an empty Node whose `joint` user data describes it."
  ^Node [{:keys [name position kind]}]
  (doto (Node. ^String name)
    (.setLocalTranslation (vec3 position))
    (.setUserData "joint" ^String (joint-descriptions kind))))

(defn centre
  "The mean of the segment centres of `description`."
  [{:keys [segments]}]
  (v* (/ 1.0 (count segments)) (reduce v+ (map :center segments))))

(defn creature
  "The scene graph of `description`, as the Blender loader would make it:
  one object node per segment and a \"joints\" node of markers. The
  creature is centred on the origin in x and z and lifted to `height`."
  ([description] (creature description 0))
  ([{:keys [name segments joints] :as description} height]
   (let [[cx _ cz] (centre description)]
     (doto ^Node (util/nodify name (concat (map segment-node segments)
                                     [(util/nodify "joints" (map joint-node joints))]))
       (.setLocalTranslation (float (- cx)) (float height) (float (- cz)))))))
