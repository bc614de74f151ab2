;; Generated from org/rollout.org by lein tangle: edit the chapter, not this file.
(ns cortex.rollout
  "Rollouts: one headless simulation described by plain data (a spec)
  and summarised by plain data (a result), and many of them on every
  core, in order, each result the same as if run alone.

  Entry points: `rollout` (one spec; throws on failure), `rollouts`
  (many, on a fixed pool of threads; a failure is its result's :error),
  `check-specs!` (every spec checked before any runs), `try-rollout`,
  `simulation` and `controller` (what a rollout runs, to watch it),
  `columns` and `flat-row` (a result as one row of a table), and the
  controllers `crawl-gait` and `sine-gait`. See org/rollout.org for the
  spec's keys and what is measured."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [cortex.engine :as engine]
            [cortex.proprioception :as p]
            [cortex.sim :as sim]
            [cortex.blender :as blender]
            [cortex.util :as util])
  (:import            (com.jme3.scene Node)
           (java.util Random)
           (java.util.concurrent Callable ExecutorService Executors Future ThreadFactory)
           (java.util.concurrent.atomic AtomicLong)))

(set! *warn-on-reflection* true)

(def spec-keys
  "Every key a spec may have."
  #{:creature :controller :params :seconds :seed :start :floor :observe
    :torso :fall-angle :trajectory :id :solver :scale})

(def max-seconds
  "The longest rollout, simulated seconds."
  3600)

