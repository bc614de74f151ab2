;; Generated from org/render.org by lein tangle: edit the chapter, not this file.
(ns cortex.render
  "Worlds people can see: started in a window when there is a display,
  or run offscreen for an exact number of frames with real OpenGL and
  no window; and any world's frames recorded to PNG files, then to an
  MP4 and a GIF with ffmpeg.

  Entry points: `start-window!`, `start-offscreen!`, `run-offscreen!`,
  `await-world!`, `record!`, `make-videos!`, `frames-in`, `display?`."
  (:require [clojure.java.io :as io]
            [clojure.java.shell :as shell]
            [clojure.string :as str]
            [cortex.world :as world])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.app.state AbstractAppState)
           (com.jme3.post SceneProcessor)
           (com.jme3.renderer RenderManager Renderer ViewPort)
           (com.jme3.system AppSettings JmeContext$Type NullRenderer)
           (com.jme3.texture Image$Format)
           (com.jme3.util BufferUtils)
           (java.awt.image BufferedImage DataBufferInt)
           (java.io File)
           (java.net InetSocketAddress Socket StandardProtocolFamily
                     UnixDomainSocketAddress)
           (java.nio ByteBuffer ByteOrder)
           (java.nio.channels SocketChannel)
           (javax.imageio ImageIO)))

(set! *warn-on-reflection* true)

