;; Generated from org/plan.org by lein tangle: edit the chapter, not this file.
(ns cortex.body
  "Give a creature loaded from Blender a physical body: a rigid body for
  every segment and a Bullet joint for every joint marker, as the
  creature's designer described them in Blender. Each is a plan (see
  cortex.plan) made from the scene and then built.

  Entry points: `body!` (all of it), `physical!` (segments made solid),
  `joints!` (segments joined), `report` (what was built, as data),
  `segment`, `joint`, `joint-records`, and, from the namespaces that
  do the work, `joints` (the joint markers), `joint-targets` (the two
  segments a joint joins), `connect`, `joint-dispatch` (a multimethod:
  add joint types), `joint-types`, `read-joint` (a joint description,
  read safely), `read-description` (any such property), `segments`,
  `mass`, `pivot`, `pivot-in-world`, `cone-engine-angles` (a cone's
  angles as its engine reads them), `spring-fields` (a spring joint's
  settings, its defaults filled in)."
  (:require [clojure.string :as str]
            [cortex.engine :as engine]
            [cortex.joint :as joint]
            [cortex.nearest :as nearest]
            [cortex.plan :as plan]
            [cortex.segment :as segment]
            [cortex.util :as util]
            [cortex.vision :as vision])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints PhysicsJoint)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Node)))

(set! *warn-on-reflection* true)

;; the seed's names stay cortex.body's, wherever the code now lives
(util/export-vars cortex.segment max-hull-points mesh-points sphere-directions simplify-hull
        hull-from-points mass ^:api segments segment-name segment-pose default-options)
(util/export-vars cortex.nearest ^:api joints segment-index nearest-segments targets-near ^:api joint-targets
        tolerance segment-sides fmt-length joint-doubts duplicate-doubts naming-doubts
        overlap-warnings limit-warnings)
(util/export-vars cortex.joint read-description read-joint ^:api joint-dispatch joint-types body-frame
        common-joint-keys joint-keys check-keys jbullet-hinge-limits cone-engine-angles
        spring-fields pivot pivot-in-world joint-gap connect)

