;; Generated from org/eyes.org by lein tangle: edit the chapter, not this file.
(ns cortex.vision
  "Eyes as a creature's designer placed them: the children of its
  \"eyes\" node, Blender cameras or empties with an `eye` property, each
  fixed to its nearest segment, with its field of view as Blender
  computes it. Draws nothing and loads no OpenGL; cortex.sight sees.

  Entry points: `eyes!` (called by cortex.body/body!), `eye-records`,
  `eye-spec`, `frustum`, `field-of-view`, `eye-pose`, `eye-rotation`,
  `eyes`, `default-eye`."
  (:require [clojure.string :as str]
            [cortex.joint :as joint]
            [cortex.nearest :as nearest]
            [cortex.segment :as segment]
            [cortex.sense :as sense]
            [cortex.util :as util])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Quaternion Vector3f)
           (com.jme3.scene Geometry Node Spatial)))

(set! *warn-on-reflection* true)

(def ^{:doc "The children of the creature's \"eyes\" node: one object
  per eye."
       :arglists '([creature])}
  eyes
  (sense/sense-nodes "eyes"))

(def default-eye
  "An empty's eye when its `eye` property leaves a key out: 60 degrees
  across, 64 by 48 pixels, seeing from 0.05 to 50 units."
  {:fov 60.0 :resolution [64 48] :near 0.05 :far 50.0})

(def ^:private empty-keys (set (keys default-eye)))

(def ^:private size-range
  "Images from 8x8 to 4096x4096 pixels."
  [8 4096])

(defn- bad-eye
  [eye-name what data]
  (throw (ex-info (str "eye " (pr-str eye-name) ": " what)
                  (merge {:eye eye-name} data))))

(defn- positive? [x] (and (number? x) (Double/isFinite (double x)) (pos? (double x))))

(defn- check-resolution!
  [eye-name resolution]
  (let [[lo hi] size-range]
    (when-not (and (vector? resolution) (= 2 (count resolution))
                   (every? integer? resolution)
                   (every? #(<= lo % hi) resolution))
      (bad-eye eye-name (str ":resolution must be [width height], whole numbers of pixels"
                             " from " lo " to " hi ", not " (pr-str resolution))
               {:kind :bad-eye :key :resolution :value resolution})))
  (mapv long resolution))

(defn- check-clip!
  [eye-name near far near-key far-key]
  (when-not (positive? near)
    (bad-eye eye-name (str near-key " must be a positive distance, not " (pr-str near))
             {:kind :bad-eye :key near-key :value near}))
  (when-not (and (positive? far) (> (double far) (double near)))
    (bad-eye eye-name (str far-key " must be a distance beyond " near-key " (" near
                           "), not " (pr-str far))
             {:kind :bad-eye :key far-key :value far})))

(defn- read-eye-property
  [eye-name text]
  (let [value (try (joint/read-description "eye" text)
                   (catch clojure.lang.ExceptionInfo e
                     (bad-eye eye-name (ex-message e) {:kind :bad-eye :text text})))]
    (when-not (map? value)
      (bad-eye eye-name (str "the eye property is a map such as "
                             (pr-str default-eye) ", not " (pr-str text))
               {:kind :bad-eye :text text}))
    value))

(defn- empty-spec
  [eye-name description]
  (let [unknown (sort (remove empty-keys (keys description)))
        {:keys [fov resolution near far]} (merge default-eye description)]
    (when (seq unknown)
      (bad-eye eye-name (str "unknown key" (when (next unknown) "s") " "
                             (str/join ", " (map pr-str unknown))
                             "; an eye's keys are " (str/join ", " (sort empty-keys)))
               {:kind :bad-eye :keys (vec unknown)}))
    (when-not (and (positive? fov) (< (double fov) 180.0))
      (bad-eye eye-name (str ":fov is the angle across the image in degrees,"
                             " more than 0 and less than 180, not " (pr-str fov))
               {:kind :bad-eye :key :fov :value fov}))
    (check-clip! eye-name near far :near :far)
    {:name eye-name :kind :empty :projection :perspective
     :fov (double fov) :resolution (check-resolution! eye-name resolution)
     :near (double near) :far (double far)}))

(defn- camera-spec
  [eye-name camera description]
  (let [unknown (sort (remove #{:resolution} (keys description)))
        {:keys [type lens sensor-width sensor-height clip-start clip-end ortho-scale]} camera]
    (when (seq unknown)
      (bad-eye eye-name (str "a camera's eye property only sets :resolution; "
                             (str/join ", " (map pr-str unknown))
                             " come" (when-not (next unknown) "s")
                             " from the camera's own settings in Blender (lens, sensor, clip)")
               {:kind :bad-eye :keys (vec unknown)}))
    (when-not (#{:perspective :orthographic} type)
      (bad-eye eye-name (str "a " (name type) " camera cannot be an eye;"
                             " make it perspective or orthographic in Blender")
               {:kind :bad-eye :key :type :value type}))
    (doseq [[k v] [[:lens lens] [:sensor-width sensor-width] [:sensor-height sensor-height]
                   [:ortho-scale ortho-scale]]]
      (when-not (positive? v)
        (bad-eye eye-name (str "the camera's " (name k) " must be positive, not " (pr-str v))
                 {:kind :bad-eye :key k :value v})))
    (check-clip! eye-name clip-start clip-end :clip-start :clip-end)
    {:name eye-name :kind :camera :projection type :camera camera
     :resolution (check-resolution! eye-name (get description :resolution [64 48]))
     :near (double clip-start) :far (double clip-end)}))

(defn eye-spec
  "The checked description of eye marker `marker` (a child of the
  \"eyes\" node): {:name :kind :projection :resolution :near :far}, with
  :fov for an empty, :camera for a Blender camera. An ex-info naming
  the eye says what is wrong with any other."
  [^Spatial marker]
  (let [eye-name (.getName marker)
        text (sense/meta-data marker "eye")
        camera (.getUserData marker sense/camera-key)
        type (.getUserData marker "blender-type")]
    (cond
      camera (camera-spec eye-name camera (if (some? text) (read-eye-property eye-name text) {}))
      (and type (not= "EMPTY" type))
      (bad-eye eye-name (str "a " type " object cannot be an eye; an eye is a camera,"
                             " or an empty with an eye property")
               {:kind :not-an-eye :blender-type type})
      (nil? text)
      (bad-eye eye-name (str "an empty under \"eyes\" needs an eye property, such as "
                             (pr-str "{:fov 60 :resolution [64 48]}"))
               {:kind :bad-eye})
      :else (empty-spec eye-name (read-eye-property eye-name text)))))

(defn frustum
  "The viewing window of eye `spec` (see `eye-spec`) for an image of
  `resolution` [w h] (default the eye's own): {:left :right :bottom :top
  :near :far :parallel?}, the window's edges at the near distance
  (perspective) or in units (orthographic), as Blender computes them."
  ([spec] (frustum spec (:resolution spec)))
  ([{:keys [kind fov near far camera projection]} [w h]]
   (let [w (double w) h (double h) near (double near)]
     (if (= kind :empty)
       (let [half-w (* near (Math/tan (Math/toRadians (/ (double fov) 2))))
             half-h (* half-w (/ h w))]
         {:left (- half-w) :right half-w :bottom (- half-h) :top half-h
          :near near :far (double far) :parallel? false})
       (let [{:keys [lens sensor-width sensor-height sensor-fit ortho-scale shift-x shift-y]} camera
             sensor (if (= sensor-fit :vertical) sensor-height sensor-width)
             fit (if (= sensor-fit :auto) (if (>= w h) :horizontal :vertical) sensor-fit)
             ortho? (= projection :orthographic)
             span (if ortho? (double ortho-scale) (/ (* (double sensor) near) (double lens)))
             [width height] (if (= fit :horizontal) [span (* span (/ h w))] [(* span (/ w h)) span])
             dx (* (double shift-x) span)
             dy (* (double shift-y) span)]
         {:left (+ dx (- (/ width 2))) :right (+ dx (/ width 2))
          :bottom (+ dy (- (/ height 2))) :top (+ dy (/ height 2))
          :near near :far (double far) :parallel? ortho?})))))

(defn field-of-view
  "What eye `spec` spans for an image of `resolution` (default its own):
  {:x :y} the angles across and up the image in degrees, for an
  unshifted perspective eye; {:width :height} in units for an
  orthographic one."
  ([spec] (field-of-view spec (:resolution spec)))
  ([spec resolution]
   (let [{:keys [left right bottom top near parallel?]} (frustum spec resolution)
         angle (fn [a b] (Math/toDegrees (+ (Math/atan (/ (- (double a)) (double near)))
                                            (Math/atan (/ (double b) (double near))))))]
     (if parallel?
       {:width (- (double right) (double left)) :height (- (double top) (double bottom))}
       {:x (angle left right) :y (angle bottom top)}))))

(defn scaled-spec
  "Eye `spec` in a scene `k` times the creature's size (a simulation's
  :scale): its near and far distances, and an orthographic camera's
  width, k times larger, so that it sees what it sees at the creature's
  size."
  [spec k]
  (let [k (double k)]
    (if (== 1.0 k)
      spec
      (cond-> (-> spec (update :near #(* k (double %))) (update :far #(* k (double %))))
        (get-in spec [:camera :ortho-scale])
        (update-in [:camera :ortho-scale] #(* k (double %)))))))

(def ^:private fmt nearest/fmt-length)

(defn- nearest!
  "The segment that carries eye `marker`, measured; an ex-info when two
  are about equally near (within `tolerance`), or the nearest is
  farther than its own longest side."
  [index tolerance ^Spatial marker]
  (let [eye-name (.getName marker)
        measured (try (nearest/nearest-segments index marker tolerance 1 "eye")
                      (catch clojure.lang.ExceptionInfo e
                        (bad-eye eye-name "no segment is near it; place it on the segment that carries it"
                                 {:kind :far-eye :found (:found (ex-data e))})))
        [a b] measured
        longest (double (peek (nearest/segment-sides (:geom a))))
        distances (into {} (map (juxt :name :distance)) measured)]
    (when b
      (bad-eye eye-name (str "it is about equally near " (:name a) " (" (fmt (:distance a))
                             ") and " (:name b) " (" (fmt (:distance b)) "; the tolerance is "
                             (fmt tolerance) "), so which segment carries it cannot be told;"
                             " move it closer to the one it belongs to")
               {:kind :ambiguous-eye :segments (mapv :name measured) :distances distances}))
    (when (> (double (:distance a)) longest)
      (bad-eye eye-name (str "its nearest segment, " (:name a) ", is " (fmt (:distance a))
                             " away, more than that segment's longest side (" (fmt longest)
                             "); move it onto the segment that carries it")
               {:kind :far-eye :segments [(:name a)] :distances distances}))
    a))

(defn- vec3-of [^Vector3f v] [(.x v) (.y v) (.z v)])

(defn plan-eyes
  "What each eye of `creature` (the children of its \"eyes\" node) will
  be, as plan data: {:name :spec (see `eye-spec`) :segment (its
  segment's Blender name) :segment-id (`id-of` that segment's Geometry)
  :distance :position :rotation (the eye's place in the world, jME
  axes)}, each found in `index` (see cortex.nearest/index-of), the
  segments the creature will have, with the ambiguity window
  `tolerance`. Throws an ex-info naming the eye for a bad description,
  a segment too far, two segments about equally near, or two eyes of
  one name."
  [^Node creature index tolerance id-of]
  (let [planned (mapv (fn [^Spatial m]
                        (segment/in-creature
                         creature
                         #(let [spec (eye-spec m)
                                {:keys [geom name distance]} (nearest! index tolerance m)]
                            {:name (:name spec) :spec (segment/plain spec) :segment name
                             :segment-id (id-of geom) :distance (double distance)
                             :position (segment/vector-data (.getWorldTranslation m))
                             :rotation (segment/quaternion-data (.getWorldRotation m))})))
                      (eyes creature))
        twice (sort (for [[n k] (frequencies (map :name planned)) :when (> k 1)] n))]
    (when (seq twice)
      (throw (ex-info (str "creature " (pr-str (.getName creature)) ", eyes share the names "
                           (pr-str (vec twice)) "; rename them in Blender so that each can be seen")
                      {:kind :duplicate-eye :names (vec twice) :creature (.getName creature)})))
    planned))

(defn eye-report
  "What `report` says of planned eye `e` (see `plan-eyes`)."
  [{:keys [name spec segment distance position]}]
  (let [{:keys [kind projection resolution near far]} spec
        fov (field-of-view spec)]
    (cond-> {:name name :kind kind :segment segment :distance distance
             :resolution resolution :near near :far far
             :position (segment/vector-data (util/jme-to-blender (util/vec3 position)))}
      (= projection :orthographic) (assoc :size [(:width fov) (:height fov)])
      (= projection :perspective) (assoc :fov [(:x fov) (:y fov)]))))

(defn build-eyes
  "The records of the planned eyes `planned` (see `plan-eyes`), each
  fixed to the rigid body of its segment: `built-of` gives a segment
  id's {:geom :control}. A record is {:name :spec :segment :geom
  :control :distance :offset :turn}: the eye's place and rotation in
  the body's frame."
  [planned built-of]
  (mapv (fn [{:keys [name spec segment segment-id distance position rotation]}]
          (let [{:keys [geom ^RigidBodyControl control]} (built-of segment-id)
                inverse (.inverse (.getPhysicsRotation control))]
            {:name name :spec spec :segment segment :geom geom :control control
             :distance distance
             :offset (.mult inverse (.subtract (util/vec3 position) (.getPhysicsLocation control)))
             :turn (.mult inverse (segment/quaternion rotation))}))
        planned))

(defn eyes!
  "Fix each eye of `creature` (the children of its \"eyes\" node) to its
  nearest segment, after the segments are solid (cortex.body/body!
  does it as part of the creature's plan). `opts`: :tolerance, as for
  body!. Errors as `plan-eyes`. Returns the creature."
  ([creature] (eyes! creature {}))
  ([^Node creature opts]
   (.updateGeometricState creature)
   (let [index (nearest/segment-index creature)
         tolerance (double (or (:tolerance opts) (nearest/tolerance index)))
         planned (plan-eyes creature index tolerance segment/segment-name)
         by-name (into {} (for [{:keys [geom]} (:items index)]
                            [(segment/segment-name geom)
                             {:geom geom :control (.getControl ^Geometry geom RigidBodyControl)}]))
         r (segment/record creature)]
     (segment/record! creature (-> r
                                   (assoc-in [:plan :eyes] planned)
                                   (assoc-in [:built :eyes] (build-eyes planned by-name)))))))

(defn eye-records
  "The eyes fixed on `creature`, in order: maps of :name, :spec (see
  `eye-spec`), :segment (its name), :geom, :control (its rigid body),
  :offset and :turn (the eye's place and rotation in the body's frame).
  Empty for a creature without eyes."
  [^Node creature]
  (get-in (segment/record creature) [:built :eyes]))

(def ^:private camera-turn
  "From an eye's axes to a jME camera's (which looks along its local +Z,
  up its +Y, its +X to the left): the camera's X is the eye's -X, its Y
  the eye's -Z, its Z the eye's -Y."
  (.fromAxes (Quaternion.) (Vector3f. -1 0 0) (Vector3f. 0 0 -1) (Vector3f. 0 -1 0)))

(defn eye-pose
  "Where eye `record` is now, as [location rotation] in jME's world: its
  segment's rigid body's place composed with the eye's offset, the
  rotation being a jME Camera's (see `camera-turn`), for
  Camera.setFrame."
  [{:keys [^RigidBodyControl control ^Vector3f offset ^Quaternion turn]}]
  (let [rotation (.getPhysicsRotation control)]
    [(.addLocal (.mult rotation offset) (.getPhysicsLocation control))
     (.multLocal (.mult rotation turn) ^Quaternion camera-turn)]))

(defn eye-rotation
  "The rotation of an eye that looks along `direction` with `up` up in
  its image (jME vectors), as an eye placed in code needs it: its local
  -Y along `direction`, its local -Z along `up` (a Blender camera's -Z
  and +Y, seen through the loader's change of axes)."
  ^Quaternion [^Vector3f direction ^Vector3f up]
  (let [d (.normalize direction)
        y (.negate d)
        z (.negate (.normalize (.subtract up (.mult d (.dot up d)))))
        x (.cross y z)]
    (.fromAxes (Quaternion.) x y z)))
