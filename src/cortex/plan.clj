;; Generated from org/plan.org by lein tangle: edit the chapter, not this file.
(ns cortex.plan
  "A creature as data: `plan` decides, from the scene graph alone, every
  segment, joint and eye a body will have, as plain EDN data; `build!`
  makes the rigid bodies, joints and eyes a plan says. No Bullet object
  is made by `plan`, and `build!` decides nothing.

  Entry points: `plan`, `build!`, `plan-parts` (part of a plan, as
  `cortex.body/physical!` and `joints!` make), `version`."
  (:require [clojure.string :as str]
            [cortex.constraint :as constraint]
            [cortex.joint :as joint]
            [cortex.nearest :as nearest]
            [cortex.rigid-body :as rigid-body]
            [cortex.segment :as segment]
            [cortex.sense :as sense]
            [cortex.strength :as strength]
            [cortex.util :as util]
            [cortex.vision :as vision])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.scene Geometry Node Spatial)
           (java.util IdentityHashMap)
           (java.util.concurrent ConcurrentHashMap)
           (java.util.logging Logger)))

(set! *warn-on-reflection* true)

(def version
  "The plan's format: a plan says it as :plan/version."
  1)

(defn- path-of
  "The child indices from `creature` down to `s`."
  [^Node creature ^Spatial s]
  (loop [^Spatial s s path ()]
    (if (identical? s creature)
      (vec path)
      (let [p (.getParent s)]
        (recur p (cons (long (.getChildIndex p s)) path))))))

(defn- at-path
  "The Spatial at `path` below `creature`, or nil."
  ^Spatial [^Node creature path]
  (reduce (fn [^Spatial s i]
            (if (and (instance? Node s) (integer? i) (< -1 (long i) (.getQuantity ^Node s)))
              (.getChild ^Node s (int i))
              (reduced nil)))
          creature path))

(defn- ids
  "A unique id for each of `geoms`: its segment name, or, where several
  share one, name/geometry-name (and #2, #3... after that)."
  [geoms]
  (let [counts (frequencies (map segment/segment-name geoms))]
    (loop [[^Geometry g & more] geoms seen #{} out []]
      (if-not g
        out
        (let [n (segment/segment-name g)
              base (if (= 1 (counts n)) n (str n "/" (.getName g)))
              id (loop [k 2 id base] (if (seen id) (recur (inc k) (str base "#" k)) id))]
          (recur more (conj seen id) (conj out id)))))))

(defn- tab-shape
  "The shape the Physics tab gives segment `g` of a creature built with
  joint markers, as data: its object's rigid body Shape (Blender's
  rule for its size), when the object has a rigid body, `g` is its only
  Geometry and the shape is one cortex's segments take (box, sphere,
  capsule, cylinder, convex hull); else nil."
  [^Geometry g]
  (let [node (.getParent g)
        rb (when (instance? Node node) (rigid-body/rigid-body node))]
    (when (and rb (identical? g (rigid-body/body-spatial node)))
      (let [{:keys [shape empty?]} (rigid-body/shape-plan node rb (= "PASSIVE" (:type rb)))]
        (when (and (not empty?) (#{:box :sphere :capsule :cylinder :hull} (:type shape)))
          shape)))))

(defn- plan-segments
  "The plan of each of `geoms` (with `ids`): a segment that already has
  a rigid body is recorded as kept. Unless `opts` ask for the seed's
  hulls, a segment whose object has a Physics-tab rigid body takes its
  Shape (see `tab-shape`)."
  [^Node creature geoms ids opts]
  (mapv (fn [^Geometry g id]
          (merge {:id id :path (path-of creature g)}
                 (if (.getControl g RigidBodyControl)
                   {:name (segment/segment-name g) :kept? true}
                   (assoc (segment/in-creature
                           creature
                           #(segment/plan-segment g opts (when (not= :hull (:shapes opts))
                                                           (tab-shape g))))
                          :kept? false))))
        geoms ids))

