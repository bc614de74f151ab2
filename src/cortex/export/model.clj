;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.export.model
  "A creature's plan as the exporters see it: each segment's Z-up frame
  and inertia (`segment-info`), which segment hangs from which
  (`tree`), each joint as one-axis degrees of freedom (`joint-dofs`,
  `cone-frame`), and each joint's muscle from the plan (`muscles`)."
  (:require [clojure.string :as str]
            [cortex.body :as body]
            [cortex.export.geometry :refer [C dot identity3 mm mv norm quat->matrix
                                            v+ v- v* z-up z-up-rotation]]
            [cortex.strength :as strength :refer [axis-of box-moments]])
  (:import (com.jme3.math Quaternion Vector3f)))

(set! *warn-on-reflection* true)

(def ^{:arglists '([shape])
       :doc "The points that bound `shape`: cortex.strength/shape-points."}
  shape-points strength/shape-points)

(defn segment-info
  "What the writers need of plan segment `s`."
  [{:keys [id mass position rotation inertia shape] :as s}]
  (let [R (z-up-rotation (quat->matrix rotation))
        box? (= :box (:source inertia))
        Q (if box? identity3 (quat->matrix (:rotation inertia)))]
    (assoc s
           :pos (z-up position) :R R
           :com (if box? [0.0 0.0 0.0] (z-up (:centre inertia)))
           ;; the principal axes, columns, in the segment's Z-up frame
           :principal (mm C Q)
           :moments (vec (if box?
                           (box-moments mass (shape-points shape) (or (:margin shape) 0.0))
                           (:moments inertia)))
           :static? (zero? (double mass)))))

