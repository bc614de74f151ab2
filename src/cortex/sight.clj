;; Generated from org/vision.org by lein tangle: edit the chapter, not this file.
(ns cortex.sight
  "What eyes see, drawn offscreen with OpenGL: for a simulation, one GL
  context of its own on a thread of its own (Mesa's EGL surfaceless
  platform, see cortex.render), every eye drawn into one framebuffer,
  read back as RGB bytes, depth in metres and, when asked, segment ids;
  for a cortex world, the same eyes drawn in the world's own context.
  Loaded only when eyes are asked for.

  Entry points: `open!` (eyes for a simulation, installed in cortex.sim
  when this namespace loads),
  `see!`, `close!`, `choose`, `eyes-state` (eyes in a world),
  `eye-image`, `depth-image`, `with-eyes`, `record-with-eyes!`."
  (:require [cortex.render :as render]
            [cortex.sim :as sim]
            [cortex.util :as util]
            [cortex.vision :as vision])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.app.state AbstractAppState)
           (com.jme3.asset AssetManager)
           (com.jme3.light AmbientLight DirectionalLight)
           (com.jme3.material MatParam Material MaterialDef RenderState)
           (com.jme3.material TechniqueDef$LightMode)
           (com.jme3.math ColorRGBA Quaternion Vector3f)
           (com.jme3.renderer Camera RenderManager Renderer ViewPort)
           (com.jme3.renderer.queue RenderQueue$Bucket)
           (com.jme3.scene Geometry Node Spatial)
           (com.jme3.shader VarType)
           (com.jme3.system AppSettings JmeContext JmeContext$Type JmeSystem SystemListener)
           (com.jme3.texture FrameBuffer Image$Format)
           (com.jme3.util BufferUtils)
           (java.awt.image BufferedImage DataBufferInt)
           (java.nio ByteBuffer FloatBuffer)
           (java.util IdentityHashMap)
           (java.util.concurrent LinkedBlockingQueue TimeUnit)
           (org.lwjgl.opengl GL11)))

(set! *warn-on-reflection* true)

(def sky-colour
  "What an eye sees where there is nothing: a pale blue."
  (ColorRGBA. 0.55 0.7 0.9 1.0))

(defn- copy-material
  "A copy of `m` made from its definition as `am` loads it: every
  parameter but textures, face culling and blending."
  ^Material [^AssetManager am ^Material m]
  (let [def-name (.getAssetName (.getMaterialDef m))
        copy (if def-name
               (Material. am def-name)
               (doto (Material. am "Common/MatDefs/Misc/Unshaded.j3md")
                 (.setColor "Color" ColorRGBA/Gray)))]
    (when def-name
      (doseq [^MatParam p (.getParams m)
              :let [t (.getVarType p)]
              :when (not (.isTextureType t))]
        (.setParam copy (.getName p) t (.getValue p))))
    (let [^RenderState from (.getAdditionalRenderState m)
          ^RenderState to (.getAdditionalRenderState copy)]
      (.setFaceCullMode to (.getFaceCullMode from))
      (.setBlendMode to (.getBlendMode from)))
    copy))

(defn- label-of
  "What segmentation calls Geometry `g`."
  ^String [^Geometry g]
  (let [p (.getParent g)]
    (if (and p (some? (.getUserData p "blender-type")))
      (.getName p)
      (.getName g))))

(defn- id-material
  ^Material [^AssetManager am id]
  (doto (Material. am "Common/MatDefs/Misc/Unshaded.j3md")
    (.setColor "Color" (ColorRGBA. (/ (float (bit-and (long id) 0xff)) 255.0)
                                   (/ (float (bit-and (bit-shift-right (long id) 8) 0xff)) 255.0)
                                   0.0 1.0))))

(defn- mirror
  "An empty mirror of scene `root`, lit as cortex lights its worlds."
  [^Node root ^AssetManager am]
  (let [node (Node. "eyes' mirror")]
    (doseq [dir [(Vector3f. -0.5 -1 -0.4) (Vector3f. 0.6 -0.3 0.7)]]
      (.addLight node (doto (DirectionalLight.)
                        (.setDirection (.normalizeLocal ^Vector3f dir))
                        (.setColor (ColorRGBA. 0.7 0.7 0.7 1)))))
    (.addLight node (doto (AmbientLight.) (.setColor (ColorRGBA. 0.35 0.35 0.35 1))))
    {:root root :node node :am am
     :copies (IdentityHashMap.)      ; original Geometry -> {:geom :look :id-material}
     :ids (atom {})}))               ; label -> id