(defn- modifier-warnings
  "A warning for each segment of `creature` whose object shows modifiers
  the reader did not apply (see cortex.sense/modifiers-key)."
  [^Node creature]
  (vec (for [^Geometry g (segment/segments creature)
             :let [ms (sense/meta-data g sense/modifiers-key)]
             :when (seq ms)
             :let [name (segment/segment-name g)]]
         {:kind :modifiers :segment name :modifiers (vec ms) :warning? true
          :message (str "segment " (pr-str name) " is built without its modifiers or shape keys ("
                        (sense/modifiers-text ms)
                        "), which is not the shape Blender shows;"
                        " apply them in Blender (Object > Convert > Mesh) to build that")})))

(defn- mass-warnings
  "A warning for each of the planned `segments` that moves and is massed
  by Bullet's box for want of a closed mesh, unless `opts` ask for that
  everywhere."
  [segments opts]
  (vec (for [{:keys [id mass inertia]} segments
             :when (and (= :box (:source inertia)) (pos? (double mass))
                        (not= :box (:mass-properties opts)))]
         {:kind :mass-properties :segment id :warning? true
          :message (str "segment " (pr-str id) " encloses no volume (its mesh is open, or flat),"
                        " so its centre of mass and inertia are Bullet's guess, a box round its"
                        " shape at its origin (moments " (str/join " " (map #(format "%.4g" (double %))
                                                                              (:moments inertia)))
                        "); close its mesh, or give it a thickness, to have them from the mesh")})))

