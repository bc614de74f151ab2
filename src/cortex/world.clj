;; Generated from org/world.org by lein tangle: edit the chapter, not this file.
(ns cortex.world
  "Worlds: jMonkeyEngine applications with Bullet physics, built from a
  scene, a key map and two functions, that run in a window for people
  or headless, for an exact number of frames, for tests.

  Entry points: `world` (make one), `run-world!` (run it headless for N
  frames), `start!`, `stop!`, `await!`, `running?` and `enqueue!` (a world
  that lives beside the REPL), `set-gravity`, `speed-up`, `enable-debug`,
  `add-element!`, `fire-cannon-ball`, `standard-debug-controls`, `no-op`,
  `physics-space`."
  (:require [clojure.string :as str]
            [cortex.engine :as engine]
            [cortex.projection :as projection]
            [cortex.util :as util])
  (:import (com.jme3.app FlyCamAppState LegacyApplication SimpleApplication)
           (com.jme3.app.state AbstractAppState AppState)
           (com.jme3.bullet BulletAppState BulletAppState$ThreadingType
                            PhysicsSpace)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.input KeyInput MouseInput)
           (com.jme3.input.controls ActionListener KeyTrigger
                                    MouseButtonTrigger Trigger)
           (com.jme3.material TechniqueDef$LightMode)
           (com.jme3.math ColorRGBA Vector3f)
           (com.jme3.scene Node Spatial)
           (com.jme3.system AppSettings JmeContext$Type)
           (cortex RatchetTimer)
           (java.lang.reflect Method)
           (java.util.concurrent Callable)
           (java.util.logging Handler Logger LogRecord SimpleFormatter)))

(set! *warn-on-reflection* true)

(defn ^:api no-op
  "Does nothing, whatever it is given: the update function of a world
  that needs none."
  [& _])

(defn trigger
  "The jME input trigger a key-map name stands for: \"key-space\",
  \"key-a\", \"key-f1\"... name the keys of com.jme3.input.KeyInput;
  \"mouse-left\", \"mouse-right\" and \"mouse-middle\" the buttons."
  ^Trigger [^String input-name]
  (let [[kind key] (str/split input-name #"-" 2)
        field (str (case kind "key" "KEY_" "mouse" "BUTTON_" "") (str/upper-case (or key "")))
        klass (case kind "key" KeyInput "mouse" MouseInput nil)
        value (when (and klass key)
                (try (.getInt (.getField ^Class klass field) nil)
                     (catch NoSuchFieldException _ nil)))]
    (cond
      (nil? value)
      (throw (ex-info (str "no such input: " (pr-str input-name)
                           " (use names like \"key-space\", \"key-a\", \"mouse-left\")")
                      {:input input-name}))
      (= kind "key") (KeyTrigger. value)
      :else (MouseButtonTrigger. value))))

(defn bind-keys!
  "Map each input in `key-map` (a name understood by `trigger`) to its
  function, called as (f world pressed?) on press and on release."
  [^SimpleApplication world key-map]
  (let [input (.getInputManager world)]
    (doseq [[input-name f] key-map]
      (.addMapping input ^String input-name
                   (into-array Trigger [(trigger input-name)]))
      (.addListener input
                    (reify ActionListener
                      (onAction [_ _ pressed? _] (f world pressed?)))
                    (into-array String [input-name])))
    world))

(defn physics
  "The world's BulletAppState; once a run has ended, that run's (see
  \"Starting again\" below)."
  ^BulletAppState [^SimpleApplication world]
  (or (.getState (.getStateManager world) BulletAppState)
      (some-> (meta world) ::state deref ::physics)))

(defn physics-space
  "The world's Bullet PhysicsSpace."
  ^PhysicsSpace [world]
  (.getPhysicsSpace (physics world)))

(def simulation-key
  "The user data under which a creature carries how its world should
  step (cortex.physics-tab/simulation-settings)."
  "blender-simulation")

(defn substep-length
  "The largest float a such that Java's float arithmetic gives
  (int) ((float) x / a) >= k, for x = t/60 as a float: Bullet's fixed
  step loop then runs exactly k substeps of a in a step of x (or more,
  clamped to k)."
  [t k]
  (let [x (float (* (float (/ 1.0 60.0)) (float t)))]
    (loop [a (float (/ x (float k)))]
      (if (>= (int (float (/ (double x) (double a)))) (long k))
        a
        (recur (Math/nextDown a))))))

(def max-thin-substeps
  "The most substeps a world takes for its thinnest body (a flat one
  would ask for ever more)."
  16)