(defn- geometries
  [^Spatial root]
  (filter #(and (instance? Geometry %)
                (not= RenderQueue$Bucket/Sky (.getQueueBucket ^Geometry %)))
          (util/node-seq root)))

(defn- copy-of!
  [{:keys [^Node node ^AssetManager am ^IdentityHashMap copies ids]} ^Geometry g]
  (or (.get copies g)
      (let [label (label-of g)
            id (or (get @ids label) (get (swap! ids #(assoc % label (inc (count %)))) label))
            geom (Geometry. (.getName g) (.deepClone (.getMesh g)))
            look (copy-material am (.getMaterial g))
            c {:geom geom :look look :id-material (id-material am id) :label label :id id}]
        (.setMaterial geom look)
        (.attachChild node geom)
        (.put copies g c)
        c)))

(defn- update-mirror!
  "Place every copy where its original is now (adding copies of new
  Geometries, dropping those of Geometries gone), in `look` materials
  or segmentation's. Returns the mirror's node."
  ^Node [{:keys [root ^Node node ^IdentityHashMap copies] :as m} segmentation?]
  (let [seen (IdentityHashMap.)]
    (doseq [^Geometry g (geometries root)]
      (let [{:keys [^Geometry geom look id-material]} (copy-of! m g)]
        (.put seen g true)
        (.setLocalTransform geom (.getWorldTransform g))
        (.setCullHint geom (.getCullHint g))
        (.setMaterial geom ^Material (if segmentation? id-material look))))
    (when (< (.size seen) (.size copies))
      (doseq [g (vec (.keySet copies)) :when (not (.containsKey seen g))]
        (.removeFromParent ^Geometry (:geom (.get copies g)))
        (.remove copies g)))
    (.updateGeometricState node)
    node))

(defn- set-materials!
  [{:keys [^IdentityHashMap copies]} segmentation?]
  (doseq [{:keys [^Geometry geom look id-material]} (.values copies)]
    (.setMaterial geom ^Material (if segmentation? id-material look)))
  nil)

(defn- eye-camera
  "A camera of the strip's size `strip-w` x `strip-h` whose viewport is
  eye rectangle x0..x0+w, 0..h and whose projection is eye `spec`'s for
  a w x h image. The viewport's edges are nudged a quarter pixel in, so
  that jME's float arithmetic lands on whole pixels."
  ^Camera [spec [w h] x0 strip-w strip-h]
  (let [{:keys [left right bottom top near far parallel?]} (vision/frustum spec [w h])
        cam (Camera. (int strip-w) (int strip-h))
        sw (double strip-w) sh (double strip-h)]
    (.setViewPort cam (float (/ (+ x0 0.25) sw)) (float (/ (+ x0 w 0.25) sw))
                  (float (/ 0.25 sh)) (float (/ (+ h 0.25) sh)))
    (.setParallelProjection cam (boolean parallel?))
    (.setFrustum cam (float near) (float far) (float left) (float right) (float top) (float bottom))
    cam))

(defn- layout
  "Where each of `chosen` eyes ([record options] pairs) goes in the
  strip: maps of the eye's record, options, :size and :x, and the
  strip's width and height."
  [chosen]
  (let [sizes (mapv (fn [[{:keys [spec]} opts]] (or (:resolution opts) (:resolution spec))) chosen)
        xs (vec (reductions + 0 (map first sizes)))]
    {:eyes (mapv (fn [[record opts] size x] {:record record :options opts :size size :x x})
                 chosen sizes xs)
     :width (peek xs)
     :height (apply max (map second sizes))}))

(defn- rig
  "Cameras, viewports and the strip's framebuffer for the eyes in
  `layout`, drawing `scene`. Call on the GL thread."
  [{:keys [eyes width height]} ^Node scene]
  (let [fb (doto (FrameBuffer. (int width) (int height) 1)
             (.setDepthBuffer Image$Format/Depth24)
             (.setColorBuffer Image$Format/RGBA8))]
    {:fb fb :width width :height height
     :eyes (mapv (fn [{:keys [record size x] :as e}]
                   (let [cam (eye-camera (:spec record) size x width height)
                         vp (doto (ViewPort. (str "eye " (:name record)) cam)
                              (.setClearFlags false false false)
                              (.setOutputFrameBuffer fb)
                              (.attachScene scene))]
                     (assoc e :camera cam :view-port vp)))
                 eyes)
     :rgba (BufferUtils/createByteBuffer (int (* 4 width height)))
     :depth (BufferUtils/createFloatBuffer (int (* width height)))}))

(defn- aim!
  "Put each eye's camera where its segment has taken it."
  [{:keys [eyes]}]
  (doseq [{:keys [record ^Camera camera]} eyes]
    (let [[^Vector3f location ^Quaternion rotation] (vision/eye-pose record)]
      (.setFrame camera location rotation))))

(defn- draw!
  "Clear the strip to `colour` and draw the eyes for which (want? eye)."
  [{:keys [^FrameBuffer fb eyes]} ^RenderManager rm ^ColorRGBA colour want?]
  (let [^Renderer r (.getRenderer rm)]
    (.setFrameBuffer r fb)
    (.clearClipRect r)
    (.setBackgroundColor r colour)
    (.clearBuffers r true true true)
    (doseq [{:keys [^ViewPort view-port] :as e} eyes :when (want? e)]
      (.renderViewPort rm view-port 0.0))
    (.setFrameBuffer r fb)))

(defn- read-rgba!
  ^ByteBuffer [{:keys [^ByteBuffer rgba width height]}]
  (.clear rgba)
  (GL11/glPixelStorei GL11/GL_PACK_ALIGNMENT 1)
  (GL11/glReadPixels 0 0 (int width) (int height) GL11/GL_RGBA GL11/GL_UNSIGNED_BYTE rgba)
  rgba)

(defn- read-depth!
  ^FloatBuffer [{:keys [^FloatBuffer depth width height]}]
  (.clear depth)
  (GL11/glReadPixels 0 0 (int width) (int height) GL11/GL_DEPTH_COMPONENT GL11/GL_FLOAT depth)
  depth)

(defn- rgb-of
  "Eye rectangle x0, w x h of the strip's RGBA pixels (bottom row
  first), as RGB bytes, top row first."
  ^bytes [^ByteBuffer rgba strip-w x0 w h]
  (let [w (long w) h (long h) strip-w (long strip-w) x0 (long x0)
        out (byte-array (* 3 w h))]
    (dotimes [row h]
      (let [src-row (* 4 (+ x0 (* strip-w (- h 1 row))))
            dst-row (* 3 w row)]
        (dotimes [col w]
          (let [s (+ src-row (* 4 col)) d (+ dst-row (* 3 col))]
            (aset out d (.get rgba (int s)))
            (aset out (inc d) (.get rgba (int (inc s))))
            (aset out (+ d 2) (.get rgba (int (+ s 2))))))))
    out))

(defn- depth-of
  "Eye rectangle x0, w x h of the strip's depth (0 to 1, bottom row
  first) as distances along the view axis, top row first, over `scale`
  (the scene's size over the creature's)."
  ^floats [^FloatBuffer depth strip-w x0 w h {:keys [near far parallel?]} scale]
  (let [w (long w) h (long h) strip-w (long strip-w) x0 (long x0)
        n (double near) f (double far) k (double scale)
        out (float-array (* w h))]
    (dotimes [row h]
      (let [src-row (+ x0 (* strip-w (- h 1 row)))
            dst-row (* w row)]
        (dotimes [col w]
          (let [d (double (.get depth (int (+ src-row col))))]
            (aset out (+ dst-row col)
                  (float (/ (if parallel?
                              (+ n (* d (- f n)))
                              (/ (* n f) (- f (* d (- f n)))))
                            k)))))))
    out))