(defn- faceless-meshes
  "The names of `creature`'s mesh objects that hold no Geometry: meshes
  with no faces, which are no segment."
  [^Node creature]
  (sort (for [n (util/node-seq creature)
              :when (and (instance? Node n) (= "MESH" (.getUserData ^Node n "blender-type"))
                         (not-any? #(instance? Geometry %) (.getChildren ^Node n)))]
          (.getName ^Node n))))

(defn- with-faceless-note
  "`f`'s value; when it throws that a joint found too few segments, the
  error says which of `creature`'s meshes are no segment."
  [creature f]
  (try (f)
       (catch clojure.lang.ExceptionInfo e
         (let [none (faceless-meshes creature)]
           (if (and (:found (ex-data e)) (seq none))
             (throw (ex-info (str (ex-message e) "; " (str/join ", " none)
                                  (if (next none) " are meshes" " is a mesh")
                                  " with no faces (edges or points only), which is no segment:"
                                  " give it faces, or delete it")
                             (assoc (ex-data e) :faceless none) e))
             (throw e))))))

(defn- measure-joint
  "Where joint empty `marker` is and which segments it is nearest."
  [index tol ^Spatial marker]
  (segment/check-placement! "joint" marker)
  (let [measured (nearest/nearest-segments index marker tol)
        pair (vec (nearest/ordered-pair marker (map :geom (take 2 measured))))]
    {:marker marker :name (.getName marker) :measured measured :geoms pair
     :point (let [p (.getWorldTranslation marker)] [(.x p) (.y p) (.z p)])
     :segments (mapv segment/segment-name pair)}))

(defn- doubts-error
  [^Node creature doubts]
  (ex-info (str (segment/label creature) ": " (count doubts)
                (if (= 1 (count doubts)) " doubt" " doubts")
                " about its joints:\n"
                (str/join "\n" (map #(str "- " (:message %)) doubts))
                (str/join (map #(str "\n(note: " (:message %) ")") (modifier-warnings creature)))
                "\n(to build it anyway, (body! creature {:strict? false}))")
           {:creature (.getName creature) :doubts doubts}))

(defn- plan-joints
  "{:joints :doubts :warnings} for the joints of `creature`, found in
  `index` with the ambiguity window `tol`; `id-of` names a Geometry's
  segment. With :strict? any doubt is an error listing them all; with
  :tolerance given, `tol` is the whole window (see joint-doubts)."
  [^Node creature index tol id-of {:keys [strict? tolerance]}]
  (let [given? (some? tolerance)
        found (mapv #(segment/in-creature creature
                                          (fn [] (with-faceless-note creature (fn [] (measure-joint index tol %)))))
                    (nearest/joints creature))
        naming (nearest/naming-doubts creature)
        doubts (vec (concat (remove :warning? naming)
                            (mapcat #(nearest/joint-doubts (:name %) (:measured %) tol given? (:point %)) found)
                            (nearest/duplicate-doubts (map (juxt :name :segments) found))))]
    (when (and strict? (seq doubts))
      (throw (doubts-error creature doubts)))
    (let [joints (mapv (fn [{:keys [^Spatial marker name measured geoms]}]
                         (let [d (segment/in-creature creature #(joint/joint-description marker))]
                           {:name name :kind :marker :type (:type d)
                            :segments (mapv id-of geoms)
                            :description (joint/description-data d)
                            :pivot (segment/vector-data (.getWorldTranslation marker))
                            :rotation (segment/quaternion-data (.getWorldRotation marker))
                            :distances (into {} (for [{n :name dd :distance} (take 2 measured)]
                                                  [n (double dd)]))}))
                       found)
          joined (set (map #(set (:geoms %)) found))]
      {:joints joints
       :doubts doubts
       :warnings (vec (concat (map #(assoc % :relaxed? true) doubts)
                              (filter :warning? naming)
                              (nearest/overlap-warnings index joined)
                              (nearest/limit-warnings joints)))})))

(defn- members
  "Of `nodes`, those whose names are in `names` and those that are not,
  or all of them when `names` is nil (no collection to go by) or `all?`."
  [nodes names all?]
  (if (or all? (nil? names))
    [nodes []]
    (let [in (set names)]
      [(filter #(in (.getName ^Spatial %)) nodes) (remove #(in (.getName ^Spatial %)) nodes)])))

(defn- names-of [nodes] (mapv #(.getName ^Spatial %) nodes))

(defn- tab-warning [message] {:kind :physics-tab :warning? true :message message})

(defn- plan-tab
  "The Physics-tab part of the plan of `creature`: {:bodies (segment
  plans, :kind :rigid-body) :spatials (the Spatials their bodies go on)
  :constraints :world :joint-order :warnings}."
  [^Node creature {:keys [all-rigid-bodies? simulation?] :or {simulation? true}}]
  (let [world (constraint/world-settings creature)
        [body-nodes left] (members (rigid-body/rigid-body-objects creature)
                                   (:collection-objects world) all-rigid-bodies?)
        [con-nodes con-left] (members (rigid-body/constraint-objects creature)
                                      (:constraint-objects world) all-rigid-bodies?)
        spatials (mapv rigid-body/body-spatial body-nodes)
        bodies (mapv (fn [^Node n ^Spatial s]
                       (assoc (rigid-body/plan-rigid-body n)
                              :id (.getName n) :path (path-of creature s)
                              ;; where its body is made: the Spatial's world transform
                              :position (segment/vector-data (.getWorldTranslation s))
                              :rotation (segment/quaternion-data (.getWorldRotation s))
                              :scale (segment/vector-data (.getWorldScale s))))
                     body-nodes spatials)
        by-name (into {} (map (juxt :name identity)) bodies)
        excluded (set (names-of left))
        out? #(some excluded ((juxt :ob1 :ob2) (rigid-body/rigid-body-constraint %)))
        skipped (filter out? con-nodes)
        constraints (mapv #(constraint/plan-constraint % by-name) (remove out? con-nodes))
        settings (when simulation? (constraint/simulation-settings world))]
    {:bodies bodies
     :spatials spatials
     :constraints constraints
     :world settings
     :joint-order (:constraint-objects world)
     :warnings
     (mapv tab-warning
           (concat
            (when (seq left)
              [(str "rigid bodies " (pr-str (names-of left)) " are not in the Rigid Body"
                    " World's collection: Blender does not simulate them, and they are"
                    " not built ({:all-rigid-bodies? true} builds them)")])
            (when (seq con-left)
              [(str "rigid body constraints " (pr-str (names-of con-left)) " are not in"
                    " the Rigid Body World's constraints collection: not built")])
            (when (seq skipped)
              [(str "rigid body constraints " (pr-str (names-of skipped)) " join bodies"
                    " that are not built: not built")])
            (when (and settings (> (double (:time-scale settings)) 1.0))
              [(str "the Rigid Body World's time scale is " (:time-scale settings)
                    ": a cortex world steps at most 1/60 s of physics a frame; set its"
                    " BulletAppState's speed to the time scale to follow it")])
            (mapcat :warnings bodies) (mapcat :warnings constraints)))}))

(defn- identity-lookup
  "A function from each of `ks` (by identity) to its `vs`."
  [ks vs]
  (let [m (IdentityHashMap.)]
    (doseq [[k v] (map vector ks vs)] (.put m k v))
    (fn [k] (.get m k))))

(defn- with-muscles
  "`p` with each joint's muscle, {:strength :kp :kd} (a cone's or point
  joint's gains per axis of its frame, jME's order), as cortex.muscle
  will work it out from the built bodies (see cortex.strength): the
  description's own where it gives them. A joint with a segment the
  plan keeps, or one of the Physics tab's, has none here: its mass
  properties are not the plan's."
  [p]
  (let [segments (filterv :inertia (:segments p))
        planned (set (map :id segments))
        sized (filterv #(every? planned (:segments %)) (:joints p))
        ms (if (seq sized) (strength/plan-muscles (assoc p :segments segments :joints sized)) {})]
    (update p :joints (fn [js] (mapv #(if-let [m (ms (:name %))] (assoc % :muscle m) %) js)))))

(defn plan-parts
  "The plan of `creature` (see `plan`) for `parts`, a set of :segments,
  :joints and :eyes. Without :segments, the plan holds the segments
  that already have a rigid body (kept), and the joints and eyes are
  found among them, as `cortex.body/joints!` does. With :physics-tab?
  in `opts`, the Physics tab's bodies and constraints come first (see
  `plan-tab`), and cortex's own segments, joints and eyes follow only
  when the creature has a joints empty."
  [^Node creature opts parts]
  (let [opts (merge segment/default-options opts)
        tab? (:physics-tab? opts)]
    (.updateGeometricState creature)
    (let [tab (when tab? (plan-tab creature opts))
          taken (identity-lookup (:spatials tab) (:bodies tab))
          parts (if (and tab? (empty? (nearest/joints creature))) #{} parts)
          all (vec (segment/segments creature))
          free (remove taken all)
          geoms (vec (if (:segments parts) free (filter nearest/physical? free)))
          ids (ids geoms)
          planned (identity-lookup geoms ids)
          id-of (fn [g] (or (:id (taken g)) (planned g)))
          segments (plan-segments creature geoms ids opts)
          index (nearest/index-of (filter #(or (taken %) (planned %)) all))
          tol (double (or (:tolerance opts) (nearest/tolerance index)))
          js (when (:joints parts) (plan-joints creature index tol id-of opts))
          eyes (when (and (:eyes parts) (instance? Node (.getChild creature "eyes")))
                 (vision/plan-eyes creature index tol id-of))]
      ;; segments, joints, eyes and constraints are plain data as they
      ;; are made; what is gathered from elsewhere is made so here
      (cond-> (with-muscles
               {:plan/version version
               :creature (.getName creature)
               :parts (vec (sort (cond-> parts tab? (conj :physics-tab))))
               :options (segment/plain opts)
               :tolerance tol
               :segments (into (vec (:bodies tab)) segments)
               :joints (:joints js [])
               :eyes (or eyes [])
               :doubts (segment/plain (:doubts js []))
               :warnings (segment/plain (-> (modifier-warnings creature)
                                              (into (mass-warnings segments opts))
                                              (into (:warnings js []))
                                              (into (:warnings tab))))})
        tab? (assoc :constraints (:constraints tab)
                    :world (segment/plain (:world tab))
                    :joint-order (vec (:joint-order tab)))))))
(defn ^:api plan
  "What `body!` would make of `creature` (a Node loaded from Blender, or
  built in code the same way), as plain data: every segment, joint and
  eye, and the doubts and warnings, decided from the scene graph alone
  (see the chapter for the shape). `opts` as cortex.body/body!'s (see
  cortex.segment/default-options), and cortex.physics-tab/build!'s
  (:all-rigid-bodies?, :simulation?); :physics-tab? says whether the
  Physics tab's rigid bodies and constraints are planned, by default
  when the creature has any. Errors are those body! gives, naming the
  creature and the segment, joint or eye at fault; with :strict? (the
  default) a doubt about any joint is one."
  ([creature] (plan creature {}))
  ([^Node creature opts]
   (let [tab? (if (contains? opts :physics-tab?)
                (:physics-tab? opts)
                (boolean (seq (rigid-body/rigid-body-objects creature))))]
     (plan-parts creature (assoc opts :physics-tab? tab?) #{:segments :joints :eyes}))))

(defn- segment-at
  "The Geometry planned segment `p` names in `creature`."
  ^Geometry [^Node creature {:keys [id name path]}]
  (let [s (at-path creature path)]
    (if (and (instance? Geometry s) (= name (segment/segment-name s)))
      s
      (throw (ex-info (str (segment/label creature) ": the plan's segment " (pr-str id)
                           " is not where the plan says (" (pr-str path) " holds "
                           (if s (pr-str (.getName s)) "nothing")
                           "); make the plan from this creature")
                      {:creature (.getName creature) :segment id :path path})))))

(defn- joint-record
  "What is kept of joint `j` of a plan, made as `physics-joint` between
  built segments `a` and `b`."
  [j physics-joint a b]
  (let [{:keys [name type description pivot rotation distances]} j]
    {:name name :type type :description description
     :physics-joint physics-joint :geoms [(:geom a) (:geom b)]
     :segments [(segment/segment-name (:geom a)) (segment/segment-name (:geom b))]
     :pivot pivot :rotation rotation
     :body-rotations (mapv #(segment/quaternion-data
                             (.getPhysicsRotation ^RigidBodyControl (:control %)))
                           [a b])
     :distances distances}))

(defn- log-warnings!
  [^Node creature warnings]
  (let [logger (Logger/getLogger "cortex.body")
        tab-logger (Logger/getLogger "cortex.physics-tab")]
    (doseq [{:keys [kind ^String message]} warnings]
      (if (= :physics-tab kind)
        (.warning tab-logger message)
        (.warning logger (str (segment/label creature) ": " message))))))

(defn- build-rigid-body
  "The rigid body of planned Physics-tab body `p`, made or kept."
  [^Node creature {:keys [id name path kept?] :as p}]
  (let [s (at-path creature path)
        node (cond (instance? Node s) s s (.getParent s))]
    (when-not (and node (= name (.getName ^Spatial node)))
      (throw (ex-info (str (segment/label creature) ": the plan's rigid body " (pr-str id)
                           " is not where the plan says (" (pr-str path) "); make the plan"
                           " from this creature")
                      {:creature (.getName creature) :segment id :path path})))
    (let [c (if kept?
              (.getControl s RigidBodyControl)
              (rigid-body/build-rigid-body! s node p))]
      {:id id :geom s :spatial s :control c :rigid-body? true
       :report {:object name :control c :spatial s :shape (:blender-shape p)
                :mass (if kept? (.getMass ^RigidBodyControl c) (:mass p))
                :warnings (:warnings p)}})))

(defn- merged
  "The record of a creature that held `old`, after building `plan`,
  whose pieces are `built`: the plan's parts (see `plan-parts`) replace
  what the record held of them; segments add up."
  [old plan built]
  (let [parts (set (:parts plan))
        old-plan (:plan old)
        old-built (:built old)
        old-ids (set (map :id (:segments old-plan)))
        ;; a segment kept now was planned before: keep the earlier plan of it
        segments (vec (concat (:segments old-plan)
                              (remove #(old-ids (:id %)) (:segments plan))))
        new-built (into {} (map (juxt :id identity)) (:segments built))
        old-built-ids (set (map :id (:segments old-built)))
        pick (fn [part ks] (if (or (parts part) (nil? old-plan)) (select-keys plan ks) (select-keys old-plan ks)))]
    {:plan (merge old-plan
                  (dissoc plan :joints :doubts :warnings :tolerance :eyes)
                  {:parts (vec (sort (into (set (:parts old-plan)) parts)))
                   :segments segments}
                  (pick :joints [:joints :doubts :tolerance])
                  (pick :eyes [:eyes])
                  ;; the Physics tab's warnings stay with it
                  {:warnings (let [tab? #(= :physics-tab (:kind %))]
                               (vec (concat (remove tab? (:warnings (if (or (parts :joints) (nil? old-plan))
                                                                      plan old-plan)))
                                            (filter tab? (:warnings (if (or (parts :physics-tab) (nil? old-plan))
                                                                      plan old-plan))))))})
     :built (merge
            {:segments (vec (concat (map #(new-built (:id %) %) (:segments old-built))
                                    (remove #(old-built-ids (:id %)) (:segments built))))
             :joints (if (or (parts :joints) (nil? old-built)) (:joints built) (:joints old-built))
             :eyes (if (or (parts :eyes) (nil? old-built)) (:eyes built) (:eyes old-built))}
            (select-keys old-built [:bodies :constraints :broken])
            (select-keys built [:bodies :constraints :broken]))}))

(defn ^:api build!
  "Make `creature` physical as `plan` (see `plan`) says: a rigid body for
  each planned segment (a kept one keeps its own), the joints between
  them, the eyes on them; log the plan's warnings; keep the plan and
  what was built on the creature's Node. Returns the creature."
  [^Node creature plan]
  (.updateGeometricState creature)
  (let [built-segments
        (mapv (fn [{:keys [id kept?] :as p}]
                (if (= :rigid-body (:kind p))
                  (build-rigid-body creature p)
                (let [g (segment-at creature p)]
                  {:id id :geom g
                   :control (if kept?
                              (or (.getControl g RigidBodyControl)
                                  (throw (ex-info (str (segment/label creature) ": the plan keeps"
                                                       " the rigid body of segment " (pr-str id)
                                                       ", which has none; make the plan again")
                                                  {:creature (.getName creature) :segment id})))
                              (segment/in-creature creature #(segment/build-segment! g p)))})))
              (:segments plan))
        by-id (into {} (map (juxt :id identity)) built-segments)
        built-of (fn [j id]
                   (or (by-id id)
                       (throw (ex-info (str (segment/label creature) ", joint " (pr-str (:name j))
                                            ": the plan has no segment " (pr-str id))
                                       {:creature (.getName creature) :joint (:name j)}))))
        joints (mapv (fn [j]
                       (let [[a b] (map #(built-of j %) (:segments j))]
                         (joint-record j (segment/in-creature
                                          creature
                                          #(joint/build-joint! (:control a) (:control b) j))
                                       a b)))
                     (:joints plan))
        eyes (vision/build-eyes (:eyes plan) by-id)
        tab (when (contains? plan :constraints)
              (let [reports (mapv #(constraint/build-constraint! % by-id) (:constraints plan))
                    broken (ConcurrentHashMap.)]
                (.addControl creature ^com.jme3.scene.control.Control
                             (constraint/simulation-control
                              (:world plan) (filterv :breaking-threshold reports) broken
                              (constraint/blender-joint-order reports (:joint-order plan))))
                {:bodies (vec (keep :report built-segments)) :constraints reports :broken broken}))]
    (log-warnings! creature (:warnings plan))
    (segment/record! creature (merged (segment/record creature) plan
                                      (merge {:segments (mapv #(dissoc % :report) built-segments)
                                              :joints joints :eyes eyes}
                                             tab)))))
