;; Generated from org/sim.org by lein tangle: edit the chapter, not this file.
(ns cortex.sim
  "A step loop for a creature: build a simulation, then call `step!`
  with each step's actions, without jME's application or render thread.
  Stepping is bit for bit what a cortex world does.

  Entry points: `simulation`, `step!`, `observe`, `sync!` (copy the
  bodies to the scene graph), `world` (a cortex world that shows a
  simulation and steps it, for windows and cortex.render's recording),
  `steps`, `sim-time`, `last-efforts` (the torques the last step applied),
  `solver` (its solver iterations and substeps), `check-solver!`,
  `check-scale!`, `destroy!`; for a scene of one's own, `scaled-body!`,
  `built-scale` and `scaled-substeps!`."
  (:require [clojure.string :as str]
            [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.muscle :as muscle]
            [cortex.plan :as plan]
            [cortex.projection :as projection]
            [cortex.proprioception :as p]
            [cortex.segment :as segment]
            [cortex.touch :as touch]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import            (com.jme3.app SimpleApplication)
           (com.jme3.bullet PhysicsSpace PhysicsSpace$BroadphaseType)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bounding BoundingBox BoundingSphere)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.math ColorRGBA Vector3f)
           (com.jme3.scene Geometry Node)
           (java.util IdentityHashMap Map)
           (java.util.logging Logger)))

(set! *warn-on-reflection* true)

(def tpf
  "The time per frame a cortex world passes to Bullet: the ratchet
  timer's 1f/60."
  (float (/ (float 1) (float 60))))

(def max-sub-steps
  "PhysicsSpace's default: at most four Bullet steps per frame (a
  simulation's :solver, or a Physics-tab creature's file, may ask for
  more)."
  4)

(defn physics-space
  "A PhysicsSpace made as BulletAppState makes one: world bounds of
  +-10000, the DBVT broadphase; set up as cortex's worlds are
  (cortex.engine/configure-space!), its joints projected
  (cortex.projection/install!)."
  ^PhysicsSpace []
  (projection/install!
   (engine/configure-space!
    (PhysicsSpace. (Vector3f. -10000 -10000 -10000) (Vector3f. 10000 10000 10000)
                   PhysicsSpace$BroadphaseType/DBVT))))

(defn ^:api floor
  "A static grey box named \"floor\", 400 by 400 units (room for a
  hundred-segment chain), its top at `height`, of friction `friction`
  (0.5, Bullet's default, when not given). `spec` is the height, or
  {:height h :friction f}."
  ^Geometry [spec]
  (let [{:keys [height friction] :or {friction 0.5}} (if (map? spec) spec {:height spec})]
    (util/box 200 0.5 200 :position (Vector3f. 0 (- (float height) 0.5) 0)
              :color ColorRGBA/Gray :mass 0 :name "floor" :friction friction)))

(def all-observations
  "Everything a step can observe (:eyes only in a simulation asked for
  eyes, see `simulation`)."
  #{:joints :segments :touch :eyes})

(defn- physical-segments
  "[name geometry rigid-body] of each physical segment under `node`."
  [^Node node]
  (let [segs (vec (for [^Geometry g (body/segments node)
                        :let [^RigidBodyControl c (.getControl g RigidBodyControl)]
                        :when c]
                    [(body/segment-name g) g (engine/rigid-body c)]))
        twice (sort (for [[n k] (frequencies (map first segs)) :when (> k 1)] n))]
    (when (seq twice)
      (throw (ex-info (str "segments share the names " (pr-str (vec twice))
                           "; rename them in Blender so that each can be observed")
                      {:names (vec twice)})))
    segs))

(defn- offset-of
  "A segment's offset (cortex.segment/mass-offset's {:centre [x y z]
  :rotation Quaternion}, or nil) as `segment-state` uses it at every
  step: the centre as a Vector3f, the rotation inverted, once."
  [offset]
  (when-let [{:keys [centre ^com.jme3.math.Quaternion rotation]} offset]
    {:centre-v (util/vec3 centre) :inverse (.inverse rotation)}))