(defn- ids-of
  ^ints [^ByteBuffer rgba strip-w x0 w h]
  (let [w (long w) h (long h) strip-w (long strip-w) x0 (long x0)
        out (int-array (* w h))]
    (dotimes [row h]
      (let [src-row (* 4 (+ x0 (* strip-w (- h 1 row))))
            dst-row (* w row)]
        (dotimes [col w]
          (let [s (+ src-row (* 4 col))]
            (aset out (+ dst-row col)
                  (int (bit-or (bit-and (long (.get rgba (int s))) 0xff)
                               (bit-shift-left (bit-and (long (.get rgba (int (inc s)))) 0xff) 8))))))))
    out))

(defn- look!
  "What every eye of `rig` sees of `mirror` now: {eye-name {:width
  :height :rgb :depth :segmentation :labels}}, each key only when asked."
  [{:keys [eyes width] :as rig} mirror ^RenderManager rm]
  (let [want (fn [k] (fn [e] (get-in e [:options k] true)))
        rgb? (some (want :rgb) eyes)
        depth? (some (want :depth) eyes)
        seg? (some #(get-in % [:options :segmentation]) eyes)
        _ (update-mirror! mirror false)
        _ (aim! rig)
        _ (draw! rig rm sky-colour (fn [e] (or ((want :rgb) e) ((want :depth) e))))
        rgba (when rgb? (read-rgba! rig))
        depth (when depth? (read-depth! rig))
        base (into {} (for [{:keys [record options size x]} eyes
                            :let [[w h] size
                                  f (vision/frustum (:spec record) size)]]
                        [(:name record)
                         (cond-> {:width w :height h}
                           (get options :rgb true) (assoc :rgb (rgb-of rgba width x w h))
                           (get options :depth true)
                           (assoc :depth (depth-of depth width x w h f (:scale rig 1.0))))]))]
    (if-not seg?
      base
      (do (set-materials! mirror true)
          (draw! rig rm ColorRGBA/Black #(get-in % [:options :segmentation]))
          (set-materials! mirror false)
          (let [rgba (read-rgba! rig)
                labels (into (sorted-map) (map (fn [[k v]] [v k])) @(:ids mirror))]
            (reduce (fn [m {:keys [record options size x]}]
                      (if (:segmentation options)
                        (let [[w h] size]
                          (update m (:name record) assoc
                                  :segmentation (ids-of rgba width x w h)
                                  :labels labels))
                        m))
                    base eyes))))))

(def ^:private option-keys #{:rgb :depth :segmentation :resolution})

(defn choose
  "The eyes of `creature` that `eyes` (true, or a map of eye name, or
  :all, to options) asks for, as [record options] pairs. An ex-info
  names an eye the creature does not have, an unknown option, or a
  creature without eyes."
  [creature eyes]
  (let [records (vision/eye-records creature)
        by-name (into {} (map (juxt :name identity)) records)
        spec (cond (true? eyes) {:all {}}
                   (map? eyes) eyes
                   :else (throw (ex-info (str ":eyes must be true or a map of eye name to options, not "
                                              (pr-str eyes))
                                         {:eyes eyes})))]
    (when (empty? records)
      (throw (ex-info "this creature has no eyes (an \"eyes\" node with cameras or eye empties, given its body by body!)"
                      {:eyes eyes})))
    (doseq [[k opts] spec]
      (when-not (or (= k :all) (by-name k))
        (throw (ex-info (str "no eye called " (pr-str k) "; the eyes are "
                             (pr-str (mapv :name records)))
                        {:eye k})))
      (when-not (map? opts)
        (throw (ex-info (str "the options of eye " (pr-str k) " must be a map, not " (pr-str opts))
                        {:eye k})))
      (when-let [bad (seq (remove option-keys (keys opts)))]
        (throw (ex-info (str "unknown eye option" (when (next bad) "s") " " (pr-str (vec bad))
                             "; an eye's options are " (pr-str (sort option-keys)))
                        {:eye k :options opts})))
      (when-let [r (:resolution opts)]
        (#'vision/check-resolution! k r)))
    (vec (for [{:keys [name] :as r} records
               :when (or (contains? spec :all) (contains? spec name))]
           [r (merge (:all spec) (get spec name))]))))

(defn- gl-listener
  "A jME SystemListener that sets up with (init) on the context's thread,
  then runs the tasks put on `tasks` as they come."
  ^SystemListener [init ready ^LinkedBlockingQueue tasks failure]
  (reify SystemListener
    (initialize [_]
      (deliver ready (try (init) (catch Throwable t t))))
    (reshape [_ _ _])
    (update [_]
      (when-let [task (.poll tasks 20 TimeUnit/MILLISECONDS)]
        (task)))
    (requestClose [_ _])
    (gainFocus [_])
    (loseFocus [_])
    (handleError [_ message t]
      (reset! failure (ex-info (str "eyes: " message ": " (ex-message t)) {} t))
      (deliver ready @failure))
    (destroy [_])))

(defn- call!
  "Run (f) on the eyes' GL thread and return its value, rethrowing what
  it throws; an ex-info if the context has died."
  [{:keys [^LinkedBlockingQueue tasks failure ^JmeContext context]} f]
  (let [result (promise)]
    (when @failure (throw @failure))
    (.put tasks (fn [] (deliver result (try [:ok (f)] (catch Throwable t [:error t])))))
    (loop []
      (let [r (deref result 1000 nil)]
        (cond
          (nil? r) (if (or @failure (not (.isCreated context)))
                     (throw (or @failure (ex-info "eyes: the OpenGL context has stopped" {})))
                     (recur))
          (= :ok (first r)) (second r)
          :else (throw (second r)))))))

(defn- open-context!
  "Start an offscreen GL context on its own thread and run (init
  render-manager) there; returns {:context :tasks :failure :state}, the
  state being what init returned."
  [init]
  (let [settings (doto (AppSettings. true)
                   (.setRenderer "CUSTOMcortex.SurfacelessContext")
                   (.setResolution 16 16)
                   (.setDepthBits 24)
                   (.setSamples 0)
                   (.setAudioRenderer nil))
        ^JmeContext context (JmeSystem/newContext settings JmeContext$Type/OffscreenSurface)
        tasks (LinkedBlockingQueue.)
        failure (atom nil)
        ready (promise)]
    (.setSystemListener context
                        (gl-listener #(let [rm (doto (RenderManager. (.getRenderer context))
                                                 (.setPreferredLightMode TechniqueDef$LightMode/SinglePass)
                                                 (.setSinglePassLightBatchSize 4))]
                                        (init rm))
                                     ready tasks failure))
    (.create context false)
    (let [state (deref ready 60000 ::timeout)]
      (cond
        (= state ::timeout) (do (.destroy context false)
                                (throw (ex-info "eyes: no OpenGL context after a minute" {})))
        (instance? Throwable state) (do (.destroy context true)
                                        (throw (if (instance? clojure.lang.ExceptionInfo state)
                                                 state
                                                 (ex-info (str "eyes: " (ex-message state)) {} state))))
        :else {:context context :tasks tasks :failure failure :state state}))))

