(ns cortex.world
  "Worlds: jMonkeyEngine applications with Bullet physics, built from a
  scene, a key map and two functions, that run in a window for people
  or headless, for an exact number of frames, for tests.

  Entry points: `world` (make one), `run-world!` (run it headless for N
  frames), `set-gravity`, `speed-up`, `enable-debug`, `add-element!`,
  `fire-cannon-ball`, `standard-debug-controls`, `no-op`, `physics-space`."
  (:require [clojure.string :as str]
            [cortex.util :as util])
  (:import (com.jme3.app FlyCamAppState SimpleApplication)
           (com.jme3.app.state AbstractAppState AppState)
           (com.jme3.bullet BulletAppState BulletAppState$ThreadingType
                            PhysicsSpace)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.input KeyInput MouseInput)
           (com.jme3.input.controls ActionListener KeyTrigger
                                    MouseButtonTrigger Trigger)
           (com.jme3.math ColorRGBA Vector3f)
           (com.jme3.scene Node Spatial)
           (com.jme3.system AppSettings JmeContext$Type)
           (cortex RatchetTimer)))

(set! *warn-on-reflection* true)

(defn no-op
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
  "The world's BulletAppState."
  ^BulletAppState [^SimpleApplication world]
  (.getState (.getStateManager world) BulletAppState))

(defn physics-space
  "The world's Bullet PhysicsSpace."
  ^PhysicsSpace [world]
  (.getPhysicsSpace (physics world)))

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

(defn world
  "A jME application with Bullet physics, not yet started.

  `root-node` is attached to the root node and its rigid bodies and
  joints are added to the physics space; `key-map` maps input names
  (see `trigger`) to functions of [world pressed?]; (setup-fn world)
  runs once when the world starts; (update-fn world tpf) runs every
  frame. Start it in a window with (.start world), or headless with
  `run-world!`. Dereferencing the world gives its state: :frames run so
  far and the :error that stopped it, if any."
  [^Node root-node key-map setup-fn update-fn]
  (let [settings (world-settings)
        state (atom {:frames 0 :done (promise) :settings settings})
        physics-state (doto (BulletAppState.)
                        (.setThreadingType BulletAppState$ThreadingType/SEQUENTIAL))]
    (doto
        (proxy [SimpleApplication clojure.lang.IDeref]
            [(into-array AppState [(FlyCamAppState.)])]
          (deref [] @state)
          (initialize []
            (swap! state assoc :thread (Thread/currentThread))
            (let [^SimpleApplication this this]
              (guard this state #(proxy-super initialize))))
          (simpleInitApp []
            (.attach (.getStateManager ^SimpleApplication this) physics-state)
            (.attachChild (.getRootNode ^SimpleApplication this) root-node)
            (.addAll (.getPhysicsSpace physics-state) root-node)
            (bind-keys! this key-map)
            (setup-fn this))
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
            (try (let [^SimpleApplication this this] (proxy-super destroy))
                 (catch Throwable t
                   (swap! state update :error #(or % t)))
                 (finally (deliver (:done @state) true)))))
      (.setShowSettings false)
      (.setSettings settings))))

(defn- frame-limit
  "An AppState that stops `world` at the end of frame `n`."
  ^AppState [^SimpleApplication world n]
  (let [seen (atom 0)]
    (proxy [AbstractAppState] []
      (postRender []
        (when (= n (swap! seen inc))
          (.stop world))))))

(defn run-world!
  "Run `world` headless (no window, no GPU: jME's null renderer) for
  exactly `frames` frames, blocking until it has stopped and its thread
  has ended. A world without a fixed-step timer gets a 60 fps
  RatchetTimer, so that runs repeat exactly. Throws an ex-info if the
  world failed, or did not finish within :timeout-ms (default ten
  minutes). :context-type, a JmeContext$Type, replaces the null
  renderer with another context: cortex.render passes OffscreenSurface
  to draw real frames without a window. Returns the world."
  ([world frames] (run-world! world frames {}))
  ([^SimpleApplication world frames {:keys [timeout-ms context-type]
                                     :or {timeout-ms 600000
                                          context-type JmeContext$Type/Headless}}]
   (when-not (pos-int? frames)
     (throw (ex-info (str "frames must be a positive integer, not " (pr-str frames))
                     {:frames frames})))
   (let [done (:done @world)]
     (.attach (.getStateManager world) (frame-limit world frames))
     (when-not (instance? RatchetTimer (.getTimer world))
       (.setTimer world (RatchetTimer. 60)))
     ;; jME's null context throttles a non-positive rate to 60 fps
     (.setFrameRate ^AppSettings (:settings @world) Integer/MAX_VALUE)
     (.start world ^JmeContext$Type context-type)
     (let [finished? (deref done timeout-ms false)
           ^Thread thread (:thread @world)]
       (when-not finished?
         (.stop world))
       (some-> thread (.join 10000))
       (cond
         (:error @world)
         (throw (ex-info (str "world failed after " (:frames @world) " frames: "
                              (ex-message (:error @world)))
                         {:frames (:frames @world)} (:error @world)))
         (not finished?)
         (throw (ex-info (str "world did not finish " frames " frames in "
                              timeout-ms " ms")
                         {:frames (:frames @world)}))
         :else world)))))

(defn add-element!
  "Attach `element` to `node` (the world's root node unless given) and
  put its rigid bodies and joints into the world's physics space.
  Returns the element."
  ([world element] (add-element! world element (.getRootNode ^SimpleApplication world)))
  ([world ^Spatial element ^Node node]
   (.attachChild node element)
   (.addAll (physics-space world) element)
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

(def standard-debug-controls
  "The keys every test world has: space fires a cannon ball. The fly-by
  camera moves with W, A, S, D, Q and Z and turns with the mouse or the
  arrows; Escape quits."
  {"key-space" (fire-cannon-ball)})

(defn set-gravity
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