(defn- identity-map ^Map [pairs]
  (let [m (IdentityHashMap.)]
    (doseq [[k v] pairs] (.put m k v))
    m))

(def option-keys
  "Every option `simulation` takes."
  #{:gravity :floor :observe :eyes :solver :scale})

(def solver-keys
  "What a simulation's :solver may set: :iterations (the constraint
  solver's passes per Bullet step), :substeps (Bullet steps per 1/60 s
  step) and :projection (whether joints are put back within their
  limits after each Bullet step, see cortex.projection)."
  #{:iterations :substeps :projection})

(def solver-bounds
  "The largest :iterations and :substeps a :solver may ask for."
  {:iterations 1000 :substeps 64})

(defn- unknown-key-error
  "An ex-info for the key `k` of `what`, which is none of `known`,
  naming the known key it is most likely a misspelling of."
  [what k known data]
  (let [near (util/near-miss k known)]
    (ex-info (str what " has no key " (pr-str k)
                  (when near (str "; did you mean " near "?"))
                  " It takes " (str/join ", " (sort known)))
             (assoc data :key k :known (vec (sort known))))))

(defn check-scale!
  "Check a simulation's :scale option `scale` (:auto, or a positive
  number); an ex-info that says what it must be otherwise."
  [scale]
  (when-not (or (= :auto scale) (and (util/finite? scale) (pos? (double scale))))
    (throw (ex-info (str ":scale must be :auto or a positive number, not " (pr-str scale)
                         " (how many times its size the creature is simulated)")
                    {:scale scale})))
  scale)

(defn check-solver!
  "Check a simulation's :solver option `solver` (nil, or a map of
  `solver-keys` to whole numbers from 1 to `solver-bounds`, :projection
  to true or false); an ex-info naming the key at fault otherwise."
  [solver]
  (when (some? solver)
    (when-not (map? solver)
      (throw (ex-info (str ":solver must be a map such as {:iterations 20 :substeps 2}, not "
                           (pr-str solver))
                      {:solver solver})))
    (doseq [k (keys solver) :when (not (solver-keys k))]
      (throw (unknown-key-error ":solver" k solver-keys {:solver solver})))
    (when-not (boolean? (:projection solver true))
      (throw (ex-info (str ":solver :projection must be true or false, not "
                           (pr-str (:projection solver)))
                      {:solver solver :key :projection :value (:projection solver)})))
    (doseq [[k v] (dissoc solver :projection)
            :let [hi (solver-bounds k)]
            :when (not (and (int? v) (<= 1 (long v) (long hi))))]
      (throw (ex-info (str ":solver " k " must be a whole number from 1 to " hi ", not " (pr-str v))
                      {:solver solver :key k :value v}))))
  solver)

(defn- check-options!
  [{:keys [gravity floor observe solver scale] :as opts}]
  (doseq [k (keys opts) :when (not (option-keys k))]
    (throw (unknown-key-error "a simulation" k option-keys {:options opts})))
  (check-solver! solver)
  (check-scale! scale)
  (when-not (and (sequential? gravity) (= 3 (count gravity)) (every? util/finite? gravity))
    (throw (ex-info (str ":gravity must be [x y z], finite numbers, not " (pr-str gravity)) opts)))
  (when-not (or (nil? floor) (util/finite? floor)
                (and (map? floor) (util/finite? (:height floor))
                     (or (nil? (:friction floor))
                         (and (util/finite? (:friction floor)) (not (neg? (:friction floor)))))
                     (empty? (dissoc floor :height :friction))))
    (throw (ex-info (str ":floor must be a height, {:height h :friction f} or nil, not "
                         (pr-str floor))
                    opts)))
  (when-not (and (coll? observe) (every? all-observations observe))
    (throw (ex-info (str ":observe must be a subset of " (pr-str all-observations)
                         ", not " (pr-str observe))
                    opts))))