(defn- scaled-choice
  "The eyes of `creature` that `eyes` asks for (see `choose`), each with
  its clipping distances `scale` times farther: built that many times
  its size (cortex.vision/scaled-spec)."
  [creature eyes scale]
  (mapv (fn [[record opts]] [(update record :spec vision/scaled-spec scale) opts])
        (choose creature eyes)))

(defn open!
  "Eyes for a simulation of `creature` whose scene is `root`, as `eyes`
  asks (see `choose`): a GL context on its own thread, the mirror and
  the strip. Returns the eyes, for `see!` and `close!`. `scale` (1 when
  not given) is how many times its size the simulation built the
  creature: each eye's clipping distances are that many times farther
  (cortex.vision/scaled-spec), and its depth is read back in the
  creature's units."
  ([creature root eyes] (open! creature root eyes 1.0))
  ([creature ^Node root eyes scale]
   (let [plan (layout (scaled-choice creature eyes scale))]
     (open-context!
      (fn [^RenderManager rm]
        (let [am (util/asset-manager {:new true})
              m (mirror root am)]
          {:rm rm :mirror m :rig (assoc (rig plan (:node m)) :scale (double scale))}))))))

(defn see!
  "What the eyes see now, on their GL thread: {eye-name {:width :height
  :rgb :depth ...}} (see the chapter)."
  [eyes]
  (call! eyes (fn [] (let [{:keys [rm mirror rig]} (:state eyes)]
                       (look! rig mirror rm)))))

