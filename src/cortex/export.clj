;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.export
  "A creature's plan (see cortex.plan) written for other simulators:
  MuJoCo's MJCF and URDF, with its hulls as OBJ meshes beside them.

  Entry points: `mjcf` (the MJCF document of a plan, a string), `urdf`
  (the URDF document), `meshes` (the OBJ files both name, file name to
  text), `scene` (a MuJoCo scene putting the MJCF on a floor), `write!`
  (documents and meshes into files), `tree` (which
  segment hangs from which), `joint-dofs` (how each joint is written),
  `muscles` (each joint's strength and gains, from the plan),
  `cylinders-as-meshes` (a plan for MJX). The
  geometry (`hull-faces`, `z-up`, `quat->matrix`) is
  cortex.export.geometry's."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [cortex.export.geometry :as geometry
             :refer [C axis-turn flat-notes identity3 matrix->quat mesh-files mm mv pieces
                     quat->matrix transpose v* v+ v- z-up z-up-rotation]]
            [cortex.export.model :as model :refer [blender->jme plan-dofs segment-info
                                                   shape-points]]
            [cortex.export.urdf :as urdf]
            [cortex.export.xml :refer [xml]]
            [cortex.plan :as plan]
            [cortex.segment :as segment]
            [cortex.shapes :as shapes]
            [cortex.vision :as vision])
  (:import (com.jme3.scene Node)))

(set! *warn-on-reflection* true)

(defn- with-bullet-moments
  "`plan` with each segment massed by Bullet's approximation that has no
  :moments of its own (a plan written by hand) given those the engine
  gives its shape, cortex.segment/bullet-moments, as build! would: so
  that its muscles and its inertia are the built body's."
  [plan]
  (update plan :segments
          (fn [ss]
            (mapv (fn [{:keys [inertia mass shape] :as s}]
                    (if (and (= :box (:source inertia)) (nil? (:moments inertia)))
                      (assoc-in s [:inertia :moments] (segment/bullet-moments mass shape))
                      s))
                  ss))))

(defn plan-of
  "What the writers write for `x`: a plan (see cortex.plan), its missing
  moments filled in (see `with-bullet-moments`); a creature Node, the
  plan its body was built from (at its own size, for a creature a
  simulation built larger: see cortex.sim), or, before it has a body,
  its plan now.
  An ex-info names a segment the plan holds no body for (a plan drawn up
  after body!, whose segments are only kept), or whose mass is not a
  number of kilograms."
  [x]
  (let [p (if (instance? Node x)
            (let [r (segment/record x)] (or (:plan-at-size r) (:plan r) (plan/plan x)))
            x)]
    (doseq [{:keys [id kept? shape]} (:segments p)
            :when (or kept? (nil? shape))]
      (throw (ex-info (str "segment " (pr-str id) " of " (:creature p) " has no shape or mass in"
                           " this plan: it was planned after body! had built it; export the"
                           " creature itself, (cortex.export/mjcf creature), or a plan drawn up"
                           " before body!")
                      {:creature (:creature p) :segment id})))
    (doseq [{:keys [id mass]} (:segments p)
            :when (not (and (number? mass) (<= 0.0 (double mass) Double/MAX_VALUE)))]
      (throw (ex-info (str "segment " (pr-str id) " of " (:creature p) " has mass " (pr-str mass)
                           " in this plan: give it a number of kilograms, 0 for a static segment")
                      {:creature (:creature p) :segment id :mass mass})))
    (if (model/physics-tab? p) (model/check-tab! p) (with-bullet-moments p))))

(defn ^:api urdf
  "The URDF document (a string) of `x`, a plan or a creature (see
  `plan-of`): cortex.export.urdf/urdf."
  ([x] (urdf/urdf (plan-of x)))
  ([x opts] (urdf/urdf (plan-of x) opts)))

(defn ^:api meshes
  "The OBJ files `mjcf` and `urdf` name for `x`, a plan or a creature:
  cortex.export.geometry/meshes."
  [x]
  (geometry/meshes (plan-of x)))