(defn- has-body?
  "Whether `creature` has been given its body: its plan (see
  cortex.plan) has cortex's joints, or the Physics tab's bodies and
  constraints (cortex.physics-tab/physics-body!, whose plan has no
  :joints when the creature has no joints empty)."
  [creature]
  (boolean (some #{:joints :physics-tab} (get-in (segment/record creature) [:plan :parts]))))

(defn- tab-settings
  "The settings of `creature`'s Physics tab (see
  cortex.physics-tab/simulation-settings), nil for a creature without
  one."
  [^Node creature]
  (get-in (segment/record creature) [:plan :world]))

(defn- set-solver!
  "Override `space`'s solver iterations and substeps with those `solver`
  gives (see `solver-keys`); a creature's Physics tab has set its own by
  now, when it has one."
  [^PhysicsSpace space solver time-scale]
  (when-let [n (:iterations solver)]
    (.setSolverNumIterations space (int n)))
  (when-let [k (:substeps solver)]
    (.setAccuracy space (float (world/substep-length time-scale k)))
    (.setMaxSubSteps space (int k)))
  (when (contains? solver :projection)
    (projection/enable! space (:projection solver))))

(defn- solver-of
  "How a simulation steps, {:iterations n :substeps k :projection bool}:
  what `solver` asked for, else the creature's Physics tab, else
  cortex's defaults (cortex.engine/solver-iterations, `thin-substeps`
  (1 but for small bodies, see cortex.world/substeps-for), and true);
  `tab` is the creature's `tab-settings`."
  [^PhysicsSpace space solver tab thin-substeps]
  {:iterations (.getSolverNumIterations space)
   :substeps (long (or (:substeps solver) (:substeps tab) thin-substeps))
   :projection (projection/enabled? space)})

(defonce ^:private sight (atom nil))

(defn install-sight!
  "Make `hooks`, {:open! :see! :close!}, how a simulation sees through a
  creature's eyes: cortex.sight installs its own when it is loaded, so
  that the step loop needs no renderer until eyes are asked for."
  [hooks]
  (reset! sight hooks))

(defn- sight-hooks
  []
  (or @sight
      (throw (ex-info (str "seeing through a creature's eyes needs cortex.sight, which is not"
                           " loaded: (require 'cortex.sight) first")
                      {}))))

(defn- scale-up!
  "Give `creature` its body `k` times its size: its Node scaled by k
  about the world's origin, its segments' sleeping thresholds times
  sqrt k (the same rest as a creature of the larger size), k kept in
  its record (see `built-scale`), and the plan body! would build of it
  at its size (:plan-at-size: what cortex.body/report and
  cortex.export write)."
  [^Node creature ^double k]
  (let [at-size (plan/plan creature {:physics-tab? false})]
    (.setLocalScale creature (.mult (.getLocalScale creature) (float k)))
    (.setLocalTranslation creature (.mult (.getLocalTranslation creature) (float k)))
    (body/body! creature {:sleeping-thresholds
                          (mapv #(* (Math/sqrt k) (double %))
                                (:sleeping-thresholds segment/default-options))})
    (segment/record! creature (assoc (segment/record creature) :scale k :plan-at-size at-size))))

(defn ^:api built-scale
  "How many times its size `creature` was built, by a simulation or
  `scaled-body!`: k, or 1 (at its size, or without its body yet)."
  ^double [^Node creature]
  (double (or (:scale (segment/record creature)) 1.0)))


(def small-creature
  "The size (the longest side of its box, in the world's units) under
  which a creature without its body is simulated larger: 1. The
  strangers dropped at 0.3 to 0.9 of their size on both engines came to
  rest at their size in all 16 drops 1 across or more, and in only 4 of
  the 8 under it (see the chapter)."
  1.0)

(defn creature-size
  "The longest side of the box round everything `creature` shows, in the
  world; 0 for a creature that shows nothing."
  ^double [^Node creature]
  (.updateGeometricState creature)
  (let [b (.getWorldBound creature)]
    (cond (instance? BoundingBox b) (let [e (.getExtent ^BoundingBox b (Vector3f.))]
                                      (* 2.0 (max (.x e) (.y e) (.z e))))
          (instance? BoundingSphere b) (* 2.0 (.getRadius ^BoundingSphere b))
          :else 0.0)))