(defn parse-display
  "The parts of an X display name such as \":0\", \":1.0\", \"unix:2\"
  or \"host:10.0\", as {:host h :number n}, :host nil for the local
  socket; nil when `s` is not a display name."
  [s]
  (when-let [[_ host number] (and (string? s)
                                  (re-matches #"([^:]*):(\d+)(?:\.\d+)?" (str/trim s)))]
    {:host (when-not (contains? #{"" "unix"} host) host)
     :number (Long/parseLong number)}))

(defn- can-connect?
  "True when a connection to the X server of display `d` (see
  `parse-display`) opens within `timeout-ms`."
  [{:keys [host number]} timeout-ms]
  (try
    (if host
      (with-open [s (Socket.)]
        (.connect s (InetSocketAddress. ^String host (int (+ 6000 number))) (int timeout-ms))
        true)
      (let [path (str "/tmp/.X11-unix/X" number)]
        (and (.exists (io/file path))
             (with-open [ch (SocketChannel/open StandardProtocolFamily/UNIX)]
               (.connect ch (UnixDomainSocketAddress/of path))))))
    (catch Exception _ false)))

(defn display?
  "True when the process can open windows: DISPLAY names an X server
  that accepts a connection."
  ([] (display? (System/getenv "DISPLAY")))
  ([display-name]
   (boolean (some-> (parse-display display-name) (can-connect? 500)))))

(defn- check-size
  "[width height] when both are even integers from 16 to 8192, else an
  ex-info saying what is wrong."
  [[width height :as size]]
  (when-not (and (every? int? [width height])
                 (every? #(<= 16 % 8192) [width height])
                 (every? even? [width height]))
    (throw (ex-info (str "frame size must be two even numbers of pixels from 16 to 8192,"
                         " not " (pr-str size))
                    {:size size})))
  [width height])

(defn parse-size
  "A frame size written \"640x480\", as [640 480]; an ex-info when the
  text is not two such numbers (see `check-size`)."
  [s]
  (if-let [[_ w h] (and (string? s) (re-matches #"\s*(\d{1,5})\s*[xX]\s*(\d{1,5})\s*" s))]
    (check-size [(Long/parseLong w) (Long/parseLong h)])
    (throw (ex-info (str "frame size must look like 640x480, not " (pr-str s)) {:size s}))))

(def ^:private surfaceless-renderer
  "The renderer setting that makes jME use cortex.SurfacelessContext.
  Named by string so that loading this namespace loads no OpenGL."
  "CUSTOMcortex.SurfacelessContext")

(defn- configure!
  "Set the renderer and, when given, the frame size of a world that has
  not started yet. Returns its settings."
  ^AppSettings [world renderer size]
  (let [^AppSettings settings (:settings @world)]
    (.setRenderer settings ^String renderer)
    (when size
      (let [[w h] (check-size size)]
        (.setResolution settings (int w) (int h))))
    settings))

(defn ^:api run-offscreen!
  "Run `world` for exactly `frames` frames of 1/60 s, drawing every
  frame with real OpenGL into an offscreen framebuffer (Mesa's EGL
  surfaceless platform: no window, no X server), blocking until it has
  stopped and its thread has ended. Options: :size [width height] of
  the frames (default the world's, 800x600) and :timeout-ms (see
  cortex.world/run-world!). Throws an ex-info when the world fails.
  Returns the world."
  ([world frames] (run-offscreen! world frames {}))
  ([world frames {:keys [size timeout-ms] :or {timeout-ms 600000}}]
   (configure! world surfaceless-renderer size)
   (world/run-world! world frames {:context-type JmeContext$Type/OffscreenSurface
                                   :timeout-ms timeout-ms})))

(defn ^:api start-window!
  "Open `world` in a window (OpenGL through LWJGL 3) and return it at
  once, the world running on a thread of its own until the window is
  closed, Escape is pressed or cortex.world/stop! is called. Options:
  :size [width height] of the window and :fps, the most frames a second
  it draws (default 60, so that a fixed-step world runs at about the
  speed of life). Throws an ex-info, opening nothing, when there is no
  display (see `display?`)."
  ([world] (start-window! world {}))
  ([^SimpleApplication world {:keys [size fps] :or {fps 60}}]
   (let [display (System/getenv "DISPLAY")]
     (when-not (display? display)
       (throw (ex-info (str "no display to open a window on ("
                            (if (str/blank? display)
                              "DISPLAY is not set"
                              (str "DISPLAY=" display " does not answer"))
                            "): draw offscreen with run-offscreen! or start-offscreen!")
                       {:display display}))))
   (doto (configure! world AppSettings/LWJGL_OPENGL2 size)
     (.setVSync false))
   (world/start! world {:context-type JmeContext$Type/Display :fps fps})))

(defn ^:api start-offscreen!
  "Start `world` drawing offscreen (see `run-offscreen!`) and return it
  at once; it runs, as fast as it can, until cortex.world/stop! is
  called. Options: :size [width height] of the frames. Returns the
  world."
  ([world] (start-offscreen! world {}))
  ([world {:keys [size]}]
   (configure! world surfaceless-renderer size)
   (world/start! world {:context-type JmeContext$Type/OffscreenSurface})))

(defn await-world!
  "Block until a started `world` has been torn down (its window closed,
  Escape pressed, or stopped) and its thread has ended. Throws an
  ex-info if it failed. Returns the world. The same as
  cortex.world/await!."
  [world]
  (world/await! world))

(defn bgra->image!
  "Copy a frame read from OpenGL as BGRA8 (bottom row first) into
  `image`, a width x height TYPE_INT_RGB BufferedImage, top row first.
  Returns the image."
  ^BufferedImage [^ByteBuffer bgra ^BufferedImage image]
  (let [w (.getWidth image)
        h (.getHeight image)
        pixels (.asIntBuffer (.order (.duplicate bgra) ByteOrder/LITTLE_ENDIAN))
        ^ints data (.getData ^DataBufferInt (.getDataBuffer (.getRaster image)))]
    (dotimes [row h]
      (.position pixels (int (* w (- h 1 row))))
      (.get pixels data (int (* w row)) (int w)))
    image))

(defn- frame-grabber
  "A SceneProcessor that, each time its viewport has been drawn, reads
  the frame as a TYPE_INT_RGB BufferedImage and calls (on-frame image).
  The image is reused for the next frame."
  ^SceneProcessor [on-frame]
  (let [state (atom nil)]
    (reify SceneProcessor
      (initialize [_ render-manager view-port]
        (reset! state {:renderer (.getRenderer ^RenderManager render-manager)
                       :view-port view-port}))
      (isInitialized [_] (some? @state))
      (reshape [_ _ _ _])
      (preFrame [_ _])
      (postQueue [_ _])
      (postFrame [_ out]
        (let [{:keys [^Renderer renderer ^ViewPort view-port
                      ^ByteBuffer buffer ^BufferedImage image]} @state
              cam (.getCamera view-port)
              w (.getWidth cam)
              h (.getHeight cam)
              [^ByteBuffer buffer ^BufferedImage image]
              (if (and image (= w (.getWidth image)) (= h (.getHeight image)))
                [buffer image]
                (let [b (BufferUtils/createByteBuffer (int (* 4 w h)))
                      i (BufferedImage. w h BufferedImage/TYPE_INT_RGB)]
                  (swap! state assoc :buffer b :image i)
                  [b i]))]
          (.clear buffer)
          (.readFrameBufferWithFormat renderer out buffer Image$Format/BGRA8)
          (on-frame (bgra->image! buffer image))))
      (cleanup [_] (reset! state nil))
      (setProfiler [_ _]))))

(defn- last-view-port
  "The viewport drawn last in a frame: the last GUI viewport."
  ^ViewPort [^SimpleApplication world]
  (or (last (.getPostViews (.getRenderManager world)))
      (.getGuiViewPort world)))

(defn grab-frames!
  "Call (on-frame image) with every frame `world` draws from now on, as
  a BufferedImage (reused from frame to frame), and (on-end) when the
  world is torn down. Works before the world starts, from its setup
  function, or while it runs. Returns the world."
  ([world on-frame] (grab-frames! world on-frame (fn [])))
  ([^SimpleApplication world on-frame on-end]
   (let [grabber (frame-grabber on-frame)
         view-port (atom nil)]
     (.attach (.getStateManager world)
              (proxy [AbstractAppState] []
                (initialize [^com.jme3.app.state.AppStateManager state-manager
                             ^com.jme3.app.Application app]
                  (let [^AbstractAppState this this]
                    (proxy-super initialize state-manager app))
                  (when (instance? NullRenderer (.getRenderer world))
                    (throw (ex-info (str "cannot record a world that draws nothing"
                                         " (jME's null renderer): run it with"
                                         " cortex.render/run-offscreen! or in a window")
                                    {})))
                  (.addProcessor ^ViewPort (reset! view-port (last-view-port world)) grabber))
                (cleanup []
                  (let [^AbstractAppState this this]
                    (proxy-super cleanup))
                  (some-> ^ViewPort @view-port (.removeProcessor grabber))
                  (on-end))))
     world)))

(def ^:private frame-pattern
  "How frames are named: frame-000001.png, frame-000002.png, ..."
  "frame-%06d.png")

(defn- frame-file
  "The file of frame number `n` (counting from 1) in folder `dir`."
  ^File [dir n]
  (io/file dir (format frame-pattern n)))

(defn ^:api frames-in
  "The recorded frames in folder `dir`, in order."
  [dir]
  (->> (.listFiles (io/file dir))
       (filter #(re-matches #"frame-\d{6}\.png" (.getName ^File %)))
       (sort-by #(.getName ^File %))))

(defn- prepare-folder!
  "Make folder `dir` if needed and remove the frames an earlier
  recording left in it. Throws an ex-info when it cannot be made or
  written to. Returns it as a File."
  ^File [dir]
  (let [f (io/file dir)]
    (when-not (or (.isDirectory f) (.mkdirs f))
      (throw (ex-info (str "cannot make folder " f
                           (when (.exists f) " (a file of that name is in the way)"))
                      {:dir (str f)})))
    (when-not (.canWrite f)
      (throw (ex-info (str "cannot write to folder " f) {:dir (str f)})))
    (run! #(io/delete-file % true) (frames-in f))
    f))

(defn- write-png!
  "Write `image` to `file` as PNG. Returns the file."
  ^File [^BufferedImage image ^File file]
  (when-not (ImageIO/write image "png" file)
    (throw (ex-info (str "no PNG writer for " file) {:file (str file)})))
  file)

(defn- progress-line
  "The text of the progress counter after `n` frames, of `total` when
  known."
  [n total]
  (if total
    (format "recording: frame %d of %d (%d%%)" n total (quot (* 100 n) total))
    (format "recording: %d frame%s" n (if (= 1 n) "" "s"))))

(defn progress-printer
  "A progress function for `record!` that keeps a counter up to date on
  one line of *err* (as it is bound where the printer is made, so the
  counter reaches the REPL that asked for the recording): at the first
  frame, every `every` frames, and when the recording is done (then
  ending the line)."
  ([] (progress-printer nil))
  ([total] (progress-printer total 10))
  ([total every]
   (let [^java.io.Writer err *err*
         show! (fn [n end]
                 (.write err (str "\r" (progress-line n total) end))
                 (.flush err))]
     (fn
       ([n]
        (when (or (= n 1) (zero? (mod n every)))
          (show! n "")))
       ([n done?]
        (when done? (show! n "\n")))))))

(defn ^:api record!
  "Write every frame `world` draws, from its first, to folder `dir` as
  frame-000001.png, frame-000002.png, ... (see `frame-file`), removing
  frames an earlier recording left there. Options: :progress, a
  function called with the number of frames written so far after each
  frame, and with that number and true at the end (default: a counter
  on standard error, see `progress-printer`; nil for none) and
  :decorate, a function of each frame (a BufferedImage) returning the
  picture to write instead (cortex.sight adds what eyes see). Call it
  from a setup function or before the world starts. Throws an ex-info
  when `dir` cannot be written. Returns the world."
  ([world dir] (record! world dir {}))
  ([world dir {:keys [progress decorate] :or {progress (progress-printer) decorate identity}}]
   (let [folder (prepare-folder! dir)
         n (atom 0)]
     (grab-frames! world
                   (fn [image]
                     (write-png! (decorate image) (frame-file folder (swap! n inc)))
                     (when progress (progress @n)))
                   (fn []
                     (when (and progress (pos? @n))
                       (progress @n true)))))))

(defn mp4-args
  "ffmpeg's arguments to make `out` from the frames in `dir`, played at
  `fps` frames a second."
  [dir fps out]
  ["-y" "-loglevel" "error" "-framerate" (str fps)
   "-i" (str (io/file dir frame-pattern))
   "-pix_fmt" "yuv420p" "-movflags" "+faststart" (str out)])

(defn gif-args
  "ffmpeg's arguments to make the GIF `out` from the frames in `dir`,
  recorded at `fps` frames a second: `gif-fps` frames a second, `width`
  pixels wide, with a palette made for these frames."
  [dir fps out {:keys [gif-fps width] :or {gif-fps 15 width 320}}]
  ["-y" "-loglevel" "error" "-framerate" (str fps)
   "-i" (str (io/file dir frame-pattern))
   "-vf" (str "fps=" gif-fps ",scale=" width ":-2:flags=lanczos,"
              "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse")
   (str out)])

(defn ffmpeg
  "The path of the ffmpeg program on PATH, or nil."
  []
  (some (fn [dir]
          (let [f (io/file dir "ffmpeg")]
            (when (and (.isFile f) (.canExecute f)) (str f))))
        (str/split (or (System/getenv "PATH") "") (re-pattern File/pathSeparator))))

(defn- run-ffmpeg!
  "Run ffmpeg with `args`; an ex-info with its complaint if it fails."
  [program args]
  (let [{:keys [exit err]} (apply shell/sh program args)]
    (when-not (zero? exit)
      (throw (ex-info (str "ffmpeg failed (exit " exit "): " (str/trim err))
                      {:args args :exit exit})))))

(defn ^:api make-videos!
  "Turn the frames recorded in folder `dir` (played at `fps` frames a
  second) into NAME.mp4 and NAME.gif beside them, NAME being the
  folder's name unless :name is given; see `gif-args` for :gif-fps and
  :width of the GIF. Returns {:mp4 path :gif path}, or nil, after saying
  so on standard error, when ffmpeg is not installed or there are no
  frames."
  ([dir fps] (make-videos! dir fps {}))
  ([dir fps {:keys [name] :as options}]
   (let [folder (io/file dir)
         name (or name (.getName (.getCanonicalFile folder)))
         program (ffmpeg)]
     (cond
       (empty? (frames-in folder))
       (binding [*out* *err*] (println "no frames in" (str folder) "to make videos of") nil)
       (nil? program)
       (binding [*out* *err*]
         (println "ffmpeg is not installed: skipped the MP4 and GIF"
                  "(the PNG frames are in" (str folder ")")) nil)
       :else
       (let [mp4 (io/file folder (str name ".mp4"))
             gif (io/file folder (str name ".gif"))]
         (run-ffmpeg! program (mp4-args folder fps mp4))
         (run-ffmpeg! program (gif-args folder fps gif options))
         {:mp4 (str mp4) :gif (str gif)})))))
