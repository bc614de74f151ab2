;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.export.urdf
  "A creature's plan as a URDF document (see `urdf`)."
  (:require [clojure.string :as str]
            [cortex.export.geometry :refer [C axis-turn flat-notes identity3 matrix->quat mesh-files
                                            mm mv pieces quat->matrix transpose v* v+ v- z-up]]
            [cortex.export.model :refer [blender->jme muscles physics-tab? plan-dofs segment-info
                                         tab-joints tab-plan-dofs tab-segment-info tab-tree tree]]
            [cortex.export.xml :refer [text xml]]))

(set! *warn-on-reflection* true)

(defn- rpy
  "Roll, pitch, yaw (URDF's fixed X, Y, Z angles: R = Rz Ry Rx) of `m`."
  [m]
  (let [[[a _ _] [d _ _] [g h i]] m]
    [(Math/atan2 h i) (Math/asin (max -1.0 (min 1.0 (- (double g))))) (Math/atan2 d a)]))

(defn- origin
  "URDF's <origin> of a frame at `p` turned by `R` (Z-up world), seen
  from the frame [o F]."
  [[o F] p R]
  [:origin {:xyz (mv (transpose F) (v- p o)) :rpy (rpy (mm (transpose F) R))}])

(defn- urdf-geometry
  [meshes id k {:keys [type half-extents radius height axis]}]
  [:geometry
   (case type
     :mesh [:mesh {:filename (:file (meshes [id k]))}]
     :box [:box {:size (v* 2 half-extents)}]
     :sphere [:sphere {:radius radius}]
     :cylinder (let [k (or axis 1)]
                 [:cylinder {:radius (nth half-extents (if (zero? k) 1 0))
                             :length (* 2 (double (nth half-extents k)))}]))])

(defn- urdf-solids
  "The pieces URDF is given for `piece`: a capsule as its cylinder and
  the spheres at its two ends; any other piece as it is."
  [{:keys [type radius height axis pos rot] :as piece}]
  (if (= type :capsule)
    (let [k (long (or axis 1))
          h (/ (double height) 2)
          end (fn [sign] (v+ pos (mv rot (assoc [0.0 0.0 0.0] k (* sign h)))))]
      [{:type :cylinder :axis k :pos pos :rot rot
        :half-extents (assoc [(double radius) (double radius) (double radius)] k h)}
       {:type :sphere :radius radius :pos (end 1.0) :rot rot}
       {:type :sphere :radius radius :pos (end -1.0) :rot rot}])
    [piece]))

(defn- urdf-link
  "The <link> of segment `info` whose frame is `frame` [o F]."
  [{:keys [id pos R com principal moments mass friction shape static?]} meshes frame]
  [:link {:name id}
   [:inertial
    (origin frame (v+ pos (mv R com)) (mm R principal))
    [:mass {:value (double mass)}]
    (let [[a b c] moments]
      [:inertia {:ixx a :ixy 0.0 :ixz 0.0 :iyy b :iyz 0.0 :izz c}])]
   (flat-notes meshes id)
   (for [[k whole] (map-indexed vector (pieces shape))
         {:keys [type] :as piece} (urdf-solids whole)
         tag [:visual :collision]]
     (let [placed (if (= type :mesh)
                    [(:pos piece) identity3]
                    [(:pos piece) (mm (:rot piece)
                                      (if (= :cylinder type) (axis-turn (:axis piece)) identity3))])
           [pp pr] placed]
       ;; a mesh's points are already Z up; a primitive's own axes are
       ;; the segment's (jME's), turned to Z up by C, as the MJCF's geoms are
       [tag (origin frame (v+ pos (mv R (z-up pp))) (if (= type :mesh) R (mm R (mm C pr))))
        (urdf-geometry meshes id k piece)]))
   [:contact [:lateral_friction {:value (double friction)}]]])