(defn substeps-for
  "Bullet steps per 1/60 s for a world whose thinnest moving body is
  `thickness` thick (nil: none): 1 down to cortex.engine/thin, below it
  sqrt(thin / thickness) rounded up (but for a thousandth: thicknesses
  are read from floats), at most `max-thin-substeps`."
  ^long [thickness]
  (if (and thickness (< (double thickness) (double engine/thin)))
    (min max-thin-substeps
         (long (Math/ceil (- (Math/sqrt (/ (double engine/thin) (max 1e-9 (double thickness))))
                             0.001))))
    1))

(defn thinnest
  "The smallest thickness (cortex.engine/thickness) of the moving bodies
  in `space`, or nil."
  [^PhysicsSpace space]
  (let [ts (keep (fn [^PhysicsRigidBody b]
                   (when (pos? (.getMass b)) (engine/thickness (.getCollisionShape b))))
                 (.getRigidBodyList space))]
    (when (seq ts) (apply min ts))))

(defn step-thin-bodies!
  "Give `space` the substeps its thinnest moving body needs
  (`substeps-for`), when that is more than one, at time scale `t` (1 by
  default); the number of substeps."
  (^long [space] (step-thin-bodies! space 1.0))
  (^long [^PhysicsSpace space t]
   (let [k (substeps-for (thinnest space))]
     (when (> k 1)
       (.setAccuracy space (float (substep-length t k)))
       (.setMaxSubSteps space (int k)))
     k)))

(defn world-settings
  "jME settings for a cortex world: a 800x600 window titled cortex, no
  settings dialog, no audio."
  ^AppSettings []
  (doto (AppSettings. true)
    (.setTitle "cortex")
    (.setResolution 800 600)
    (.setAudioRenderer nil)))