(defn tree
  "How the segments of `plan` hang together as a tree: {:roots [id
  ...], :children {id [id ...]}, :parent {id id}, :joint {child-id
  plan-joint}, :flipped #{joint names whose first segment is the
  child}}. `root` names the root segment (default: the heaviest; a
  static segment first). An ex-info names a joint that closes a loop."
  [plan & [root]]
  (let [segs (:segments plan)
        by-id (into {} (map (juxt :id identity)) segs)
        _ (when (and root (not (by-id root)))
            (throw (ex-info (str "no segment " (pr-str root) " to be the root; the segments are "
                                 (str/join ", " (map :id segs)))
                            {:root root})))
        rank (fn [id] (let [m (double (:mass (by-id id)))]
                        [(if (= id root) 0 1) (if (zero? m) 0 1) (- m)]))
        ordered (sort-by rank (map :id segs))
        joints (:joints plan)]
    (loop [unplaced ordered
           out {:roots [] :children {} :parent {} :joint {} :flipped #{}}]
      (if-let [r (first unplaced)]
        (let [out (loop [queue [r] placed (conj (set (keys (:parent out))) r)
                         out (update out :roots conj r) used #{}]
                    (if-let [p (first queue)]
                      (let [mine (filter #(and (some #{p} (:segments %)) (not (used (:name %)))) joints)
                            [queue placed out used]
                            (reduce (fn [[queue placed out used] {[a b] :segments n :name :as j}]
                                      (let [child (if (= a p) b a)]
                                        (when (placed child)
                                          (throw (ex-info (str "joint " (pr-str n) " joins " a " and " b
                                                               ", which other joints already join: it"
                                                               " closes a loop, and MJCF and URDF"
                                                               " describe a creature as a tree")
                                                          {:joint n})))
                                        [(conj queue child) (conj placed child)
                                         (-> out
                                             (update-in [:children p] (fnil conj []) child)
                                             (assoc-in [:parent child] p)
                                             (assoc-in [:joint child] j)
                                             (cond-> (not= child b) (update :flipped conj n)))
                                         (conj used n)]))
                                    [(subvec queue 1) placed out used] mine)]
                        (recur queue placed out used))
                      (assoc out ::placed placed)))]
          (recur (remove (::placed out) unplaced) (dissoc out ::placed)))
        out))))

(defn cone-frame
  "[turn limits] of a cone of description `d`: the turn (a matrix,
  columns the engine's X, Y and Z in the joint's frame, jME's axes)
  cortex's engine limits it in, and its three limits there."
  [d]
  (let [e 1e-3
        angles (fn [axis] (first (body/cone-engine-angles
                                  d (.fromAngleAxis (Quaternion.) (float e)
                                                    (Vector3f. (float (axis 0)) (float (axis 1))
                                                               (float (axis 2)))))))
        ;; a turn e about the frame's axis k moves the engine's angles by
        ;; -e (turn^-1 e_k): row k of the turn
        rows (mapv (fn [k] (mapv #(double (Math/round (/ (- (double %)) e)))
                                 (angles (assoc [0 0 0] k 1))))
                   (range 3))
        [_ limits] (body/cone-engine-angles d (Quaternion.))]
    (when-not (= (sort (map #(Math/abs (double %)) (flatten rows))) [0.0 0.0 0.0 0.0 0.0 0.0 1.0 1.0 1.0])
      (throw (ex-info (str "cone " (pr-str d) ": its engine frame is not a turn of its own")
                      {:rows rows})))
    [rows (mapv double limits)]))

(def ^{:arglists '([v])
       :doc "Blender's [x y z] in jME's axes: cortex.strength/blender->jme."}
  blender->jme strength/blender->jme)

(defn- dofs
  "The one-axis degrees of freedom of plan joint `j` in the tree, the
  child's side first: [{:name :axis (Z-up world) :range [lo hi] :frame-axis
  k}], in the order the child hangs from them; for a point joint,
  :ball."
  [{:keys [name type description rotation]} flipped?]
  (let [E (quat->matrix rotation)]
    (case type
      :hinge (let [[lo hi] (:limit description)
                   [lo hi] (if flipped? [(- (double hi)) (- (double lo))] [(double lo) (double hi)])
                   a (blender->jme (axis-of description))]
               [{:name name :axis (z-up (mv E a)) :range [lo hi] :jme-axis (mv E a)}])
      :cone (let [[turn limits] (cone-frame description)
                  G (mm E turn)
                  order (if flipped? [0 1 2] [2 1 0])]
              (vec (for [k order
                         :let [l (nth limits k)
                               col (mapv #(nth % k) G)]]
                     {:name (str name "/" (nth ["x" "y" "z"] k))
                      :axis (z-up col) :range [(- l) l] :jme-axis col :engine-axis k
                      ;; which of the joint frame's own axes this is
                      :frame-axis (first (keep-indexed #(when-not (zero? (double %2)) %1)
                                                       (mapv #(nth % k) turn)))})))
      :point [{:name name :ball true}]
      (throw (ex-info (str "joint " (pr-str name) ": a " (clojure.core/name type)
                           " joint cannot be exported yet")
                      {:joint name :type type})))))

(def ^{:arglists '([plan])
       :doc "Each joint's muscle, by name, from `plan`: cortex.strength/plan-muscles."}
  muscles strength/plan-muscles)


(defn plan-dofs
  "Each plan joint's dofs (see `dofs`) in the tree `t`, by joint name."
  [plan {:keys [flipped]}]
  (into {} (for [j (:joints plan)] [(:name j) (dofs j (contains? flipped (:name j)))])))

(defn joint-dofs
  "How each joint of `plan` is written, by name: {:flipped? (its first
  segment is the child) :dofs [{:name (the MJCF joint) :axis (Z-up
  world) :range [lo hi] :engine-axis k (a cone's)} ...]}, or :ball."
  ([plan] (joint-dofs plan {}))
  ([plan {:keys [root]}]
   (let [{:keys [flipped] :as t} (tree plan root)]
     (into {} (for [[n ds] (plan-dofs plan t)]
                [n {:flipped? (contains? flipped n) :dofs ds}])))))

