;; Generated from org/test-body.org by lein tangle: edit the chapter, not this file.
(ns cortex.demo
  "The scene cortex's demos share: the reference creatures, a floor, a
  camera, lights and keys.

  Entry points: `hand`, `worm` (load the reference creatures), `floor`,
  `setup` (camera, light, fixed step), `gravity-control` and
  `debug-control` (key maps for cortex.world/world); `stage` (any built
  creature on a lit floor, framed, with shadows), `watch` and `watched`
  (joint gaps and the time it came to rest)."
  (:require [cortex.body :as body]
            [cortex.blender :as blender]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.bounding BoundingBox)
           (com.jme3.bullet.collision.shapes BoxCollisionShape)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.joints PhysicsJoint)
           (com.jme3.light AmbientLight DirectionalLight)
           (com.jme3.material Material)
           (com.jme3.math ColorRGBA Vector3f)
           (com.jme3.renderer.queue RenderQueue$ShadowMode)
           (com.jme3.scene Geometry Node Spatial)
           (com.jme3.scene.shape Box)
           (com.jme3.shadow DirectionalLightShadowRenderer)
           (cortex RatchetTimer)))

(set! *warn-on-reflection* true)

(def hand-path "Models/test-creature/hand.blend")
(def worm-path "Models/test-creature/worm.blend")

(defn ^:api hand
  "The hand, as Blender describes it: a palm and five fingers."
  []
  (blender/load-blender-model hand-path))

(defn ^:api worm
  "The worm: two segments and one joint."
  []
  (blender/load-blender-model worm-path))

(def earth-gravity (Vector3f. 0 -9.81 0))

(defn gravity-keys
  "G turns gravity `g` on, U turns it off."
  [^Vector3f g]
  {"key-g" (fn [w pressed?] (when pressed? (world/set-gravity w g)))
   "key-u" (fn [w pressed?] (when pressed? (world/set-gravity w Vector3f/ZERO)))})

(def gravity-control
  "G turns the Earth's gravity on, U turns it off."
  (gravity-keys earth-gravity))

(def debug-control
  "H shows the physics: collision shapes and joints."
  {"key-h" (fn [w pressed?] (when pressed? (world/enable-debug w)))})

(defn floor
  "A grey static slab whose top is at y = -7."
  []
  (util/box 10 3 10 :position (Vector3f. 0 -10 0) :color ColorRGBA/Gray :mass 0
            :name "floor"))

(defn setup
  "Point the camera at the creature from above and to the side, light
  the scene and fix the step at 1/60 s. Returns the world."
  [^SimpleApplication world]
  (doto (.getCamera world)
    (.setLocation (Vector3f. -6.5 7 7))
    (.lookAt (Vector3f. 0 -1 -1) Vector3f/UNIT_Y))
  (util/light-up-everything world)
  (.setTimer world (RatchetTimer. 60))
  world)

(def ^com.jme3.math.ColorRGBA sky
  "The colour behind everything."
  (ColorRGBA. 0.62 0.77 0.93 1))

(defn- lit-material
  ^Material [^SimpleApplication world ^ColorRGBA colour]
  (doto (Material. (.getAssetManager world) "Common/MatDefs/Light/Lighting.j3md")
    (.setBoolean "UseMaterialColors" true)
    (.setColor "Diffuse" colour)
    (.setColor "Ambient" colour)))

(defn bounds
  "The lowest and highest corners, [x y z] each, of `spatial`'s world
  bounds."
  [^Spatial spatial]
  (.updateGeometricState spatial)
  (let [^BoundingBox b (let [wb (.getWorldBound spatial)]
                         (if (instance? BoundingBox wb) wb
                             (BoundingBox. (.getCenter wb) 1 1 1)))
        c (.getCenter b)
        e [(.getXExtent b) (.getYExtent b) (.getZExtent b)]
        c [(.x c) (.y c) (.z c)]]
    [(mapv - c e) (mapv + c e)]))