(defn urdf
  "The URDF document (a string) of `plan`, naming the same meshes as
  `mjcf`. `opts` as for `mjcf`. An ex-info for a creature in several
  pieces (URDF is one tree)."
  ([plan] (urdf plan {}))
  ([plan {:keys [root]}]
   (let [tab? (physics-tab? plan)
         infos (into {} (map (juxt :id (if tab? tab-segment-info segment-info))) (:segments plan))
         {:keys [roots children joint] :as t} (if tab? (tab-tree plan root) (tree plan root))
         _ (when-let [[{n :name [a b] :segments}] (and tab? (seq (:loops (tab-joints plan))))]
             (throw (ex-info (str "rigid body constraint " (pr-str n) " closes a loop (" a " and " b
                                  " are already joined, by other constraints or through passive"
                                  " bodies): a URDF robot is a tree; export MJCF,"
                                  " which closes it with an equality, or remove the constraint")
                             {:object n})))
         ;; a Physics-tab creature's passive bodies that nothing hangs
         ;; from (its ground) are the world's, not the robot's
         scenery (when tab? (filter #(and (:static? (infos %)) (empty? (children %))) roots))
         roots (remove (set scenery) roots)
         _ (when (empty? roots)
             (throw (ex-info (str "creature " (:creature plan) " has no "
                                  (if tab? "body but passive ones joined to nothing" "segment")
                                  ": a URDF robot needs a link; give it a "
                                  (if tab? "rigid body that moves" "segment") ", or export MJCF")
                             {:creature (:creature plan)})))
         _ (when (next roots)
             (throw (ex-info (str "creature " (:creature plan) " is in " (count roots)
                                  " pieces (roots " (str/join ", " roots)
                                  "); a URDF robot is one tree: join the pieces, or export MJCF,"
                                  " which holds any number of free bodies")
                             {:roots roots})))
         all-dofs (if tab? (tab-plan-dofs plan t) (plan-dofs plan t))
         meshes (mesh-files plan)
         ms (if tab? {} (muscles plan))
         frame-of (fn [id] (if-let [j (joint id)]
                             [(z-up (:pivot j)) (:R (infos id))]
                             [(:pos (infos id)) (:R (infos id))]))
         tiny (fn [n] [:link {:name n}
                       [:inertial [:mass {:value 1e-6}]
                        [:inertia {:ixx 1e-9 :ixy 0.0 :ixz 0.0 :iyy 1e-9 :iyz 0.0 :izz 1e-9}]]])

         links (fn links [id]
                 (cons (urdf-link (infos id) meshes (frame-of id))
                       (mapcat links (children id))))
         joints (fn joints [parent]
                  (mapcat
                   (fn [id]
                     (let [{jn :name :keys [type rotation] :as j} (joint id)
                           [o F :as frame] (frame-of id)
                           ds (all-dofs jn)
                           ;; a Physics-tab joint has no muscle: effort 0
                           strength (or (:strength (ms jn)) 0.0)
                           ds (cond
                                (some :ball ds)
                                (for [[k b] (map-indexed vector [[1 0 0] [0 1 0] [0 0 1]])]
                                  {:name (str jn "/" (["x" "y" "z"] k)) :continuous true
                                   :axis (z-up (mv (quat->matrix rotation) (blender->jme b)))})
                                (empty? ds) [{:name jn :fixed true}]
                                (some #(and (:slide? %) (nil? (:range %))) ds)
                                (throw (ex-info (str "rigid body constraint " (pr-str jn) " leaves a"
                                                     " body free to slide without end, which a URDF"
                                                     " prismatic joint cannot say: give it limits")
                                                {:object jn}))
                                :else ds)
                           chain (concat [parent] (for [k (range 1 (count ds))] (str "_" jn "/" k)) [id])]
                       (concat
                        (when (next ds)
                          [(str "joint " jn ": a " (name type) " joint, written as " (count ds)
                                " one-axis joints through links of negligible mass (_" jn "/1, ...)"
                                (when (#{:cone :spring} type) ", in the order cortex's engine limits it")
                                (when (some :stiffness ds) "; its springs are lost: URDF has no joint spring"))])
                        (map tiny (butlast (rest chain)))
                        (for [[{:keys [name axis range continuous fixed slide?]} [p c]]
                              (map vector ds (partition 2 1 chain))
                              :let [continuous (or continuous (and (not slide?) (nil? range)))]]
                          [:joint {:name name :type (cond fixed "fixed" slide? "prismatic"
                                                          continuous "continuous" :else "revolute")}
                           [:parent {:link p}] [:child {:link c}]
                           (if (= p parent)
                             (origin (frame-of parent) o F)
                             [:origin {:xyz [0.0 0.0 0.0] :rpy [0.0 0.0 0.0]}])
                           (when-not fixed [:axis {:xyz (mv (transpose F) axis)}])
                           (cond
                             fixed nil
                             continuous [:limit {:effort strength :velocity 100.0}]
                             :else [:limit {:lower (first range) :upper (second range)
                                            :effort strength :velocity 100.0}])])
                        (joints id))))
                   (children parent)))
         r (first roots)
         [o F] (frame-of r)]
     (xml
      [:robot {:name (:creature plan)}
       (str "written by cortex.export from the plan of creature " (:creature plan)
            ": metres, kilograms, seconds, radians; Z up; see org/export.org")
       (str "the root link " r " is placed in the world at xyz " (text o) ", quaternion [x y z w] "
            (text (matrix->quat F)))
       (when (seq scenery)
         (str "left out, passive and joined to nothing (the world's, where the loader puts it): "
              (str/join ", " scenery)))
       (links r)
       (joints r)]))))