(def ^{:arglists '([plan] [plan root])} tree
  "How the segments of `plan` hang together: cortex.export.model/tree."
  model/tree)

(def ^{:arglists '([plan] [plan opts])} joint-dofs
  "How each joint of `plan` is written: cortex.export.model/joint-dofs."
  model/joint-dofs)

(defn ^:api muscles
  "Each joint's muscle from `x`, a plan or a creature (see `plan-of`):
  cortex.export.model/muscles."
  [x]
  (model/muscles (plan-of x)))

(defn- wxyz [m] (let [[x y z w] (matrix->quat m)] [w x y z]))

(defn- local-point
  "The Z-up world point `p` in segment `info`'s Z-up frame."
  [{:keys [pos R]} p]
  (mv (transpose R) (v- p pos)))

(defn- local-vector [{:keys [R]} v] (mv (transpose R) v))

(defn- bounds
  "[centre half-sizes] of the bounding box of `points`."
  [points]
  (let [lo (apply mapv min points) hi (apply mapv max points)]
    [(v* 0.5 (v+ lo hi)) (v* 0.5 (v- hi lo))]))

(defn- piece-geom
  "The MJCF <geom> of `piece` (see `pieces`), number `k`, of segment `info`."
  [{:keys [id friction]} meshes k {:keys [type pos rot half-extents radius height axis] :as piece}]
  (let [common {:name (str id (when (pos? k) (str "/" k))) :friction [(double friction) 0.005 0.0001]}
        placed (fn [R] {:pos (z-up pos) :quat (wxyz (mm C R))})]
    (case type
      :mesh [:geom (merge common {:type "mesh" :mesh (:file (meshes [id k]))})]
      :box [:geom (merge common (placed rot) {:type "box" :size half-extents})]
      :sphere [:geom (merge common (placed rot) {:type "sphere" :size [radius]})]
      :capsule [:geom (merge common (placed (mm rot (axis-turn axis)))
                             {:type "capsule" :size [radius (/ (double height) 2)]})]
      :cylinder (let [k (or axis 1)
                      r (nth half-extents (if (zero? k) 1 0))]
                  [:geom (merge common (placed (mm rot (axis-turn k)))
                                {:type "cylinder" :size [r (nth half-extents k)]})]))))

(defn- eye-camera
  "The MJCF <camera> of plan eye `e`, in segment `info`'s body."
  [info {:keys [name spec position rotation]}]
  (let [fov (vision/field-of-view spec)
        [w h] (:resolution spec)
        R (z-up-rotation (quat->matrix rotation))]
    [:camera (merge {:name name :pos (local-point info (z-up position))
                     :quat (wxyz (mm (transpose (:R info)) R))
                     :resolution [w h]}
                    (if (= :orthographic (:projection spec))
                      {:projection "orthographic" :fovy (:height fov)}
                      {:fovy (:y fov)}))]))

(defn- mjcf-joints
  "The <joint>s by which segment `info` hangs from its parent by plan
  joint `j`."
  [info j dofs]
  (let [pin (local-point info (z-up (:pivot j)))]
    (for [{:keys [name axis range ball slide? stiffness damping] :as d} dofs]
      (if ball
        [:joint {:name name :type "ball" :pos pin}]
        ;; an axis locked away from 0 has no range: an equality holds it
        [:joint {:name name :type (if slide? "slide" "hinge") :pos pin :axis (local-vector info axis)
                 :range (when-not (model/held-at d) range) :stiffness stiffness :damping damping}]))))

(defn- held
  "[[dof value] ...]: each one-axis dof of `all-dofs` locked at one
  value, which MuJoCo takes as a range only if its ends differ."
  [all-dofs]
  (for [[_ ds] (sort-by key all-dofs) d ds :let [v (model/held-at d)] :when v]
    [(:name d) v]))

(defn- held-equality
  "The MJCF equality that holds dof `n` at `v`, and a comment."
  [[n v]]
  (list (str "joint " n " is locked at " v ": held there by an equality")
        [:joint {:name (str n "/held") :joint1 n :polycoef [v 0.0 0.0 0.0 0.0]}]))


(defn- body-element
  "The <body> of segment `id` hung from `parent` (nil: the world), given
  the writers' `infos`, the tree's `joint` and the degrees of freedom
  `all-dofs`: its place, joints and inertial, then `contents`."
  [infos joint all-dofs id parent & contents]
  (let [{:keys [R pos com principal moments mass static?] :as info} (infos id)
        j (joint id)
        P (if parent (:R (infos parent)) identity3)]
    (into [:body {:name id
                  :pos (if parent (mv (transpose P) (v- pos (:pos (infos parent)))) pos)
                  :quat (wxyz (mm (transpose P) R))}
           (cond j (mjcf-joints info j (all-dofs (:name j)))
                 (not static?) [:freejoint {:name (str id "/free")}])
           (when-not static?
             [:inertial {:pos com :quat (wxyz principal) :mass (double mass)
                         :diaginertia moments}])]
          contents)))

(declare tab-mjcf)

(defn- marker-mjcf
  "The MJCF document of `plan`, a creature of cortex's own segments and
  joints, hung from `root` (nil: the heaviest segment), each of a cone's
  or point joint's three actuators bounded by `share` of its strength,
  its friction cone `cone` (see `mjcf`)."
  [plan root share cone]
  (let [infos (into {} (map (juxt :id segment-info)) (:segments plan))
        {:keys [roots children joint] :as t} (tree plan root)
        all-dofs (plan-dofs plan t)
        meshes (mesh-files plan)
        ms (muscles plan)
        eyes (group-by :segment (:eyes plan))
        child-of (into {} (for [[child j] joint] [(:name j) child]))
        body (fn body [id parent]
               (let [{:keys [shape] :as info} (infos id)]
                 (body-element infos joint all-dofs id parent
                               (flat-notes meshes id)
                               (map-indexed #(piece-geom info meshes %1 %2) (pieces shape))
                               (let [[c half] (bounds (map z-up (shape-points shape)))]
                                 [:site {:name (str id "/touch") :type "box" :pos c
                                         :size (mapv #(+ 0.01 (double %)) half) :rgba [0 0 0 0]}])
                               (map #(eye-camera info %) (eyes id))
                               (map #(body % id) (children id)))))]
    (xml
     [:mujoco {:model (:creature plan)}
      (str "written by cortex.export from the plan of creature " (:creature plan)
           ": metres, kilograms, seconds, radians; Z up (cortex's jME Y is Z here,"
           " its Z is -Y); see org/export.org for every mapping and what is lost")
      [:compiler {:angle "radian" :inertiafromgeom "false" :autolimits "true"}]
      [:option {:timestep (/ 1.0 240) :gravity [0.0 0.0 -9.81] :integrator "implicitfast"
                :solver "Newton" :cone cone}]
      (when (seq meshes)
        [:asset (for [[_ {:keys [file]}] (sort-by key meshes)]
                  [:mesh {:name file :file file}])])
      [:worldbody (map #(body % nil) roots)]
      (when (seq (:joints plan))
        [:contact (for [{[a b] :segments} (:joints plan)] [:exclude {:body1 a :body2 b}])])
      (when-let [hs (seq (held all-dofs))]
        [:equality (map held-equality hs)])
      [:actuator
       (for [{:keys [name rotation]} (:joints plan)
             :let [{:keys [strength kp kd]} (ms name)]
             {dof :name :keys [ball frame-axis] :as d} (all-dofs name)]
         (if ball
           ;; a ball joint's servo acts about an axis of its body's
           ;; frame, the joint frame's (Blender's X, Y, Z) there; its
           ;; length is the rotation vector's part along that axis
           (for [[k axis b] [[0 "x" [1 0 0]] [1 "y" [0 1 0]] [2 "z" [0 0 1]]]]
             [:position {:name (str "muscle/" dof "/" axis) :joint dof
                         :gear (concat (local-vector (infos (child-of name))
                                                     (z-up (mv (quat->matrix rotation) (blender->jme b))))
                                       [0 0 0])
                         :kp (nth kp k) :kv (nth kd k)
                         :forcerange [(- (share strength)) (share strength)]
                         :ctrlrange [(- Math/PI) Math/PI]}])
           (let [f (if frame-axis (share strength) strength)]
             [:position {:name (str "muscle/" dof) :joint dof
                         :kp (if frame-axis (nth kp frame-axis) kp)
                         :kv (if frame-axis (nth kd frame-axis) kd)
                         :forcerange [(- f) f]
                         :ctrlrange (when-not (model/held-at d) (:range d))}])))]
      [:sensor
       (for [{:keys [name]} (:joints plan)
             {dof :name :keys [ball]} (all-dofs name)]
         (if ball
           (list [:ballquat {:name (str "angle/" dof) :joint dof}]
                 [:ballangvel {:name (str "speed/" dof) :joint dof}])
           (list [:jointpos {:name (str "angle/" dof) :joint dof}]
                 [:jointvel {:name (str "speed/" dof) :joint dof}])))
       (for [{:keys [id]} (:segments plan)]
         [:touch {:name (str "touch/" id) :site (str id "/touch")}])]])))

(defn ^:api mjcf
  "The MJCF document (a string) of `plan` (see cortex.plan; or a creature,
  see `plan-of`), its meshes named by file (see `meshes`, written beside
  it). `opts`: :root, the segment to hang the rest from (default the
  heaviest); :cone-strength, how a cone's or point joint's strength
  bounds its three actuators: :per-axis (default) each by the strength,
  :inscribed each by the strength over sqrt 3, never more than cortex's
  bound on the whole torque (see the chapter); :friction-cone,
  MuJoCo's friction cone: :pyramidal (default) or :elliptic, Coulomb's
  own, the same in every direction (see the chapter). A Physics-tab
  creature's is `tab-mjcf`'s."
  ([plan] (mjcf plan {}))
  ([x {:keys [root cone-strength friction-cone]}]
   (let [plan (plan-of x)
         ;; both options checked here, whichever kind of creature
         share (case cone-strength
                 (nil :per-axis) double
                 :inscribed #(/ (double %) (Math/sqrt 3.0))
                 (throw (ex-info (str "cortex.export/mjcf: :cone-strength " (pr-str cone-strength)
                                      " is neither :per-axis nor :inscribed")
                                 {:cone-strength cone-strength})))
         cone (case friction-cone
                (nil :pyramidal) "pyramidal"
                :elliptic "elliptic"
                (throw (ex-info (str "cortex.export/mjcf: :friction-cone " (pr-str friction-cone)
                                     " is neither :pyramidal nor :elliptic")
                                {:friction-cone friction-cone})))]
     (if (model/physics-tab? plan)
       (tab-mjcf plan {:root root :cone cone})
       (marker-mjcf plan root share cone)))))

(defn- support-down
  "The height (jME's y) of the lowest point of primitive `piece` (see
  cortex.export.geometry/pieces) whose centre is at height `y` and whose
  rotation matrix is `R` (jME's axes): its support straight down."
  ^double [{:keys [type half-extents radius height axis]} ^double y R]
  (let [up (nth R 1)                    ; the world's up in the piece's axes
        along (fn [k] (Math/abs (double (nth up (or k 1)))))
        across (fn [k] (Math/sqrt (max 0.0 (- 1.0 (* (along k) (along k))))))]
    (case type
      :box (- y (reduce + (map #(* (Math/abs (double %1)) (double %2)) up half-extents)))
      :sphere (- y (double radius))
      :capsule (- y (* (along axis) (/ (double height) 2)) (double radius))
      :cylinder (let [k (or axis 1)]
                  (- y (* (along k) (double (nth half-extents k)))
                     (* (across k) (double (nth half-extents (if (zero? k) 1 0)))))))))

(defn- lowest
  "The height (MuJoCo's z, jME's y) of the lowest point of `plan`'s
  geoms as the MJCF writes them (a mesh's points, a flat piece's plate
  included), or 0 for a plan with no segment."
  ^double [plan]
  (let [meshes (mesh-files plan)
        low (reduce min Double/POSITIVE_INFINITY
                    (for [{:keys [id position rotation shape]} (:segments plan)
                          :let [R (quat->matrix rotation) y (double (second position))]
                          [k {:keys [type pos rot] :as piece}] (map-indexed vector (pieces shape))]
                      (if (= :mesh type)
                        (let [Rz (z-up-rotation R)]
                          (reduce min (map #(+ y (double (nth (mv Rz %) 2)))
                                           (:points (meshes [id k])))))
                        (support-down piece (+ y (double (second (mv R pos)))) (mm R rot)))))]
    (if (Double/isInfinite low) 0.0 low)))

(defn ^:api scene
  "A MuJoCo scene (MJCF, a string) in which the document `file` (the
  file name `write!` gave the MJCF of `x`, a plan or a creature: see
  `plan-of`) stands on a floor at its lowest point, under a light."
  [x ^String file]
  (let [plan (plan-of x)
        z (lowest plan)]
    (xml [:mujoco {:model (str (:creature plan) " on a floor")}
          (str "written by cortex.export: " file " on a floor at its lowest point (" z
               " m); see org/export.org")
          [:include {:file file}]
          [:asset
           [:texture {:name "scene-sky" :type "skybox" :builtin "gradient" :width 512 :height 3072
                      :rgb1 "0.62 0.76 0.92" :rgb2 "0.3 0.45 0.65"}]
           [:texture {:name "scene-floor" :type "2d" :builtin "checker" :width 256 :height 256
                      :rgb1 "0.55 0.6 0.5" :rgb2 "0.45 0.5 0.42"}]
           [:material {:name "scene-floor" :texture "scene-floor" :texrepeat "8 8"
                       :texuniform "true"}]]
          [:worldbody
           [:light {:name "scene-light" :pos "0 0 10" :dir "0 0 -1" :directional "true"}]
           [:geom {:name "scene-floor" :type "plane" :size "0 0 0.05" :pos (str "0 0 " z)
                   :material "scene-floor"}]]])))

(defn- scene-file
  "The scene's file beside the MJCF `file`: its name with -scene added."
  ^java.io.File [^java.io.File file]
  (io/file (.getParentFile (.getAbsoluteFile file))
           (str (str/replace (.getName file) #"\.xml$" "") "-scene.xml")))

(defn ^:api write!
  "Write `plan` as MJCF to `mjcf-path` and/or URDF to `urdf-path` (nil
  for neither), each with its meshes beside it. `opts` as for `mjcf`,
  and :scene (true: also `scene`'s document beside the MJCF, named as
  it is with -scene added). Returns the files written."
  ([plan mjcf-path urdf-path] (write! plan mjcf-path urdf-path {}))
  ([x mjcf-path urdf-path opts]
   (let [plan (plan-of x)
         ms (meshes plan)
         written (vec (for [[path doc] [[mjcf-path mjcf] [urdf-path urdf]]
                            :when path
                            f (let [file (io/file path)
                                    dir (or (.getParentFile (.getAbsoluteFile file)) (io/file "."))]
                                (io/make-parents file)
                                (spit file (doc plan (dissoc opts :scene)))
                                (cons (str file) (for [[n t] ms]
                                                   (let [mf (io/file dir n)]
                                                     (spit mf t)
                                                     (str mf)))))]
                        f))]
     (if (and mjcf-path (:scene opts))
       (let [file (io/file mjcf-path)
             sf (scene-file file)]
         (spit sf (scene plan (.getName file)))
         (conj written (str sf)))
       written))))

(def mesh-cylinder-sides
  "The sides of the prism `cylinders-as-meshes` writes for a cylinder."
  16)

(defn- prism-hull
  "The hull shape of a prism of `mesh-cylinder-sides` sides round the
  cylinder shape `c`'s axis, its corners on the cylinder (the shapes
  chapter's prism, drawn in by nothing)."
  [c]
  {:type :hull :points (vec (shapes/prism-points c 0.0 mesh-cylinder-sides))})

(defn ^:api cylinders-as-meshes
  "`plan` (or a creature, see `plan-of`) with each cylinder shape, alone
  or in a compound, the hull of a prism round it, so that `mjcf` writes
  it as a convex mesh: for MJX, which collides a cylinder with few
  shapes. Masses and inertias stay the plan's."
  [x]
  (let [cyl (fn cyl [shape]
              (case (:type shape)
                :cylinder (prism-hull shape)
                :compound (update shape :children (partial mapv #(update % :shape cyl)))
                shape))]
    (update (plan-of x) :segments (partial mapv #(update % :shape cyl)))))

(defn- loop-equality
  "The MJCF equality constraints that close the loop of Physics-tab
  constraint `c` between its two bodies (`infos` by id), with a comment
  saying what is lost; an ex-info naming a constraint that cannot."
  [infos {:keys [name type pivot rotation segments] :as c}]
  (let [[a b] segments
        lin (model/axis-limits c "lin")
        ang (model/axis-limits c "ang")
        six? (#{"GENERIC" "GENERIC_SPRING"} type)
        pin (z-up pivot)
        connect (fn [n p] [:connect {:name n :body1 a :body2 b :anchor (local-point (infos a) p)}])]
    (cond
      (or (= "FIXED" type) (and six? (every? #{:locked} (concat lin ang))))
      (list (str "constraint " name " closes a loop: a weld") [:weld {:name name :body1 a :body2 b}])
      (or (= "POINT" type) (and six? (every? #{:locked} lin)))
      (list (str "constraint " name " closes a loop: a connect at its pivot"
                 (when six? ", its angular limits lost"))
            (connect name pin))
      (= "HINGE" type)
      (let [z (mapv #(nth % 2) (z-up-rotation (quat->matrix rotation)))]
        (list (str "constraint " name " closes a loop: two connects on its axis, its limits lost")
              (connect name pin) (connect (str name "/axis") (v+ pin (v* 0.1 z)))))
      :else
      (throw (ex-info (str "rigid body constraint " (pr-str name) " (" type ") closes a loop: "
                           (str/join ", " segments) " are already joined, and MJCF can close a"
                           " loop only with a weld (FIXED), a connect (POINT, or GENERIC with"
                           " its linear axes locked) or two (HINGE); lock its linear axes, or"
                           " join the bodies as a tree")
                      {:object name :type type})))))

(defn- tab-mjcf
  "The MJCF document of Physics-tab `plan`, its friction cone `cone`
  (see `mjcf`)."
  [plan {:keys [root cone]}]
  (let [infos (into {} (map (juxt :id model/tab-segment-info)) (:segments plan))
        {:keys [loops skipped]} (model/tab-joints plan)
        {:keys [roots children joint] :as t} (model/tab-tree plan root)
        all-dofs (model/tab-plan-dofs plan t)
        meshes (mesh-files plan)
        body (fn body [id parent]
               (let [{:keys [shape collision-groups] :as info} (infos id)]
                 (body-element infos joint all-dofs id parent
                               (flat-notes meshes id)
                               (map-indexed (fn [k piece]
                                              (cond-> (piece-geom info meshes k piece)
                                                collision-groups (update 1 assoc :contype collision-groups
                                                                         :conaffinity collision-groups)))
                                            (pieces shape))
                               (map #(body % id) (children id)))))
        held (held all-dofs)
        world (:world plan)
        step (double (or (:step world) (/ 1.0 240)))
        ;; a constraint left out for freeing every axis still keeps its
        ;; bodies apart in Bullet, if it says so
        excluded (for [{:keys [segments settings enabled?]} (concat (vals joint) loops (map first skipped))
                       :when (and enabled? (:disable-collisions settings)
                                  (not-every? (comp :static? infos) segments))]
                   segments)]
    (xml
     [:mujoco {:model (:creature plan)}
      (str "written by cortex.export from the plan of Physics-tab creature " (:creature plan)
           ": metres, kilograms, seconds, radians; Z up (cortex's jME Y is Z here,"
           " its Z is -Y); see org/export.org for every mapping and what is lost")
      (for [[{:keys [name]} why] skipped]
        (str "constraint " name " is left out: " why))
      [:compiler {:angle "radian" :inertiafromgeom "false" :autolimits "true"}]
      ;; limits and loops as hard as MuJoCo holds steadily (see the text);
      ;; a tree has no equality, and its document says nothing of one
      [:default [:joint {:solreflimit [(* 2 step) 1.0] :solimplimit [0.99 0.999 0.001]}]
       (when (or (seq loops) (seq held))
         [:equality {:solref [(* 2 step) 1.0] :solimp [0.99 0.999 0.001]}])]
      [:option {:timestep step
                :gravity (z-up (or (:gravity world) [0.0 -9.81 0.0]))
                :integrator "implicitfast" :solver "Newton" :cone cone}
       [:flag {:filterparent "disable"}]]
      (when (seq meshes)
        [:asset (for [[_ {:keys [file]}] (sort-by key meshes)]
                  [:mesh {:name file :file file}])])
      [:worldbody (map #(body % nil) roots)]
      (when (seq excluded)
        [:contact (for [[a b] excluded] [:exclude {:body1 a :body2 b}])])
      (when (or (seq loops) (seq held))
        [:equality (map #(loop-equality infos %) loops) (map held-equality held)])])))
