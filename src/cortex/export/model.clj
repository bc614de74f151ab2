;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.export.model
  "A creature's plan as the exporters see it: each segment's Z-up frame
  and inertia (`segment-info`), which segment hangs from which
  (`tree`), each joint as one-axis degrees of freedom (`joint-dofs`,
  `cone-frame`), and each joint's muscle from the plan (`muscles`)."
  (:require [clojure.string :as str]
            [cortex.body :as body]
            [cortex.constraint :as constraint]
            [cortex.engine :as engine]
            [cortex.export.geometry :refer [C dot identity3 mm mv norm quat->matrix
                                            v+ v- v* z-up z-up-rotation]]
            [cortex.rigid-body :as rigid-body]
            [cortex.segment :as segment]
            [cortex.strength :as strength :refer [axis-of]])
  (:import (com.jme3.bullet.collision.shapes CollisionShape)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Quaternion Vector3f)))

(set! *warn-on-reflection* true)

(def ^{:arglists '([shape])
       :doc "The points that bound `shape`: cortex.strength/shape-points."}
  shape-points strength/shape-points)

(defn segment-info
  "What the writers need of plan segment `s`; a segment with Bullet's
  approximation of inertia has the plan's moments, or without them those
  `bullet` gives it (by default cortex.segment/bullet-moments of its
  mass and shape)."
  ([s] (segment-info s (fn [{:keys [mass shape]}] (segment/bullet-moments mass shape))))
  ([{:keys [mass position rotation inertia] :as s} bullet]
   (let [R (z-up-rotation (quat->matrix rotation))
         box? (= :box (:source inertia))
         Q (if box? identity3 (quat->matrix (:rotation inertia)))]
     (assoc s
            :pos (z-up position) :R R
            :com (if box? [0.0 0.0 0.0] (z-up (:centre inertia)))
            ;; the principal axes, columns, in the segment's Z-up frame
            :principal (mm C Q)
            :moments (vec (or (:moments inertia) (bullet s)))
            :static? (zero? (double mass))))))

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
  cortex's engine limits it in, and its three limits there; a spring
  joint's description is read with its defaults (cortex.body/spring-fields)."
  [d]
  (let [d (if (= :spring (:type d)) (merge d (body/spring-fields d)) d)
        e 1e-3
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
  k}], in the order the child hangs from them, a spring joint's each
  with its :stiffness and :damping; for a point joint, :ball."
  [{:keys [name type description rotation]} flipped?]
  (let [E (quat->matrix rotation)
        cone (fn [d]
               (let [[turn limits] (cone-frame d)
                     G (mm E turn)
                     order (if flipped? [0 1 2] [2 1 0])]
                 (vec (for [k order
                            :let [l (nth limits k)
                                  col (mapv #(nth % k) G)]]
                        {:name (str name "/" (nth ["x" "y" "z"] k))
                         :axis (z-up col) :range [(- l) l] :jme-axis col :engine-axis k
                         ;; which of the joint frame's own axes this is
                         :frame-axis (first (keep-indexed #(when-not (zero? (double %2)) %1)
                                                          (mapv #(nth % k) turn)))}))))]
    (case type
      :hinge (let [[lo hi] (:limit description)
                   [lo hi] (if flipped? [(- (double hi)) (- (double lo))] [(double lo) (double hi)])
                   a (blender->jme (axis-of description))]
               [{:name name :axis (z-up (mv E a)) :range [lo hi] :jme-axis (mv E a)}])
      :cone (cone description)
      :spring (let [{:keys [stiffness damping]} (body/spring-fields description)]
                (mapv #(assoc % :stiffness stiffness :damping damping) (cone description)))
      :point [{:name name :ball true}]
      (throw (ex-info (str "joint " (pr-str name) ": a " (clojure.core/name type) " joint (a type"
                           " added through cortex.body/joint-dispatch) cannot be written: the"
                           " exporters know :hinge, :cone, :spring and :point joints; describe it"
                           " as one of those to export the creature")
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


(defn physics-tab?
  "Whether `plan` is a creature of Blender's Physics tab: its segments
  are rigid bodies (see cortex.physics-tab)."
  [plan]
  (boolean (some #(= :rigid-body (:kind %)) (:segments plan))))

(defn- refuse
  [what name msg data]
  (throw (ex-info (str what " " (pr-str name) ": " msg) (assoc data :object name))))

(defn check-tab!
  "`plan`, a Physics-tab plan, when MJCF and URDF can say it; else an
  ex-info naming the body or constraint and what to change."
  [plan]
  (when (seq (:joints plan))
    (throw (ex-info (str "creature " (:creature plan) " has both cortex's joints ("
                         (str/join ", " (map :name (:joints plan))) ") and the Physics tab's"
                         " rigid bodies: export it planned as one or the other"
                         " (cortex.plan/plan's :physics-tab?)")
                    {:creature (:creature plan)})))
  (doseq [{:keys [id kind mass shape empty?]} (:segments plan)]
    (when (not= :rigid-body kind)
      (refuse "segment" id (str "is cortex's own segment in a Physics-tab creature: export it"
                                " planned as one or the other (cortex.plan/plan's :physics-tab?)")
              {}))
    (when (= :mesh (:type shape))
      (refuse "rigid body" id (str "has a MESH collision shape, whose triangles the plan does not"
                                   " hold and which MuJoCo would collide as its convex hull: set its"
                                   " Shape to Convex Hull (or Box) in the Physics tab")
              {:shape :mesh}))
    (when (and empty? (pos? (double mass)))
      (refuse "rigid body" id (str "is a mesh without vertices: Bullet gives it no moment of"
                                   " inertia (it never turns), which MJCF and URDF cannot say;"
                                   " give it a mesh, or make it Passive")
              {})))
  plan)

(defn rigid-body-moments
  "The principal moments (the body's own axes, jME's, about its origin)
  that Bullet gives the rigid body of plan segment `s`: its shape's
  inertia for its mass, asked of cortex's engine."
  [{:keys [mass shape]}]
  (let [c (RigidBodyControl. ^CollisionShape (rigid-body/shape-of shape nil) (float mass))]
    (mapv #(/ 1.0 (double %)) (engine/inverse-inertia (engine/rigid-body c)))))

(defn tab-segment-info
  "What the writers need of Physics-tab plan segment `s` (see
  `segment-info`): its centre of mass at its origin, its principal axes
  its own, its moments Bullet's (`rigid-body-moments`)."
  [s]
  (segment-info (assoc s :inertia {:source :box})
                #(if (zero? (double (:mass %))) [0.0 0.0 0.0] (rigid-body-moments %))))

(defn axis-limits
  "Constraint `c`'s limits of `kind` (\"lin\" or \"ang\") on its X, Y
  and Z: :locked (at 0), [lo hi] (lo = hi for an axis locked away from
  0, which Bullet pushes there), or nil (free: no limit, or the lower
  above the upper, which Bullet frees)."
  [{:keys [settings name]} kind]
  (mapv (fn [l]
          (when l
            (let [[lo hi] (mapv double l)]
              (cond (> lo hi) nil
                    (and (== lo hi) (zero? lo)) :locked
                    :else [lo hi]))))
        (constraint/limits name settings kind)))

(defn- sprung?
  "Whether constraint `c` is a GENERIC_SPRING with a spring on any axis
  (Bullet gives a GENERIC none, whatever its settings say)."
  [{:keys [type settings]}]
  (boolean (and (= "GENERIC_SPRING" type)
                (some #(get settings (keyword (str "use-spring-" %))) ["x" "y" "z" "ang-x" "ang-y" "ang-z"]))))

(defn held-at
  "The value a one-axis dof of `tab-dofs` is locked at away from 0
  (its range's ends equal), or nil."
  [{[lo hi] :range}]
  (when (and lo (== (double lo) (double hi))) (double lo)))

(defn tab-joints
  "How the constraints of Physics-tab `plan` join its bodies, in the
  plan's order: {:joints [constraint ...] (a tree), :loops [constraint
  ...] (each joins two bodies already joined, passive bodies being one
  with the world), :skipped [[constraint why] ...]}. An ex-info names a
  MOTOR whose motor is on."
  [plan]
  (let [static (set (keep #(when (zero? (double (:mass %))) (:id %)) (:segments plan)))
        root-of (fn [m x] (let [p (get m x x)] (if (= p x) x (recur m p))))]
    (loop [cs (:constraints plan)
           m (zipmap static (repeat ::world))
           out {:joints [] :loops [] :skipped []}]
      (if-let [{:keys [name type enabled? segments settings] :as c} (first cs)]
        (let [[a b] segments
              why (cond (not enabled?) "it is disabled in Blender"
                        (every? static segments) "both its bodies are passive"
                        (= "MOTOR" type)
                        (if (or (:use-motor-ang settings) (:use-motor-lin settings))
                          (refuse "rigid body constraint" name
                                  (str "is a MOTOR, which neither MJCF nor URDF can say (a motor"
                                       " that drives two bodies towards a relative speed); join its"
                                       " bodies with another constraint and drive them some other"
                                       " way, or turn its motor off")
                                  {:type type})
                          "a MOTOR with its motors off frees every axis")
                        (and (#{"GENERIC" "GENERIC_SPRING"} type)
                             (every? nil? (concat (axis-limits c "lin") (axis-limits c "ang")))
                             (not (sprung? c)))
                        (str "a " type " that limits no axis frees every axis"))
              ra (root-of m a)
              rb (root-of m b)]
          (cond why (recur (rest cs) m (update out :skipped conj [c why]))
                (= ra rb) (recur (rest cs) m (update out :loops conj c))
                :else (recur (rest cs) (if (= rb ::world) (assoc m ra rb) (assoc m rb ra))
                             (update out :joints conj c))))
        out))))

(defn tab-tree
  "The tree (see `tree`) of Physics-tab `plan`'s bodies, joined by the
  constraints `tab-joints` puts in it; `root` as for `tree`."
  [plan & [root]]
  (tree (assoc plan :joints (:joints (tab-joints plan))) root))

(defn tab-dofs
  "The one-axis degrees of freedom (see `dofs`) of Physics-tab
  constraint `c`, the child's side first when `flipped?` (its first
  body is the child): [{:name :axis (Z-up world) :range [lo hi] or nil
  :slide? :stiffness :damping}], or [{:name :ball true}]; [] welds."
  [{:keys [name type settings rotation] :as c} flipped?]
  (let [F (z-up-rotation (quat->matrix rotation))
        spring (fn [kind k]
                 (let [suffix (str (when (= kind "ang") "ang-") (["x" "y" "z"] k))]
                   (when (and (= "GENERIC_SPRING" type)
                              (get settings (keyword (str "use-spring-" suffix))))
                     {:stiffness (double (get settings (keyword (str "spring-stiffness-" suffix))))
                      :damping (double (get settings (keyword (str "spring-damping-" suffix))))})))
        one (fn [n kind k lim negate?]
              (when-not (= :locked lim)
                (merge {:name n :axis (mapv #(nth % k) F) :slide? (= kind "lin")
                        :range (when-let [[lo hi] lim] (if negate? [(- hi) (- lo)] [lo hi]))}
                       (spring kind k))))
        sub (fn [kind k] (str name "/" (when (= kind "lin") "slide-") (["x" "y" "z"] k)))]
    (vec
     (remove nil?
             (case type
               "FIXED" []
               "POINT" [{:name name :ball true}]
               ;; Bullet's hinge angle is the first body's turn about Z
               "HINGE" [(one name "ang" 2 (nth (axis-limits c "ang") 2) (not flipped?))]
               "SLIDER" [(one name "lin" 0 (first (axis-limits c "lin")) flipped?)]
               "PISTON" [(one (sub "lin" 0) "lin" 0 (first (axis-limits c "lin")) flipped?)
                         (one (sub "ang" 0) "ang" 0 (first (axis-limits c "ang")) flipped?)]
               ("GENERIC" "GENERIC_SPRING")
               (let [lin (axis-limits c "lin")
                     ang (axis-limits c "ang")
                     slides (for [k [0 1 2]] (one (sub "lin" k) "lin" k (lin k) flipped?))
                     ;; Bullet's angles are those of the inverse relative turn
                     turns (for [k (if flipped? [0 1 2] [2 1 0])]
                             (one (sub "ang" k) "ang" k (ang k) (not flipped?)))]
                 (if flipped? (concat turns slides) (concat slides turns)))
               (refuse "rigid body constraint" name
                       (str "is of type " (pr-str type) ", which cortex cannot export") {:type type}))))))

(defn tab-plan-dofs
  "Each tree constraint's dofs (see `tab-dofs`) in the tree `t` of
  Physics-tab `plan`, by constraint name."
  [plan {:keys [flipped joint]}]
  (into {} (for [c (vals joint)] [(:name c) (tab-dofs c (contains? flipped (:name c)))])))