(def defaults
  "What a spec leaves out."
  {:controller nil :params nil :seed 0 :start {:shift 0.0 :turn 0.0} :floor 0
   :observe #{} :torso nil :fall-angle (/ Math/PI 3) :trajectory nil :solver nil :scale :auto})

(defn- fail!
  [index spec field message & [cause]]
  (throw (ex-info (str (if index (str "spec " index) "spec") ", " field ": " message)
                  {:index index :field field :value (get spec field) :spec spec}
                  cause)))

(defn- finite? [x] (and (number? x) (Double/isFinite (double x))))

(defn controller-maker
  "The function the symbol `controller` (or a string naming one) names,
  required when its namespace is not loaded yet; nil for nil. An
  ex-info when it names nothing."
  [controller]
  (when (some? controller)
    (let [sym (if (string? controller) (symbol controller) controller)]
      (when-not (qualified-symbol? sym)
        (throw (ex-info (str "a controller is a qualified symbol such as my.ns/gait, not "
                             (pr-str controller)) {})))
      (let [v (try (requiring-resolve sym)
                   (catch Exception e
                     (throw (ex-info (str "cannot load " sym ": " (ex-message e)) {} e))))]
        (when-not (and v (ifn? @v))
          (throw (ex-info (str sym " names no function") {})))
        @v))))

(defn creature-exists?
  "Whether `creature` is a file or an asset on the classpath."
  [creature]
  (and (string? creature)
       (or (.isFile (io/file creature)) (some? (io/resource creature)))))

(defn check-spec!
  "Check `spec` (at `index` in its collection, or nil); return it with
  the defaults filled in. An ex-info naming the index and the field
  when anything is wrong; the controller is made once from the
  parameters, so that it can reject them."
  [index spec]
  (when-not (map? spec)
    (throw (ex-info (str (if index (str "spec " index) "spec") " must be a map, not " (pr-str spec))
                    {:index index :spec spec})))
  (when (contains? spec :eyes)
    (fail! index spec :eyes (str "rollouts run without eyes (one OpenGL context per"
                                 " simulation would be needed on every worker); for eyes,"
                                 " make each simulation with cortex.sim/simulation and"
                                 " {:eyes true} on its own thread (see org/vision.org)")))
  (doseq [k (keys spec) :when (not (spec-keys k))
          :let [near (util/near-miss k spec-keys)]]
    (fail! index spec k (str "unknown key; " (when near (str "did you mean " near "? "))
                             "a spec takes " (str/join ", " (sort spec-keys)))))
  (let [{:keys [creature controller params seconds seed start floor observe torso
                fall-angle trajectory scale] :as s} (merge defaults spec)]
    (when-not (creature-exists? creature)
      (fail! index s :creature (str (pr-str creature) " is no file, nor an asset under assets/"
                                    " or on the classpath")))
    (when-not (and (finite? seconds) (pos? (double seconds)) (<= (double seconds) max-seconds))
      (fail! index s :seconds (str "must be a finite number of seconds, more than 0 and at most "
                                   max-seconds ", not " (pr-str seconds))))
    (when-not (int? seed)
      (fail! index s :seed (str "must be an integer, not " (pr-str seed))))
    (when-not (and (map? start) (every? #{:shift :turn} (keys start))
                   (every? #(and (finite? %) (not (neg? (double %)))) (vals start)))
      (fail! index s :start (str "must be {:shift s :turn t}, finite and not negative, not "
                                 (pr-str start))))
    (when-not (or (nil? floor) (finite? floor))
      (fail! index s :floor (str "must be a height or nil, not " (pr-str floor))))
    (when-not (and (coll? observe) (every? sim/all-observations observe))
      (fail! index s :observe (str "must be a subset of " (pr-str sim/all-observations)
                                   ", not " (pr-str observe))))
    (when-not (or (nil? torso) (string? torso))
      (fail! index s :torso (str "must be a segment's name, not " (pr-str torso))))
    (when-not (and (finite? fall-angle) (< 0 (double fall-angle)) (<= (double fall-angle) Math/PI))
      (fail! index s :fall-angle (str "must be an angle in (0, pi], not " (pr-str fall-angle))))
    (try (sim/check-solver! (:solver s))
         (catch clojure.lang.ExceptionInfo e
           (fail! index s :solver (ex-message e) e)))
    (try (sim/check-scale! scale)
         (catch clojure.lang.ExceptionInfo e
           (fail! index s :scale (ex-message e) e)))
    (when-not (or (nil? trajectory) (pos-int? trajectory))
      (fail! index s :trajectory (str "must be nil or a positive whole number of steps, not "
                                      (pr-str trajectory))))
    (let [make (try (controller-maker controller)
                    (catch clojure.lang.ExceptionInfo e
                      (fail! index s :controller (ex-message e) e)))]
      (when make
        (let [c (try (make params)
                     (catch Exception e
                       (fail! index s :params (str "rejected by " controller ": " (ex-message e)) e)))]
          (when-not (ifn? c)
            (fail! index s :controller (str controller " returned " (pr-str c)
                                            ", not a function of an observation"))))))
    s))

(defn ^:api check-specs!
  "Check every spec of `specs` (see `check-spec!`) before any runs;
  return them with their defaults."
  [specs]
  (when-not (sequential? specs)
    (throw (ex-info (str "specs must be a sequence of specs, not " (pr-str specs)) {})))
  (vec (map-indexed check-spec! specs)))

(defn- as-doubles [v] (mapv double v))

(defn- mass ^double [rb]
  (let [inv (engine/inverse-mass rb)]
    (if (zero? inv) 0.0 (/ 1.0 inv))))

(defn- centre
  "The centre of mass of the `weights` ({segment mass}) in `observation`."
  [weights observation]
  (let [segs (:segments observation)
        total (reduce + (vals weights))]
    (mapv (fn [i] (/ (reduce + (for [[n m] weights]
                                 (* (double m) (double (nth (get-in segs [n :position]) i)))))
                     total))
          (range 3))))

(def ^:private up [0.0 1.0 0.0])

(defn- tilt
  "The angle between the vertical and the torso's own up, `local-up`,
  as the torso is turned in `observation`."
  ^double [torso local-up observation]
  (let [q (as-doubles (get-in observation [:segments torso :rotation]))
        [_ y _] (p/rotate q local-up)]
    (Math/acos (max -1.0 (min 1.0 (double y))))))

(defn- power
  "Sum over joints of |effort . relative angular velocity|, W."
  ^double [efforts joints]
  (reduce + 0.0 (for [[n e] efforts
                      :let [j (get joints n)]]
                  (Math/abs (double (if (number? e)
                                      (* (double e) (double (:velocity j)))
                                      (p/dot e (:angular-velocity j))))))))

(defn- pose [observation]
  {:segments (into (sorted-map)
                   (for [[n {:keys [position rotation]}] (:segments observation)]
                     [n {:position (as-doubles position) :rotation (as-doubles rotation)}]))
   :joints (into (sorted-map) (:joints observation))})

(defn- place!
  "Move and turn `creature` as `seed` and `start` say."
  [^Node creature seed {:keys [shift turn] :or {shift 0.0 turn 0.0}}]
  (let [r (Random. (long seed))
        u #(- (* 2.0 (.nextDouble r)) 1.0)
        dx (* (double shift) (u)) dz (* (double shift) (u)) yaw (* (double turn) (u))]
    (.move creature (float dx) 0 (float dz))
    (.rotate creature 0 (float yaw) 0)
    creature))

(defn simulation
  "The cortex.sim simulation a rollout of the checked spec `s` runs,
  before its first step: the creature loaded, placed as its seed says,
  built, over its floor. To watch a rollout, show it with sim/world and
  `controller`."
  [{:keys [creature seed start floor observe solver scale]}]
  (let [c (doto ^Node (blender/load-blender-model creature) (place! seed start))]
    (sim/simulation c (cond-> {:floor floor :observe (into #{:joints :segments} observe)
                               :scale (or scale :auto)}
                        solver (assoc :solver solver)))))

(defn controller
  "The controller proper of the checked spec `s`: a function from an
  observation to actions (none without a :controller)."
  [{:keys [controller params]}]
  (if-let [make (controller-maker controller)] (make params) (constantly nil)))

(defn run-checked
  "Run the checked spec `s` (see `check-spec!`); the result."
  [{:keys [creature seconds torso fall-angle trajectory] :as s}]
  (let [sim (simulation s)]
    (try
      (let [weights (into (sorted-map) (for [[n rb] (:segments sim)
                                             :let [m (mass rb)] :when (pos? m)]
                                         [n m]))
            _ (when (empty? weights)
                (throw (ex-info (str creature " has no segment that moves") {:creature creature})))
            torso (or torso (key (apply max-key val (reverse (seq weights)))))
            _ (when-not (contains? weights torso)
                (throw (ex-info (str creature " has no moving segment " (pr-str torso)
                                     "; its segments are " (str/join ", " (keys weights)))
                                {:torso torso})))
            control (controller s)
            dt (/ 1.0 60.0)
            n (long (Math/round (* 60.0 (double seconds))))
            obs0 (sim/observe sim)
            start-centre (centre weights obs0)
            q0 (as-doubles (get-in obs0 [:segments torso :rotation]))
            local-up (p/rotate (p/q-conj q0) up)
            entry (fn [obs efforts]
                    {:time (double (:time obs)) :centre (centre weights obs)
                     :tilt (tilt torso local-up obs) :joints (into (sorted-map) (:joints obs))
                     :efforts (into (sorted-map) efforts)})
            thread (Thread/currentThread)]
        (loop [i 0 obs obs0 energy 0.0 max-tilt 0.0 fell-at nil
               traj (when trajectory [(entry obs0 nil)])]
          (if (< i n)
            (do (when (.isInterrupted thread)
                  (throw (InterruptedException. "rollout interrupted")))
                (let [obs (sim/step! sim (control obs))
                      efforts (sim/last-efforts sim)
                      t (tilt torso local-up obs)
                      i (inc i)]
                  (recur i obs (+ energy (* dt (power efforts (:joints obs))))
                         (max max-tilt t)
                         (or fell-at (when (> t (double fall-angle)) (double (:time obs))))
                         (if (and traj (zero? (mod i (long trajectory))))
                           (conj traj (entry obs efforts))
                           traj))))
            (let [d (mapv - (centre weights obs) start-centre)]
              (cond-> {:spec s
                       :distance (Math/hypot (d 0) (d 2))
                       :displacement d
                       :energy energy
                       :fell? (some? fell-at) :fell-at fell-at :max-tilt max-tilt
                       :torso torso
                       :steps n :seconds (/ (double n) 60.0)
                       :final-pose (pose obs)}
                traj (assoc :trajectory traj))))))
      (finally (sim/destroy! sim)))))

(defn ^:api rollout
  "Run one rollout of `spec` (see the chapter for its keys) on this
  thread; its result as plain data. Bad specs are ex-infos naming the
  field; a failure while running is thrown."
  [spec]
  (run-checked (check-spec! nil spec)))

(defn error-of
  "Plain data about the Throwable `e`: :message, :class, :data (EDN
  text) and the :cause's message."
  [^Throwable e]
  (cond-> {:message (str (ex-message e)) :class (.getName (class e))}
    (ex-data e) (assoc :data (binding [*print-length* 20 *print-level* 4]
                               (pr-str (dissoc (ex-data e) :spec))))
    (.getCause e) (assoc :cause (str (ex-message (.getCause e))))))

(defn ^:api try-rollout
  "The result of the checked spec `s`, or {:spec s :error ...} when
  running it throws."
  [s]
  (try (run-checked s)
       (catch InterruptedException e (throw e))
       (catch Throwable e {:spec s :error (error-of e)})))

(def ^:private pool-number (AtomicLong.))

(defn- pool
  ^ExecutorService [threads]
  (let [k (.incrementAndGet ^AtomicLong pool-number)
        made (AtomicLong.)]
    (Executors/newFixedThreadPool
     (int threads)
     (reify ThreadFactory
       (newThread [_ r]
         (doto (Thread. r (str "cortex-rollout-" k "-" (.incrementAndGet made)))
           (.setDaemon true)))))))

(defn available-threads
  "The processors the JVM may use."
  ^long []
  (.availableProcessors (Runtime/getRuntime)))

(defn ^:api rollouts
  "Run every spec of `specs` (see `rollout`) on a fixed pool of
  :threads threads (default: one per processor); their results in the
  order of `specs`, each equal to what `rollout` returns for it alone.
  Every spec is checked before any runs (an ex-info names the first bad
  one by index, and its field); a rollout that throws gives a result
  with :error instead, and the others still run."
  ([specs] (rollouts specs {}))
  ([specs {:keys [threads]}]
   (let [checked (check-specs! specs)
         threads (or threads (available-threads))]
     (when-not (pos-int? threads)
       (throw (ex-info (str ":threads must be a positive whole number, not " (pr-str threads)) {})))
     (if (empty? checked)
       []
       (let [p (pool (min (long threads) (count checked)))]
         (try
           (let [futures (mapv (fn [s] (.submit p ^Callable (fn [] (try-rollout s)))) checked)]
             (mapv #(.get ^Future %) futures))
           (finally (.shutdownNow p))))))))

(def ^:api columns
  "The columns of a result's row: [name type], type one of :long,
  :double, :boolean, :string; every column may be empty (nil)."
  [["index" :long] ["id" :string] ["creature" :string] ["controller" :string]
   ["params" :string] ["seconds" :double] ["seed" :long]
   ["distance" :double] ["dx" :double] ["dy" :double] ["dz" :double]
   ["energy" :double] ["fell" :boolean] ["fell_at" :double] ["max_tilt" :double]
   ["steps" :long] ["error" :string] ["result" :string]])

(defn edn
  "`x` as EDN text, whole (no print length or level)."
  [x]
  (binding [*print-length* nil *print-level* nil *print-meta* false
            *print-namespace-maps* false]
    (pr-str x)))

(defn ^:api flat-row
  "The values of `columns` for `result`, the `index`-th."
  [index {:keys [spec distance displacement energy fell? fell-at max-tilt steps error] :as result}]
  (let [{:keys [id creature controller params seconds seed]} spec
        [dx dy dz] displacement]
    [(long index) (some-> id edn) creature (some-> controller str) (edn params)
     (some-> seconds double) (some-> seed long)
     distance dx dy dz energy (when-not error (boolean fell?)) fell-at max-tilt
     (some-> steps long) (some-> error :message) (edn result)]))

(defn- check-param!
  [params k ok? what]
  (let [v (get params k)]
    (when-not (ok? v)
      (throw (ex-info (str k " must be " what ", not " (pr-str v)) {:param k :value v})))
    v))

(defn- check-joint-params!
  [params]
  (check-param! params :joints #(or (nil? %) (and (sequential? %) (every? string? %)))
                "nil or a vector of joint names")
  (check-param! params :phases #(or (nil? %) (and (map? %) (every? finite? (vals %))))
                "nil or {joint fraction}"))

(defn ^:api crawl-gait
  "A controller (see org/rollout.org): the slow arch and quick release
  of the worm's crawl at every hinge (or those in :joints). `params`:
  :frequency (Hz, default 1.5), :amplitude (rad, 0.6), :rise (fraction
  of a cycle rising, 0.8), :delay (s before it starts, 0.5), :phases
  ({joint fraction}, 0)."
  [params]
  (let [params (merge {:frequency 1.5 :amplitude 0.6 :rise 0.8 :delay 0.5} params)
        f (double (check-param! params :frequency #(and (finite? %) (pos? (double %)))
                                "a positive number of hertz"))
        a (double (check-param! params :amplitude finite? "a finite angle"))
        up (double (check-param! params :rise #(and (finite? %) (< 0 (double %) 1))
                                 "a fraction between 0 and 1"))
        delay (double (check-param! params :delay #(and (finite? %) (not (neg? (double %))))
                                    "a time of at least 0"))
        _ (check-joint-params! params)
        {:keys [joints phases]} params]
    (fn [{:keys [time] :as observation}]
      (let [names (or joints (sort (for [[n j] (:joints observation) :when (= :hinge (:type j))] n)))]
        (into {} (for [n names
                       :let [phase (mod (+ (* f (max 0.0 (- (double time) delay)))
                                           (double (get phases n 0.0)))
                                        1.0)]]
                   [n {:target (* a (if (< phase up)
                                      (/ phase up)
                                      (- 1 (/ (- phase up) (- 1 up)))))}]))))))

(defn ^:api sine-gait
  "A controller (see org/rollout.org): every joint (or those in :joints)
  follows amplitude sin(2 pi (frequency t + k phase)), k its place in
  name order; a hinge as its angle, a cone or point joint as a rotation
  about its frame's Z. `params`: :frequency (Hz, 1.0), :amplitude
  (rad, 0.3), :phase (fraction, 0.25), :phases ({joint fraction},
  overriding k phase)."
  [params]
  (let [params (merge {:frequency 1.0 :amplitude 0.3 :phase 0.25} params)
        f (double (check-param! params :frequency #(and (finite? %) (not (neg? (double %))))
                                "a number of hertz, at least 0"))
        a (double (check-param! params :amplitude finite? "a finite angle"))
        step (double (check-param! params :phase finite? "a finite fraction"))
        _ (check-joint-params! params)
        {:keys [joints phases]} params]
    (fn [{:keys [time] :as observation}]
      (let [names (or joints (sort (keys (:joints observation))))]
        (into {} (map-indexed
                  (fn [k n]
                    (let [phi (double (get phases n (* k step)))
                          x (* a (Math/sin (* 2.0 Math/PI (+ (* f (double time)) phi))))]
                      [n {:target (if (= :hinge (get-in observation [:joints n :type]))
                                    x
                                    [0.0 0.0 x])}]))
                  names))))))