(defn auto-scale
  "The scale :auto chooses for a creature `size` across: 1 from
  `small-creature` up, below it the least power of ten that brings the
  size to `small-creature` or more (between 1 and 10)."
  ^double [^double size]
  (if (and (pos? size) (< size (double small-creature)))
    ;; less a hair, so that a size read from floats as 0.1 is 10, not 100
    (Math/pow 10.0 (Math/ceil (- (Math/log10 (/ (double small-creature) size)) 1e-6)))
    1.0))

(defn- choose-scale
  "The scale of a simulation of `creature` with `opts`: the one an
  earlier simulation built it at, else :scale as given, else (:auto)
  `auto-scale` of its size when it has no body yet; a warning says what
  :auto chose, or why a small creature is left at its size. An ex-info
  naming the creature for a scale that cannot be kept. `bodied?`:
  whether it has its body (`has-body?`)."
  ^double [^Node creature {:keys [scale]} bodied?]
  (let [size (delay (creature-size creature))   ; measured for :auto alone
        refuse (fn [why]
                 (throw (ex-info (str (segment/label creature) ", :scale " scale ": " why)
                                 {:creature (.getName creature) :scale scale})))
        log #(.warning (Logger/getLogger "cortex.sim")
                       (str (segment/label creature) " is " (format "%.3g" @size) " across: " %))
        built (:scale (segment/record creature))]
    (cond
      built (cond (not (or (= :auto scale) (== (double built) (double scale))))
                  (refuse (str "an earlier simulation built its body " built " times larger;"
                               " load the creature again for another scale"))
                  :else (double built))
      (not= :auto scale) (let [k (double scale)]
                           (when (and bodied? (not= 1.0 k))
                             (refuse (str "the creature has its body already, built at its"
                                          " own size; pass it to simulation before body!, or"
                                          " leave :scale out")))
                           k)
      :else
      (let [k (auto-scale @size)]
        (cond (== 1.0 k) 1.0
              bodied? (do (log (str "at this size Bullet's fixed tolerances keep it from resting;"
                                    " it has its body already, so it is simulated at its size:"
                                    " give it to simulation before body!, or build it with"
                                    " cortex.sim/scaled-body!, to have it simulated "
                                    (long k) " times larger"))
                          1.0)
              :else (do (log (str "it is simulated " (long k) " times larger (:scale " (long k)
                                  "), under " (long k) " times the gravity, and observed in its"
                                  " own units; give :scale 1 to simulate it at its size"))
                        k))))))

(defn ^:api scaled-body!
  "Give `creature` its body as a simulation of it with `opts` (only
  :scale is read; :auto by default) would, and return the scale it is
  built at: the one :scale gives, or for :auto, k for a creature
  without its body under `small-creature` across (see `auto-scale`),
  else 1; a creature that has its body keeps it. Its record then keeps
  k and its plan at its size (cortex.body/report and cortex.export read
  that). A scene of one's own holding it owes it k times the gravity
  and `scaled-substeps!`."
  (^double [creature] (scaled-body! creature {}))
  (^double [^Node creature opts]
   (let [bodied? (has-body? creature)
         k (choose-scale creature (merge {:scale :auto} opts) bodied?)]
     (cond bodied? nil
           (== 1.0 k) (body/body! creature)
           :else (scale-up! creature k))
     k)))

