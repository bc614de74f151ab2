;; Generated from org/util.org by lein tangle: edit the chapter, not this file.
(ns cortex.util
  "Small helpers the rest of cortex leans on: walking scene graphs,
  making simple physical shapes, lights, coordinate changes between
  Blender and jMonkeyEngine, and printing from jME's thread.

  Entry points: `load-blender-model` (the reader's, once it is loaded),
  `asset-manager`, `box`, `sphere`, `nodify`, `node-seq`,
  `blender-to-jme`, `jme-to-blender`, `blender-axes`, `vec3`,
  `finite?`, `export-vars`, `edit-distance`, `near-miss` (the key an unknown key
  misspells), `light-up-everything`, `display-dilated-time`,
  `println-repl`."
  ;; the physics engine (org/engine.org): native Bullet loads its library here
  (:require [cortex.engine])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.app.state AbstractAppState)
           (com.jme3.asset AssetManager DesktopAssetManager)
           (com.jme3.asset.plugins FileLocator)
           (com.jme3.bullet.collision.shapes BoxCollisionShape
                                             SphereCollisionShape)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.font BitmapText)
           (com.jme3.light AmbientLight DirectionalLight)
           (com.jme3.material Material)
           (com.jme3.math ColorRGBA Matrix3f Quaternion Vector3f)
           (com.jme3.scene Geometry Node Spatial)
           (com.jme3.scene.shape Box Sphere)))

(set! *warn-on-reflection* true)