(defn stage-floor
  "A static, lit floor whose top is at height `top`, reaching well past
  the creature whose bounds are `lo` and `hi`, and a rigid body for it."
  ^Geometry [[lx _ lz] [hx _ hz] top]
  (let [half (max 10.0 (* 3 (max (- hx lx) (- hz lz))))
        geom (Geometry. "floor" (Box. (float half) 0.5 (float half)))]
    (doto geom
      (.setLocalTranslation (float (/ (+ lx hx) 2)) (float (- top 0.5)) (float (/ (+ lz hz) 2)))
      (.addControl (RigidBodyControl. ^BoxCollisionShape (util/locked-shape #(BoxCollisionShape. (Vector3f. half 0.5 half))) 0))
      (.setShadowMode RenderQueue$ShadowMode/Receive))))

(defn frame!
  "Aim `world`'s camera at the box from `lo` to `hi` so that all of it is
  in the picture, from the front, left and above. Returns the world."
  [^SimpleApplication world lo hi]
  (let [cam (.getCamera world)
        ;; a little below the middle: the creature ends on the floor
        centre (update (mapv #(/ (+ %1 %2) 2) lo hi) 1
                       (fn [_] (+ (double (second lo)) (* 0.4 (- (double (second hi)) (double (second lo)))))))
        radius (max 0.5 (/ (Math/sqrt (reduce + (map #(let [d (- %2 %1)] (* d d)) lo hi))) 2))
        fov (Math/toRadians 45)
        aspect (/ (.getWidth cam) (double (.getHeight cam)))
        fit (/ radius (Math/sin (/ (* fov (min 1.0 aspect)) 2)))
        dir (.normalize (Vector3f. -0.5 0.42 0.75))
        eye (.add (util/vec3 centre) (.mult dir (float (* 1.15 fit))))]
    (.setFrustumPerspective cam 45 (float aspect) 0.05 (float (* 20 fit)))
    (.setLocation cam eye)
    (.lookAt cam (util/vec3 centre) Vector3f/UNIT_Y)
    world))

(defn light!
  "Sky, a sun from above and behind the camera's left shoulder that
  casts shadows, and soft light from all around. Returns the world."
  [^SimpleApplication world]
  (let [root (.getRootNode world)
        sun (doto (DirectionalLight.)
              (.setDirection (.normalizeLocal (Vector3f. 0.35 -1 -0.45)))
              (.setColor (ColorRGBA. 0.85 0.85 0.8 1)))]
    (.setBackgroundColor (.getViewPort world) sky)
    (.addLight root sun)
    (.addLight root (doto (AmbientLight.) (.setColor (ColorRGBA. 0.45 0.45 0.5 1))))
    (.setShadowMode root RenderQueue$ShadowMode/CastAndReceive)
    (.addProcessor (.getViewPort world)
                   (doto (DirectionalLightShadowRenderer. (.getAssetManager world) 2048 3)
                     (.setLight sun)
                     (.setShadowIntensity 0.45)))
    world))

(defn ^:api stage
  "A world showing `creature` (a built body) on a floor `drop` units
  under its lowest point, lit, with the camera framing the creature and
  the floor beneath it, gravity on and the step fixed at 1/60 s.
  `update-fn` runs every frame, as for cortex.world/world. Keys: those
  of the demo worlds. `opts`: :gravity (default `earth-gravity`), and
  :setup, a function of the world run last as it starts."
  ([creature drop update-fn] (stage creature drop update-fn {}))
  ([^Node creature drop update-fn opts]
   (let [{:keys [gravity setup] :or {gravity earth-gravity}} opts
         [lo hi] (bounds creature)
         top (- (second lo) drop)
         floor (stage-floor lo hi top)]
     (world/world (util/nodify [creature floor])
                  (merge world/standard-debug-controls (gravity-keys gravity) debug-control)
                  (fn [^SimpleApplication w]
                    (.setMaterial floor (lit-material w (ColorRGBA. 0.55 0.6 0.5 1)))
                    (light! w)
                    (frame! w (assoc lo 1 top) hi)
                    (.setTimer w (RatchetTimer. 60))
                    (world/set-gravity w gravity)
                    (world/speed-up w)
                    (util/display-dilated-time w (.getTimer w))
                    (when setup (setup w)))
                  update-fn))))

(defn watch
  "A function of [world tpf] for cortex.world/world's update that
  measures `creature` (built by body!, `k` times its size: 1 by
  default) every frame, and an atom holding {:frames n :max-gap g
  :still-since frame-or-nil}: [update-fn atom]."
  ([creature] (watch creature 1.0))
  ([creature k]
   (let [k (double k)
         still (* 0.05 (Math/sqrt k))
         joints (mapv :physics-joint (body/joint-records creature))
         controls (mapv #(.getControl ^Geometry % RigidBodyControl) (body/segments creature))
         seen (atom {:frames 0 :max-gap 0.0 :still-since nil})]
     [(fn [_ _]
        (let [gap (/ (reduce max 0.0 (map body/joint-gap joints)) k)
              fastest (reduce max 0.0 (map #(.length (.getLinearVelocity ^RigidBodyControl %))
                                           controls))]
          (swap! seen (fn [{:keys [frames] :as s}]
                        (-> s
                            (assoc :frames (inc frames))
                            (update :max-gap max gap)
                            (update :still-since #(if (< fastest still) (or % (inc frames)) nil)))))))
      seen])))

(defn watched
  "What `watch` saw, in words."
  [{:keys [frames max-gap still-since]}]
  (str (format "largest joint gap %.4f; " max-gap)
       (if still-since
         (format "at rest from %.2f s (of %.2f s)" (/ (dec still-since) 60.0) (/ frames 60.0))
         (format "still moving after %.2f s" (/ frames 60.0)))))