(defn close!
  "Stop the eyes' GL context and its thread, freeing what they drew
  with."
  [{:keys [^JmeContext context]}]
  (.destroy context true))

;; the step loop sees through these (cortex.sim loads no renderer)
(sim/install-sight! {:open! #'open! :see! #'see! :close! #'close!})

(defn eyes-state
  "Attach to `world` an app state that draws the eyes of `creature`
  (`eyes` as for a simulation) every frame in the world's own context,
  the creature built `scale` times its size (1 by default; see `open!`).
  Returns an atom holding the last frame's images (see `see!`)."
  ([world creature eyes] (eyes-state world creature eyes 1.0))
  ([^SimpleApplication world creature eyes scale]
   (let [plan (layout (scaled-choice creature eyes scale))
         seen (atom nil)
         state (atom nil)]
     (.attach (.getStateManager world)
              (proxy [AbstractAppState] []
                (render [^RenderManager rm]
                  (let [{:keys [mirror rig]}
                        (or @state
                            (reset! state (let [m (mirror (.getRootNode world)
                                                          (util/asset-manager {:new true}))]
                                            {:mirror m
                                             :rig (assoc (rig plan (:node m)) :scale (double scale))})))]
                    (reset! seen (look! rig mirror rm))))))
     seen)))

(defn eye-image
  "An eye's RGB bytes (see `see!`) as a TYPE_INT_RGB BufferedImage."
  ^BufferedImage [{:keys [width height ^bytes rgb]}]
  (let [image (BufferedImage. (int width) (int height) BufferedImage/TYPE_INT_RGB)
        ^ints data (.getData ^DataBufferInt (.getDataBuffer (.getRaster image)))]
    (dotimes [i (* (long width) (long height))]
      (aset data i (unchecked-int
                    (bit-or (bit-shift-left (bit-and (long (aget rgb (* 3 i))) 0xff) 16)
                            (bit-shift-left (bit-and (long (aget rgb (+ 1 (* 3 i)))) 0xff) 8)
                            (bit-and (long (aget rgb (+ 2 (* 3 i)))) 0xff)))))
    image))

(defn depth-image
  "An eye's depth (see `see!`) as a grey TYPE_INT_RGB BufferedImage:
  white at the eye, black at 10 units and beyond."
  ^BufferedImage [{:keys [width height ^floats depth]}]
  (let [image (BufferedImage. (int width) (int height) BufferedImage/TYPE_INT_RGB)
        ^ints data (.getData ^DataBufferInt (.getDataBuffer (.getRaster image)))]
    (dotimes [i (* (long width) (long height))]
      (let [v (long (* 255.0 (max 0.0 (- 1.0 (/ (double (aget depth i)) 10.0)))))]
        (aset data i (unchecked-int (bit-or (bit-shift-left v 16) (bit-shift-left v 8) v)))))
    image))

(defn with-eyes
  "`frame` (the world's picture) with a strip of the eyes' pictures
  `seen` under it, each eye's colour then its depth (see `depth-image`),
  scaled up as much as fits the frame's width (at most 4 times),
  nearest pixel; the height made even for video encoders."
  ^BufferedImage [^BufferedImage frame seen]
  (let [images (vec (mapcat (fn [e] (cond-> [(eye-image e)] (:depth e) (conj (depth-image e))))
                            (vals (sort seen))))
        fw (.getWidth frame) fh (.getHeight frame)
        gap 4
        total-w (+ (reduce + (map #(.getWidth ^BufferedImage %) images)) (* gap (dec (count images))))
        k (max 1 (min 4 (quot fw (max 1 total-w))))
        strip-h (+ gap (* k (apply max 1 (map #(.getHeight ^BufferedImage %) images))))
        h (+ fh strip-h (mod (+ fh strip-h) 2))
        out (BufferedImage. fw h BufferedImage/TYPE_INT_RGB)
        g (.createGraphics out)]
    (.drawImage g frame 0 0 nil)
    (loop [x (quot (- fw (* k total-w)) 2) [^BufferedImage i & more] images]
      (when i
        (.drawImage g i (int x) (int (+ fh gap)) (int (* k (.getWidth i))) (int (* k (.getHeight i))) nil)
        (recur (+ x (* k (+ gap (.getWidth i)))) more)))
    (.dispose g)
    out))

(defn record-with-eyes!
  "Record `world` to folder `dir` as cortex.render/record! does, each
  frame with what the eyes of `creature` saw under it (see `with-eyes`).
  `opts` as for record!, :eyes (default true), and :scale (how many
  times its size the creature was built, 1 by default). Call before
  the world starts."
  ([world creature dir] (record-with-eyes! world creature dir {}))
  ([world creature dir opts]
   (let [seen (eyes-state world creature (get opts :eyes true) (get opts :scale 1.0))]
     (render/record! world dir (assoc (dissoc opts :eyes :scale)
                                      :decorate #(if @seen (with-eyes % @seen) %))))))