(defn ^:api physical!
  "Make every segment of `creature` solid: a rigid body with a convex
  hull shape and the segment's mass, the damping and sleeping thresholds
  of `opts` (see `default-options`). Segments that already have a rigid
  body keep it, so calling this twice is harmless. Returns the creature."
  ([creature] (physical! creature {}))
  ([^Node creature opts]
   (plan/build! creature (plan/plan-parts creature opts #{:segments}))))

(defn ^:api joints!
  "Join the segments of `creature` with the joints its \"joints\" node
  describes. Call after `physical!`. `opts` (see `default-options`):
  :strict? (default true) makes any doubt about a joint an error listing
  every doubt; false builds the joints anyway and keeps the doubts as
  warnings; :tolerance overrides the creature's ambiguity window.
  Returns the creature."
  ([creature] (joints! creature {}))
  ([^Node creature opts]
   (plan/build! creature (plan/plan-parts creature opts #{:joints}))))

(defn ^:api body!
  "Give `creature` its whole physical body: solid segments joined as its
  designer said, and its eyes, when it has an \"eyes\" node, fixed to
  their segments (see cortex.vision/eyes!): `(cortex.plan/plan creature
  opts)`, then `cortex.plan/build!`. `opts` as for `physical!` and
  `joints!` (see `default-options`). A creature's Physics tab is not
  read (cortex.physics-tab/physics-body! reads it) unless `opts` say
  :physics-tab? true. Returns the creature."
  ([creature] (body! creature {}))
  ([^Node creature opts]
   (plan/build! creature (plan/plan creature (merge {:physics-tab? false} opts)))))

(defn- build-record
  [^Node creature]
  (or (segment/record creature)
      (throw (ex-info (str (segment/label creature) " has no body yet: call body! first")
                      {:creature (.getName creature)}))))

(defn- vec3-of [^Vector3f v] [(.x v) (.y v) (.z v)])

(defn- segment-report
  "The report of segment `g`, planned as `planned` at its size, built
  `k` times larger."
  [^Geometry g planned ^double k]
  (let [^RigidBodyControl c (.getControl g RigidBodyControl)
        shape (:shape planned)
        hull? (or (nil? shape) (= :hull (:type shape)))
        points (when hull? (engine/hull-points (.getCollisionShape c)))
        hull-volume (if points (/ (engine/hull-volume points) (* k k k)) 0.0)
        {:keys [source centre moments]} (:inertia planned)]
    (cond-> {:name (segment-name g) :mass (double (.getMass c))
             :shape (if shape (:type shape) :hull)
             :volume (if hull? hull-volume (segment/shape-volume shape))
             :mass-properties source}
      hull? (assoc :hull-points (count points) :hull-volume hull-volume)
      (= :compound (:type shape)) (assoc :pieces (mapv #(get-in % [:shape :type]) (:children shape)))
      (= :mesh source) (assoc :centre-of-mass (vec3-of (util/jme-to-blender (util/vec3 centre)))
                              :principal-moments (vec moments)))))

(defn- joint-report
  [{:keys [name type description physics-joint segments pivot distances]}]
  (let [[x y z] pivot]
    {:name name :type type :class (.getSimpleName (class physics-joint))
     :segments segments
     :pivot (vec3-of (util/jme-to-blender (Vector3f. x y z)))
     :distances distances
     :limits (select-keys description [:limit :limit-xz :limit-xy :twist])}))

(defn ^:api report
  "What `body!` built of `creature`, as data: {:creature name, :segments
  [{:name :mass :shape (:hull, :box, :sphere, :capsule, :cylinder or
  :compound, with its :pieces) :volume (the shape's), and for a hull
  :hull-points :hull-volume}], :joints [{:name :type :class
  :segments [first second] :pivot [x y z] (Blender's world axes)
  :distances {segment distance} :limits {...}}], :warnings [{:kind
  :message ...}], :tolerance (the ambiguity window the doubts used)},
  and for a creature with eyes :eyes
  [{:name :kind :segment :distance :resolution :fov ...}] (see
  cortex.vision/eyes!). A creature a simulation built larger (see
  cortex.sim/simulation) is reported at its own size."
  [^Node creature]
  (let [{:keys [built plan-at-size scale] :as record} (build-record creature)
        ;; built larger by a simulation: reported at its size (above)
        plan (or plan-at-size (:plan record))
        {:keys [warnings tolerance eyes]} plan
        planned (into {} (map (fn [s b] [(:geom b) s]) (:segments plan) (:segments built)))]
    (cond-> {:creature (.getName creature)
             :segments (vec (for [g (segments creature)
                                  :when (.getControl ^Geometry g RigidBodyControl)]
                              (segment-report g (get planned g) (double (or scale 1.0)))))
             :joints (if plan-at-size
                       (mapv #(joint-report (merge %1 (select-keys %2 [:pivot :distances])))
                             (:joints built) (:joints plan))
                       (mapv joint-report (:joints built)))
             :warnings warnings
             :tolerance tolerance}
      (seq eyes) (assoc :eyes (mapv vision/eye-report eyes)))))

(defn ^:api segment
  "The segment (a Geometry with a rigid body) of `creature` that Blender
  calls `object-name`; the first, for an object with several materials.
  An error names the segments there are when there is none."
  ^Geometry [^Node creature ^String object-name]
  (or (first (filter #(= object-name (segment-name %)) (segments creature)))
      (throw (ex-info (str (segment/label creature) " has no segment " (pr-str object-name)
                           "; its segments are "
                           (str/join ", " (distinct (map segment-name (segments creature)))))
                      {:creature (.getName creature) :segment object-name}))))

(defn ^:api joint-records
  "The joints `body!` made of `creature`, in order, as maps of :name,
  :type, :description, :physics-joint (the jBullet joint), :geoms (the
  two segments, in order), :segments (their names), :pivot and
  :rotation (the joint empty's world position and rotation when it was
  made, jME axes), :body-rotations (the two rigid bodies' rotations
  then), :distances."
  [^Node creature]
  (:joints (:built (build-record creature))))

(defn ^:api joint
  "The jBullet joint `body!` made for the joint empty `joint-name`."
  ^PhysicsJoint [^Node creature ^String joint-name]
  (or (:physics-joint (first (filter #(= joint-name (:name %)) (joint-records creature))))
      (throw (ex-info (str (segment/label creature) " has no joint " (pr-str joint-name)
                           "; its joints are "
                           (str/join ", " (map :name (joint-records creature))))
                      {:creature (.getName creature) :joint joint-name}))))