(defn- scaled-floor
  "Floor spec `floor` (see `floor`) with its height `k` times as high."
  [floor ^double k]
  (cond (== 1.0 k) floor
        (map? floor) (update floor :height #(* k (double %)))
        :else (* k (double floor))))

(defn ^:api scaled-substeps!
  "The substeps of a world of bodies built `k` times their size that
  would take `n` at that size (by default those its thinnest body asks
  for, cortex.world/step-thin-bodies!), at time scale `t` (default 1):
  n times ceil(sqrt k) when k > 1 (at most the :substeps of
  `solver-bounds`), the larger world's step being then the larger
  creature's; set on `space` when more than n. For a scene of one's
  own holding a creature built by `scaled-body!`."
  (^long [^PhysicsSpace space k] (scaled-substeps! space k 1.0 (world/step-thin-bodies! space)))
  (^long [^PhysicsSpace space k t n]
   (let [k (double k) n (long n)
         m (if (> k 1.0)
             (min (long (:substeps solver-bounds))
                  (* n (long (Math/ceil (- (Math/sqrt k) 0.001)))))
             n)]
     (when (> m n)
       (.setAccuracy space (float (world/substep-length t m)))
       (.setMaxSubSteps space (int m)))
     m)))

(defn- unscaled-segment
  "A segment's state read in a world `k` times larger, in the creature's
  own units: positions and velocities over k (turns are the same)."
  [{:keys [position velocity] :as state} ^double k]
  (assoc state
         :position (mapv #(/ (double %) k) position)
         :velocity (mapv #(/ (double %) k) velocity)))

(defn- unscaled-touch
  "Touch read in a world `k` times larger: impulses (mass times
  velocity) over k."
  [touch ^double k]
  (update-vals touch (fn [t] (update t :impulse #(/ (double %) k)))))

(defn ^:api simulation
  "A simulation of `creature` (a creature Node; given its body with
  cortex.body/body! unless it has one) in a new PhysicsSpace, with
  `opts`: :gravity [x y z] (default [0 -9.81 0]), :floor (height of
  the top of a static floor, or nil: the default), :observe (a subset
  of #{:joints :segments :touch :eyes}, what `step!` returns besides
  :time; all by default), :eyes (true, or a map of eye name to options:
  what the creature's eyes see is observed too, drawn offscreen on a
  GL context of the simulation's own; see cortex.sight and the vision
  chapter), :solver ({:iterations n :substeps k :projection bool}, any
  of them: overrides cortex's defaults of 20, 1 (more for a creature
  with a body under cortex.engine/thin thick: cortex.world/substeps-for)
  and true, or a Physics-tab creature's file; see `check-solver!`),
  :scale (a creature without its body yet is built and simulated that
  many times its size, under that many times the gravity, and is
  observed, acted on and reported in its own units; :auto, the
  default, is 1 but for a creature under `small-creature` across, see
  `auto-scale` and the chapter). Any other key is an error. Use it
  from one thread at a time; `destroy!` frees it."
  ([creature] (simulation creature {}))
  ([^Node creature opts]
   (let [{:keys [gravity floor observe scale] :as opts}
         (merge {:gravity [0 -9.81 0] :floor nil :observe all-observations :scale :auto} opts)
         _ (check-options! opts)
         k (scaled-body! creature opts)
         tab (tab-settings creature)
         floor-geom (when floor (cortex.sim/floor (scaled-floor floor k)))
         root (util/nodify "simulation" (cond-> [creature] floor-geom (conj floor-geom)))
         space (physics-space)
         segs (physical-segments creature)
         segment-names (identity-map (for [[n _ rb] segs] [rb n]))
         ;; the engine bodies an observation reads: the segments' in
         ;; their order (a segment's state is its body's, by place),
         ;; then any other a joint joins
         joint-sensors (p/sensors creature)
         bodies (p/bodies-of (mapv #(nth % 2) segs) joint-sensors)
         sensors (p/indexed joint-sensors bodies)
         g (util/vec3 (if (== 1.0 k) gravity (mapv #(* k (double %)) gravity)))]
     (engine/add-all! space root)
     (set-solver! space (:solver opts) (double (:time-scale tab 1.0)))
     (.setGravity space g)
     (doseq [^PhysicsRigidBody b (.getRigidBodyList space)]
       (.setGravity b g)
       (.activate b))
     (let [;; a creature with a small body takes more substeps, unless
           ;; asked for a number (cortex.world/step-thin-bodies!)
           thin-substeps (if (or (:substeps (:solver opts)) (:substeps tab))
                           1
                           (scaled-substeps! space k (double (:time-scale tab 1.0))
                                             (world/step-thin-bodies!
                                              space (double (:time-scale tab 1.0)))))]
       {:space space :creature creature :root root :observe (set observe) :scale k
        :solver (solver-of space (:solver opts) tab thin-substeps)
        :sensors sensors
        :bodies bodies
        :muscles (into {} (for [s sensors] [(:name s) (muscle/muscle s k)]))
        :segments (mapv (fn [[n ^Geometry g rb]]
                          [n rb (offset-of (segment/mass-offset g))])
                        segs)
        :controls (vec (for [^Geometry geom (body/segments root)
                             :let [c (.getControl geom RigidBodyControl)]
                             :when c]
                         [geom c]))
        :segment-names segment-names
        :untouched (touch/untouched segment-names)
        :object-names (identity-map (for [[n _ rb] (when floor-geom (physical-segments root))
                                          :when (= n "floor")]
                                      [rb n]))
        :steps (long-array 1)
        :last-efforts (object-array 1)
        ;; eyes (vision.org): loaded only when asked for, so that a
        ;; simulation without eyes loads no OpenGL
        :sight (when-let [eyes (:eyes opts)]
                 ((:open! (sight-hooks)) creature root eyes k))}))))

(defn ^:api solver
  "How `sim` steps: {:iterations n :substeps k :projection bool}, the
  constraint solver's passes per Bullet step, Bullet steps per 1/60 s
  step, and whether joints are put back within their limits."
  [sim]
  (:solver sim))

(defn ^:api scale
  "How many times its size `sim` simulates its creature (see
  `simulation`'s :scale): 1.0 but for a small creature."
  ^double [sim]
  (double (:scale sim)))

(defn ^:api steps
  "How many steps `sim` has taken."
  ^long [{:keys [^longs steps]}]
  (aget steps 0))

(defn ^:api sim-time
  "Simulated seconds so far: steps / 60."
  ^double [sim]
  (/ (double (steps sim)) 60.0))

(defn- segment-state
  "The state of the segment whose body is the `i`th of `states`
  (cortex.engine/body-states), in the segment's own frame: a body whose
  centre of mass is off the segment's origin, or whose principal axes
  are turned from the segment's (see the body chapter's mass
  properties), carries `offset` (see `offset-of`); its position and
  rotation are taken back to the segment's origin and axes, and the
  velocity is the origin's."
  [^doubles states ^long i offset]
  (let [k (* 13 i)
        at (fn ^double [^long j] (aget states (+ k j)))
        w [(at 10) (at 11) (at 12)]]
    (if-let [{:keys [^com.jme3.math.Vector3f centre-v ^com.jme3.math.Quaternion inverse]} offset]
      (let [body-rot (com.jme3.math.Quaternion. (float (at 3)) (float (at 4)) (float (at 5))
                                                (float (at 6)))
            rot (.mult body-rot inverse)
            ;; from the centre of mass back to the origin, in the world
            back (.negate (.mult rot centre-v))
            ;; on primitives (every step, every segment), the arithmetic
            ;; the vectors did: a double plus a float's double
            bx (double (.x back)) by (double (.y back)) bz (double (.z back))
            wx (at 10) wy (at 11) wz (at 12)]
        {:position [(+ (at 0) bx) (+ (at 1) by) (+ (at 2) bz)]
         :rotation [(.getX rot) (.getY rot) (.getZ rot) (.getW rot)]
         :velocity [(+ (at 7) (- (* wy bz) (* wz by)))
                    (+ (at 8) (- (* wz bx) (* wx bz)))
                    (+ (at 9) (- (* wx by) (* wy bx)))]
         :angular-velocity w})
      {:position [(at 0) (at 1) (at 2)] :rotation [(at 3) (at 4) (at 5) (at 6)]
       :velocity [(at 7) (at 8) (at 9)] :angular-velocity w})))

(declare sync!)

(defn ^:api observe
  "What `sim` senses now: :time, and each of `parts` (by default its
  :observe): :joints (proprioception), :segments ({name {:position
  :rotation :velocity :angular-velocity}}, jME's world axes), :touch and,
  with eyes, :eyes (see cortex.sight/see!)."
  ([sim] (observe sim (:observe sim)))
  ([{:keys [sensors segments bodies space segment-names object-names untouched sight]
     k :scale :as sim}
    parts]
   (if (empty? parts)
     {:time (sim-time sim)}
   (let [joints? (contains? parts :joints) segments? (contains? parts :segments)
         ;; every body read once, for the joints and the segments both
         states (when (or joints? segments?) (engine/body-states bodies))]
     (cond-> {:time (sim-time sim)}
       (and sight (contains? parts :eyes))
       (assoc :eyes (do (sync! sim) ((:see! (sight-hooks)) sight)))
       joints? (assoc :joints (p/read-joints sensors states))
       segments?
       (assoc :segments (persistent! (reduce (fn [m [i [n _ offset]]]
                                               (assoc! m n (cond-> (segment-state states i offset)
                                                             (not= 1.0 k) (unscaled-segment k))))
                                             (transient {}) (map-indexed vector segments))))
       (contains? parts :touch)
       (assoc :touch (cond-> (touch/contacts space segment-names object-names untouched)
                       (not= 1.0 k) (unscaled-touch k))))))))

(defn ^:api step!
  "Apply `actions` (see cortex.muscle; nil or {} for none) for one step,
  advance `sim` by exactly 1/60 s and return the observation (see
  `observe`). Bad actions throw, naming the joint, before anything is
  applied or stepped."
  ([sim] (step! sim nil))
  ([{:keys [^PhysicsSpace space muscles ^longs steps ^objects last-efforts scale] :as sim} actions]
   (let [es (when (seq actions) (muscle/efforts muscles actions))]
     (when es (muscle/apply-efforts! muscles es scale))
     (aset last-efforts 0 es))
   ;; the space's own limit on substeps: four, or what :solver or the
   ;; creature's Physics tab set
   (.update space (float tpf))
   (.distributeEvents space)
   (aset steps 0 (inc (aget steps 0)))
   (observe sim)))

(defn ^:api last-efforts
  "The torques the last `step!` of `sim` applied, clamped, by joint name
  (see cortex.muscle/efforts: N.m for a hinge, [x y z] in the joint's
  frame, Blender's axes, otherwise); nil before the first step and after
  a step without actions. Times the joint velocities of the observation
  that step returned, they are the muscles' power (cortex.rollout sums
  it into the energy a rollout used)."
  [{:keys [^objects last-efforts]}]
  (aget last-efforts 0))

(defn ^:api sync!
  "Put every Geometry where its body says, as a world's frame does (a
  body moved to its segment's centre of mass or turned to its principal
  axes is undone: cortex.segment/segment-pose), and bring the scene
  graph's world transforms up to date. Returns the simulation's root
  Node."
  ^Node [{:keys [^Node root controls]}]
  (.updateGeometricState root)
  (doseq [[^Geometry g] controls]
    (let [[pos rot] (segment/segment-pose g)]
      (segment/place! g pos rot)))
  (.updateGeometricState root)
  root)

(defn ^:api destroy!
  "Free `sim`'s physics space, and its eyes' GL context."
  [{:keys [^PhysicsSpace space sight]}]
  (when sight ((:close! (sight-hooks)) sight))
  (.destroy space))

(defn ^:api world
  "A cortex world showing `sim` and stepping it once a frame with the
  actions (controller observation) returns, the observation being the
  last step's (at first, `observe`'s). `setup` (of the world) runs
  after the scene is lit and the camera placed to look at the creature
  from the side. The world owns the simulation until it stops."
  ([sim controller] (world sim controller world/no-op))
  ([{:keys [^Node root creature] :as sim} controller setup]
   (let [last-observation (atom nil)]
     (world/world (Node. "view") {}
                  (fn [^SimpleApplication w]
                    (.attachChild (.getRootNode w) root)
                    (util/light-up-everything w)
                    ;; the whole scene, from its root: brought up to date from
                    ;; the simulation's Node alone, the lights above would never
                    ;; reach the creature (its light list would be marked fresh)
                    (.updateGeometricState (.getRootNode w))
                    (let [c (.getCenter (.getWorldBound ^Node creature))]
                      (doto (.getCamera w)
                        (.setLocation (.add c (Vector3f. 0 3 9)))
                        (.lookAt c Vector3f/UNIT_Y)))
                    (reset! last-observation (observe sim))
                    (setup w))
                  (fn [_ _]
                    (reset! last-observation
                            (step! sim (controller @last-observation))))))))