(defn node-seq
  "Every spatial under (and including) `root`, depth first."
  [^Spatial root]
  (tree-seq #(instance? Node %) #(seq (.getChildren ^Node %)) root))

(defn ^:api nodify
  "A new Node holding `children`, named `name` (\"\" when not given)."
  ([children] (nodify "" children))
  ([^String name children]
   (let [node (Node. name)]
     (doseq [^Spatial child children]
       (.attachChild node child))
     node)))

(defmacro export-vars
  "Define each of `syms` in the calling namespace as the var of that name
  in namespace `from` (already loaded), with its doc and arglists, and
  any metadata the symbol carries here (^:api marks a re-exported name
  as part of the public surface)."
  [from & syms]
  `(do ~@(for [s syms
               :let [v (resolve (symbol (name from) (name s)))]]
           `(def ~(with-meta s (merge (meta s) {:doc (:doc (meta v)) :arglists (list 'quote (:arglists (meta v)))}))
              ~(symbol (name from) (name s))))))

(defn map-vals
  "`m` with `f` applied to each of its values."
  [f m]
  (into (empty m) (for [[k v] m] [k (f v)])))

(defn finite?
  "Is `x` a number that is neither infinite nor NaN? Every number a
  designer or a file hands cortex passes this check before it reaches
  the physics."
  [x]
  (and (number? x) (Double/isFinite (double x))))

(defn edit-distance
  "Levenshtein distance between strings `a` and `b`: the fewest letters
  inserted, deleted or changed to turn one into the other."
  [^String a ^String b]
  (peek (reduce (fn [prev ca]
                  (reduce (fn [row [j cb]]
                            (conj row (min (inc (peek row)) (inc (prev (inc j)))
                                           (+ (prev j) (if (= ca cb) 0 1)))))
                          [(inc (first prev))]
                          (map-indexed vector b)))
                (vec (range (inc (count b))))
                a)))

(defn near-miss
  "The keyword of `known` that the unknown keyword `k` most likely
  misspells (within two letters; the nearest, then the first by name),
  or nil: what an error about an unknown key suggests instead."
  [k known]
  (when (keyword? k)
    (->> (sort-by name known)
         (map (fn [c] [(long (edit-distance (name k) (name c))) c]))
         (filter #(<= (long (first %)) 2))
         (sort-by first)
         first
         second)))

(defn vec3
  "The Vector3f of three numbers `[x y z]`."
  ^Vector3f [[x y z]]
  (Vector3f. (float x) (float y) (float z)))

(def ^Matrix3f blender-axes
  "The change from Blender's Z-up axes to jME's Y-up ones, as a rotation
  whose columns are Blender's X, Y and Z seen in jME: (x, y, z) -> (x, z,
  -y). Multiply a Blender vector by it to get the jME vector."
  (Matrix3f. 1 0 0
             0 0 1
             0 -1 0))

(defn jme-to-blender
  "A jME (Y-up) vector in Blender's Z-up coordinates."
  ^Vector3f [^Vector3f v]
  (Vector3f. (.x v) (- (.z v)) (.y v)))

(defn blender-to-jme
  "A Blender (Z-up) vector in jME's Y-up coordinates."
  ^Vector3f [^Vector3f v]
  (Vector3f. (.x v) (.z v) (- (.y v))))

(defn world-to-local
  "`world-point` in the coordinates of `spatial`, undoing its world
  translation, rotation and scale."
  ^Vector3f [^Spatial spatial ^Vector3f world-point]
  (.worldToLocal spatial world-point nil))

(def ^:private repl-out
  "The writer that was *out* when this namespace loaded: the REPL's."
  *out*)

(defn println-repl
  "println to the REPL that loaded cortex, even when called from jME's
  render thread, whose *out* is the process's standard output."
  [& args]
  (binding [*out* repl-out]
    (apply println args)
    (flush)))

(defn- new-asset-manager
  ^AssetManager []
  (doto (DesktopAssetManager. true)
    (.registerLocator "assets" FileLocator)
    (.registerLoader (Class/forName "cortex.BlendLoader")
                     ^"[Ljava.lang.String;" (into-array String ["blend"]))))

(def ^:private shared-assets (delay (new-asset-manager)))

(defn asset-manager
  "The AssetManager cortex uses: it finds jME's own assets, anything on
  the classpath and the folder assets/, and reads .blend files with
  cortex's reader (loaded on the first .blend it meets). With no
  argument, the one manager shared by everything, made on first use;
  `(asset-manager {:new true})` makes a fresh one, for a caller that
  registers locators of its own."
  (^AssetManager [] @shared-assets)
  (^AssetManager [{:keys [new]}]
   (if new (new-asset-manager) @shared-assets)))

(defonce ^:private blend-reader (atom nil))

(defn install-blend-reader!
  "Make `f` the function `load-blender-model` hands its arguments to:
  cortex.blender installs its own when it is loaded."
  [f]
  (reset! blend-reader f))

(defn ^:api load-blender-model
  "Load a .blend file as a jME Node: `model` is an asset name such as
  \"Models/test-creature/worm.blend\" (under assets/ or on the
  classpath) or a file's path; `am` an AssetManager (the shared one when
  not given); `opts` a map, {:scene \"Game\"} to load that scene rather
  than the one the file was saved showing. Forms: (model), (model
  opts), (am model), (am model opts). Errors are ex-info naming the
  file. This is cortex.blender/load-blender-model, which cortex.blender
  installs here when it is loaded (see the chapter); before that, an
  ex-info says to require it."
  {:arglists '([model] [model opts] [am model] [am model opts])}
  [& args]
  (if-let [f @blend-reader]
    (apply f args)
    (throw (ex-info (str "cortex.util/load-blender-model needs the .blend reader, which is not"
                         " loaded: (require 'cortex.blender) first, or call"
                         " cortex.blender/load-blender-model")
                    {:args (vec args)}))))

(def ^:private shape-defaults
  {:name "shape"
   :color ColorRGBA/Blue
   :material "Common/MatDefs/Misc/Unshaded.j3md"
   :position Vector3f/ZERO
   :rotation Quaternion/IDENTITY
   :mass 1
   :friction 0.5
   :physical? true})

(defn- shape
  "A Geometry for `mesh` placed and coloured by `options` (see `box`),
  with a rigid body of `collision-shape` unless :physical? is false."
  [mesh collision-shape options]
  (let [{:keys [name color material position rotation mass friction physical?]}
        (merge shape-defaults options)
        geom (Geometry. ^String name mesh)]
    (.setMaterial geom (doto (Material. (asset-manager) ^String material)
                         (.setColor "Color" ^ColorRGBA color)))
    (.setLocalTranslation geom ^Vector3f position)
    (.setLocalRotation geom ^Quaternion rotation)
    (when physical?
      (.addControl geom (doto (RigidBodyControl. collision-shape (float mass))
                          (.setFriction (float friction)))))
    geom))

(def ^:private shape-lock
  "Held while jBullet makes a box or hull shape (see `locked-shape`)."
  (Object.))

(defn locked-shape
  "The collision shape `(make)` returns, made while no other thread of
  cortex makes one. jBullet's boxes and hulls (its PolyhedralConvexShapes)
  compute their bounds in a static array that every thread shares, on
  creation and whenever they are scaled, so two made at the same moment
  on two threads can get each other's bounds; every box and hull cortex
  makes is made through here."
  [make]
  (locking shape-lock (make)))

(defn ^:api box
  "A box with half-extents `x`, `y`, `z`. Options: :name, :color,
  :material (a .j3md with a Color parameter), :position, :rotation,
  :mass (0 is static), :friction and :physical? (false for scenery
  with no rigid body)."
  ([] (box 0.5 0.5 0.5))
  ([x y z & {:as options}]
   (shape (Box. (float x) (float y) (float z))
          (locked-shape #(BoxCollisionShape. (Vector3f. x y z)))
          (merge {:name "box"} options))))

(defn ^:api sphere
  "A sphere of `radius`, with the same options as `box`."
  ([] (sphere 1))
  ([radius & {:as options}]
   (shape (Sphere. 32 32 (float radius))
          (SphereCollisionShape. (float radius))
          (merge {:name "sphere"} options))))

(defn light-up-everything
  "Light the world's root node from above and around, enough to see
  lit materials from any side. Returns the world."
  [^SimpleApplication world]
  (let [root (.getRootNode world)]
    (doseq [dir [(Vector3f. -0.5 -1 -0.4) (Vector3f. 0.6 -0.3 0.7)]]
      (.addLight root (doto (DirectionalLight.)
                        (.setDirection (.normalizeLocal ^Vector3f dir))
                        (.setColor (ColorRGBA. 0.7 0.7 0.7 1)))))
    (.addLight root (doto (AmbientLight.)
                      (.setColor (ColorRGBA. 0.35 0.35 0.35 1))))
    world))

(defn dilation
  "How many simulated seconds passed per wall-clock second."
  [simulated-seconds wall-seconds]
  (if (pos? wall-seconds) (/ simulated-seconds wall-seconds) 0.0))

(defn display-dilated-time
  "Show, in the corner of the world's screen, simulated time beside wall
  time, read from `timer`: with a fixed-step timer the two drift apart
  and the ratio says how fast the simulation really runs. Returns the
  world."
  [^SimpleApplication world ^com.jme3.system.Timer timer]
  (let [text (doto (BitmapText. (.loadFont (.getAssetManager world)
                                           "Interface/Fonts/Default.fnt"))
               (.setLocalTranslation 10 (float 40) 0))
        start (System/nanoTime)]
    (.attachChild (.getGuiNode world) text)
    (.attach (.getStateManager world)
             (proxy [AbstractAppState] []
               (update [_]
                 (let [sim (.getTimeInSeconds timer)
                       wall (/ (- (System/nanoTime) start) 1e9)]
                   (.setText text (format "simulated %.2f s | wall %.2f s | x%.2f"
                                          (double sim) wall
                                          (double (dilation sim wall))))))))
    world))