(defn- guard
  "Call (f), recording any Throwable as the world's :error and stopping
  the world, so that a failure on jME's thread ends the run instead of
  killing the thread silently."
  [^SimpleApplication world state f]
  (try (f)
       (catch Throwable t
         (swap! state update :error #(or % t))
         (.stop world))))

(defn- run-state
  "The atom that holds `world`'s state."
  [world]
  (::state (meta world)))

(defn- public-state
  "What @world shows of a world's state: everything but this
  namespace's own keys."
  [m]
  (into {} (remove (comp qualified-keyword? key)) m))

(defn- failure-text
  "One line on why a world failed, after how many frames."
  [frames ^Throwable e]
  (str "world failed after " frames " frames: " (or (ex-message e) (str e))))

(defn- forward-log!
  "Print a java.util.logging record to *err*, when *err* is bound on
  this thread to something else than the process's standard error."
  [^LogRecord record]
  (when-not (identical? *err* (.getRawRoot #'*err*))
    (binding [*out* *err*]
      (println (str (.getLevel record) ": " (.formatMessage (SimpleFormatter.) record)))
      (some-> (.getThrown record) ex-message println))))

(defn- forward-logs!
  "Make sure the root logger has one handler that forwards records to
  the *err* of the thread that logs them (see `forward-log!`)."
  []
  (let [root (Logger/getLogger "")
        handler (proxy [Handler] []
                  (publish [record] (try (forward-log! record) (catch Throwable _)))
                  (flush [])
                  (close []))]
    (locking root
      (doseq [^Handler h (.getHandlers root)
              :when (= (class h) (class handler))]
        (.removeHandler root h))
      (.addHandler root handler))))

(def ^:private log-forwarding (delay (forward-logs!)))

(def ^:private ^Method init-state-manager
  "LegacyApplication's private initStateManager: make a new, empty
  AppStateManager for the application."
  (doto (.getDeclaredMethod LegacyApplication "initStateManager" (make-array Class 0))
    (.setAccessible true)))

(defn- release-bodies!
  "Take every joint and body out of `world`'s physics space while the
  space still works, so that they can join the space of its next run."
  [world]
  (when-let [^BulletAppState state (physics world)]
    (when-let [space (.getPhysicsSpace state)]
      (doseq [joint (vec (.getJointList space))]
        (.remove space joint))
      (doseq [body (concat (vec (.getRigidBodyList space))
                           (vec (.getGhostObjectList space))
                           (vec (.getCharacterList space)))]
        (.remove space body)))))

(defn- renew-states!
  "Give a stopped `world` what it had when it was made: a new state
  manager holding a fly-by camera."
  [^SimpleApplication world]
  (.invoke init-state-manager world (object-array 0))
  (.attach (.getStateManager world) (FlyCamAppState.)))

(defn- finish!
  "End the current run of the world whose state is `state`: deliver its
  :done promise, once, and, for a world started with `start!`, print
  its failure, if any, to the *err* of whoever started it."
  [state]
  (let [{:keys [done error frames] ::keys [report? err]} @state]
    (when (and (deliver done true) error report?)
      (binding [*out* (or err *err*)]
        (println (failure-text frames error))
        (flush)))))

(defn ^:api world
  "A jME application with Bullet physics, not yet started.

  `root-node` is attached to the root node and its rigid bodies and
  joints are added to the physics space; `key-map` maps input names
  (see `trigger`) to functions of [world pressed?]; (setup-fn world)
  runs once each time the world starts; (update-fn world tpf) runs every
  frame. Run it headless with `run-world!`, or start it beside the REPL
  with `start!` (see also cortex.render/start-window!). Dereferencing
  the world gives its state: :frames run so far, the :thread it runs
  on, the :error that stopped it, if any, and :done, delivered when its
  run has ended."
  [^Node root-node key-map setup-fn update-fn]
  (let [settings (world-settings)
        state (atom {:frames 0 :done (promise) :settings settings})]
    (doto
        (proxy [SimpleApplication clojure.lang.IDeref clojure.lang.IMeta]
            [(into-array AppState [(FlyCamAppState.)])]
          (deref [] (public-state @state))
          (meta [] {::state state})
          (initialize []
            ;; started with .start itself, after an earlier run
            (when (realized? (:done @state))
              (swap! state assoc :done (promise) :error nil :frames 0))
            (let [{::keys [out err]} @state]
              (push-thread-bindings {#'*out* (or out *out*) #'*err* (or err *err*)}))
            (swap! state assoc :thread (Thread/currentThread)
                   ::bound (Thread/currentThread) ::launched true)
            (let [^SimpleApplication this this]
              (guard this state #(proxy-super initialize))
              (when (::stop-requested @state)
                (.stop this))))
          (simpleInitApp []
            (let [^SimpleApplication this this
                  physics-state (doto (BulletAppState.)
                                  (.setThreadingType BulletAppState$ThreadingType/SEQUENTIAL))]
              (.attach (.getStateManager this) physics-state)
              ;; single-pass lighting, as the eyes have it: its shader
              ;; lights the back of a face drawn on both sides (an open
              ;; mesh, see the Blender chapter) by the face's back
              (.setPreferredLightMode (.getRenderManager this) TechniqueDef$LightMode/SinglePass)
              ;; the engine's settings that cortex makes the same (org/engine.org)
              (some-> (.getPhysicsSpace physics-state) engine/configure-space! projection/install!)
              (swap! state assoc ::physics physics-state)
              (.attachChild (.getRootNode this) root-node)
              (engine/add-all! (.getPhysicsSpace physics-state) (.getRootNode this))
              ;; small bodies take more substeps (above)
              (step-thin-bodies! (.getPhysicsSpace physics-state))
              (bind-keys! this key-map)
              (setup-fn this)))
          (update []
            (when-not (:error @state)
              (let [^SimpleApplication this this]
                (guard this state #(proxy-super update)))
              (swap! state update :frames inc)))
          (simpleUpdate [tpf]
            (update-fn this tpf))
          (handleError [message t]
            (swap! state update :error
                   #(or % (ex-info (str "world failed: " message) {} t)))
            (.stop ^SimpleApplication this))
          (destroy []
            (let [^SimpleApplication this this
                  note! (fn [t] (swap! state update :error #(or % t)))]
              (try (release-bodies! this) (catch Throwable t (note! t)))
              (try (proxy-super destroy) (catch Throwable t (note! t)))
              (try (renew-states! this) (catch Throwable t (note! t)))
              (finish! state)
              (when (identical? (::bound @state) (Thread/currentThread))
                (swap! state dissoc ::bound)
                (pop-thread-bindings)))))
      (.setShowSettings false)
      (.setSettings settings))))

(defn ^:api running?
  "True from the moment `world` is started until its run has ended."
  [world]
  (let [{:keys [done] ::keys [launched]} @(run-state world)]
    (boolean (and launched (not (realized? done))))))

(defn- on-world-thread?
  "True when called on `world`'s own thread."
  [world]
  (let [{:keys [thread] ::keys [launcher]} @(run-state world)
        here (Thread/currentThread)]
    (or (identical? here thread) (identical? here launcher))))

(defn- launch!
  "Start a new run of `world` in a context of type `context-type`,
  returning at once. `report?`: print a failure to the caller's *err*
  (see `finish!`). Returns the world."
  [^SimpleApplication world ^JmeContext$Type context-type report?]
  (when (running? world)
    (throw (ex-info "the world is already running: stop! it first" {})))
  @log-forwarding
  (let [state (run-state world)]
    (swap! state merge {:frames 0 :error nil :thread nil :done (promise)
                        ::launched true ::stop-requested false ::report? report?
                        ::out *out* ::err *err* ::launcher nil})
    ;; jME replaces the world's settings with its context's copy, which a
    ;; context may have changed (cortex.SurfacelessContext names the
    ;; renderer it really uses); every run starts from the world's own
    (.setSettings world ^AppSettings (:settings @state))
    (if (= JmeContext$Type/Display context-type)
      (let [launcher (Thread. ^Runnable
                              (fn []
                                (try (.start world context-type)
                                     (catch Throwable t
                                       (swap! state update :error #(or % t)))
                                     (finally (finish! state))))
                              "cortex world")]
        (swap! state assoc ::launcher launcher)
        (doto launcher (.setDaemon true) (.start)))
      (.start world context-type))
    world))

(defn- ended?
  "Whether the run whose state is `state` has ended; a run that failed
  before its world had a thread is ended here (see `finish!`)."
  [state]
  (let [{:keys [done error thread] ::keys [launcher]} @state]
    (or (realized? done)
        (when (and error (nil? thread) (not (some-> ^Thread launcher .isAlive)))
          (finish! state)
          true))))

(defn- wait-for-end
  "Wait until the current run of `world` has ended and its threads have
  finished, no longer than `timeout-ms` (nil: as long as it takes).
  True when it has ended. Interrupting the wait throws
  InterruptedException."
  [world timeout-ms]
  (let [state (run-state world)
        deadline (some->> timeout-ms (+ (System/currentTimeMillis)))
        left #(- deadline (System/currentTimeMillis))]
    (loop []
      (cond
        (ended? state)
        (let [{:keys [thread] ::keys [launcher]} @state]
          (doseq [^Thread t (distinct (remove nil? [thread launcher]))
                  :when (not (identical? t (Thread/currentThread)))]
            (if deadline
              (.join t (max 1 (left)))
              (.join t)))
          true)

        (and deadline (<= (left) 0)) false

        :else (do (deref (:done @state) (if deadline (max 1 (min 100 (left))) 100) nil)
                  (recur))))))

(defn- request-stop!
  "Ask `world` to stop at the end of its current frame."
  [^SimpleApplication world]
  (swap! (run-state world) assoc ::stop-requested true)
  (when (.getContext world)
    (.stop world)))

(defn- frame-limit
  "An AppState that stops `world` at the end of frame `n`."
  ^AppState [^SimpleApplication world n]
  (let [seen (atom 0)]
    (proxy [AbstractAppState] []
      (postRender []
        (when (= n (swap! seen inc))
          (.stop world))))))

(defn ^:api run-world!
  "Run `world` headless (no window, no GPU: jME's null renderer) for
  exactly `frames` frames, blocking until it has stopped and its thread
  has ended. A world without a fixed-step timer gets a 60 fps
  RatchetTimer, so that runs repeat exactly. Throws an ex-info if the
  world failed, did not finish within :timeout-ms (default ten minutes),
  or the waiting thread was interrupted (then the world is stopped
  first). :context-type, a JmeContext$Type, replaces the null renderer
  with another context: cortex.render passes OffscreenSurface to draw
  real frames without a window. Returns the world."
  ([world frames] (run-world! world frames {}))
  ([^SimpleApplication world frames {:keys [timeout-ms context-type]
                                     :or {timeout-ms 600000
                                          context-type JmeContext$Type/Headless}}]
   (when-not (pos-int? frames)
     (throw (ex-info (str "frames must be a positive integer, not " (pr-str frames))
                     {:frames frames})))
   (when (running? world)
     (throw (ex-info "the world is already running: stop! it first" {})))
   (.attach (.getStateManager world) (frame-limit world frames))
   (when-not (instance? RatchetTimer (.getTimer world))
     (.setTimer world (RatchetTimer. 60)))
   ;; jME's null context throttles a non-positive rate to 60 fps
   (.setFrameRate ^AppSettings (:settings @world) Integer/MAX_VALUE)
   (launch! world context-type false)
   (let [finished? (try (wait-for-end world timeout-ms)
                        (catch InterruptedException e
                          (request-stop! world)
                          (wait-for-end world 10000)
                          (throw (ex-info (str "interrupted: the world was stopped after "
                                               (:frames @world) " frames")
                                          {:frames (:frames @world)} e))))]
     (when-not finished?
       (request-stop! world)
       (wait-for-end world 10000))
     (cond
       (:error @world)
       (throw (ex-info (failure-text (:frames @world) (:error @world))
                       {:frames (:frames @world)} (:error @world)))
       (not finished?)
       (throw (ex-info (str "world did not finish " frames " frames in "
                            timeout-ms " ms")
                       {:frames (:frames @world)}))
       :else world))))

(defn ^:api start!
  "Start `world` on a thread of its own and return it at once; it runs
  until `stop!`, Escape, or a failure, which is printed to the *err* of
  the caller. What the world's thread prints goes to the caller's *out*
  and *err*. A world without a fixed-step timer gets a 60 fps
  RatchetTimer. Options: :context-type, a JmeContext$Type (default
  Headless; cortex.render/start-window! and start-offscreen! pass
  theirs), and :fps, the most frames a second it runs (default 60).
  A stopped world can be started again: it goes on from where it
  stopped, and its setup function runs again. Throws an ex-info if the
  world is already running. Returns the world."
  ([world] (start! world {}))
  ([^SimpleApplication world {:keys [context-type fps]
                              :or {context-type JmeContext$Type/Headless fps 60}}]
   (when (running? world)
     (throw (ex-info "the world is already running: stop! it first" {})))
   (when-not (instance? RatchetTimer (.getTimer world))
     (.setTimer world (RatchetTimer. 60)))
   (.setFrameRate ^AppSettings (:settings @world) (int fps))
   (launch! world context-type true)))

(defn ^:api stop!
  "Stop `world` and wait until it has stopped and its thread has ended,
  no longer than `timeout-ms` when given. On the world's own thread,
  only ask it to stop (it does at the end of the frame). A world that is
  not running is left alone. Returns the world."
  ([world] (stop! world nil))
  ([world timeout-ms]
   (when (running? world)
     (request-stop! world)
     (when-not (on-world-thread? world)
       (wait-for-end world timeout-ms)))
   world))

(defn ^:api await!
  "Wait until a started `world` has ended (stop!, Escape, its window
  closed, a failure) and its thread has finished; with `timeout-ms`, no
  longer than that, returning nil if it is still running then. Throws
  an ex-info if the run failed. Interrupting the wait leaves the world
  running. Returns the world."
  ([world] (await! world nil))
  ([world timeout-ms]
   (when (if (::launched @(run-state world))
           (wait-for-end world timeout-ms)
           true)
     (when-let [e (:error @world)]
       (throw (ex-info (failure-text (:frames @world) e) {:frames (:frames @world)} e)))
     world)))

(defn ^:api enqueue!
  "Call (f) on `world`'s thread, between two frames, and return its
  value (or throw what it threw): the safe way to change a running
  world from the REPL, e.g.
  (enqueue! w #(set-gravity w (Vector3f. 0 -1.62 0))).
  On the world's own thread, or when the world is not running, (f) is
  simply called. Throws an ex-info when the world stops before it has
  run (f)."
  [^SimpleApplication world f]
  (if (or (not (running? world)) (on-world-thread? world))
    (f)
    (let [result (promise)
          done (:done @world)
          answer (fn [[ok? value]] (if ok? value (throw value)))]
      (.enqueue world ^Callable (fn []
                                  (deliver result (try [true (f)]
                                                       (catch Throwable t [false t])))
                                  nil))
      (loop []
        (if-let [r (deref result 50 nil)]
          (answer r)
          (if (realized? done)
            (if-let [r (deref result 0 nil)]
              (answer r)
              (throw (ex-info "the world stopped before it could run the function" {})))
            (recur)))))))

(defn add-element!
  "Attach `element` to `node` (the world's root node unless given) and
  put its rigid bodies and joints into the world's physics space.
  Returns the element."
  ([world element] (add-element! world element (.getRootNode ^SimpleApplication world)))
  ([world ^Spatial element ^Node node]
   (.attachChild node element)
   (engine/add-all! (physics-space world) element)
   element))

(defn fire-cannon-ball
  "A key-map function that fires a heavy white ball from the camera
  along its line of sight when the key is released. The ball joins
  `node`, the world's root node unless given."
  ([] (fire-cannon-ball nil))
  ([node]
   (fn [^SimpleApplication world pressed?]
     (when-not pressed?
       (let [camera (.getCamera world)
             ball (util/sphere 0.7 :name "cannon-ball" :color ColorRGBA/White
                               :mass 3
                               :position (.add (.getLocation camera)
                                               (.getDirection camera)))]
         (.setLinearVelocity ^RigidBodyControl (.getControl ^Spatial ball RigidBodyControl)
                             (.mult (.getDirection camera) (float 50)))
         (add-element! world ball (or node (.getRootNode world))))))))

(def ^:api standard-debug-controls
  "The keys every test world has: space fires a cannon ball. The fly-by
  camera moves with W, A, S, D, Q and Z and turns with the mouse or the
  arrows; Escape quits."
  {"key-space" (fire-cannon-ball)})

(defn ^:api set-gravity
  "Set the world's gravity. Bullet gives each rigid body its own copy
  of gravity when the body joins the space, so the bodies already there
  are changed, and woken, too. Returns the world."
  [world ^Vector3f gravity]
  (let [space (physics-space world)]
    (.setGravity space gravity)
    (doseq [^PhysicsRigidBody body (.getRigidBodyList space)]
      (.setGravity body gravity)
      (.activate body))
    world))

(defn enable-debug
  "Draw the world's collision shapes and joints over the scene. Returns
  the world."
  [world]
  (.setDebugEnabled (physics world) true)
  world)

(defn speed-up
  "Make the fly-by camera quick enough for scenes the size of a room,
  instead of jME's walking pace. Returns the world."
  [^SimpleApplication world]
  (doto (.getFlyByCamera world)
    (.setMoveSpeed 60)
    (.setRotationSpeed 3))
  world)
