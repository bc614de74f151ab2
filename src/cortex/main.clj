;; Generated from org/main.org by lein tangle: edit the chapter, not this file.
(ns cortex.main
  "What `lein run` does: the worm (or the hand) falls onto a floor, in a
  window when there is a display, otherwise drawn offscreen to PNG
  frames, an MP4 and a GIF.

  Entry points: `-main` (lein run), `plan` (the arguments as data),
  `named-creature`, `demo-world`."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [clojure.tools.cli :as cli]
            [cortex.body :as body]
            [cortex.export :as export]
            [cortex.plan]
            [cortex.render :as render]
            [cortex.demo :as demo]
            [cortex.sight :as sight]
            [cortex.sim :as sim]
            [cortex.blender :as blender]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.math ColorRGBA Vector3f)
           (java.nio.file CopyOption Files StandardCopyOption)))

(set! *warn-on-reflection* true)

(def creatures
  "The creatures lein run can show, by name: functions that load them."
  {"worm" demo/worm
   "hand" demo/hand
   "worm-eyes" #(blender/load-blender-model "Models/test-creature/worm-eyes.blend")})

(defn named-creature
  "The creature called `creature-name` (see `creatures`), loaded from
  its .blend file; an ex-info naming the choices for any other name."
  [creature-name]
  (if-let [load-creature (get creatures creature-name)]
    (load-creature)
    (throw (ex-info (str "no creature called " (pr-str creature-name)
                         "; choose one of " (str/join ", " (sort (keys creatures))))
                    {:creature creature-name}))))

(defn- drop-height
  "How far under a built `creature` the floor goes: six units for the
  reference creatures, a tenth of its height (at least 0.05) for one
  from a file."
  [creature file?]
  (if file?
    (let [[lo hi] (demo/bounds creature)]
      (max 0.05 (* 0.1 (- (double (second hi)) (double (second lo))))))
    6.0))

(defn demo-world
  "A world in which `creature` (a node loaded from Blender, given its
  body here as a simulation at `scale` would give it, :auto by default:
  see cortex.sim/scaled-body!) falls onto a floor under gravity; see
  cortex.demo/stage. Returns [world watched], where watched is an atom
  of what cortex.demo/watch measures."
  ([creature] (demo-world creature false))
  ([creature file?] (demo-world creature file? :auto))
  ([creature file? scale]
   (let [k (sim/scaled-body! creature {:scale scale})
         [watch seen] (demo/watch creature k)]
     [(demo/stage creature (drop-height creature file?) watch
                  (if (not= k 1.0)
                    {:gravity (.mult ^Vector3f demo/earth-gravity (float k))
                     :setup #(sim/scaled-substeps! (world/physics-space %) k)}
                    {}))
      seen])))

(defn- table
  "Rows (maps) as a text table with the columns `cols` ([key title])."
  [cols rows]
  (let [cell (fn [v] (cond (float? v) (format "%.4g" (double v))
                           (and (sequential? v) (every? number? v))
                           (str "[" (str/join " " (map #(format "%.3f" (double %)) v)) "]")
                           (keyword? v) (name v)
                           :else (str v)))
        cells (for [r rows] (mapv #(cell (get r (first %))) cols))
        widths (apply map max (map (comp count second) cols)
                      (map #(map count %) (or (seq cells) [(repeat (count cols) "")])))
        line (fn [xs] (str/join "  " (map #(format (str "%-" %1 "s") %2) widths xs)))]
    (str/join "\n" (concat [(line (map second cols))
                            (line (map #(apply str (repeat % "-")) widths))]
                           (map line cells)))))

(defn report-text
  "A built creature's report (see cortex.body/report) as tables."
  [{:keys [creature segments joints warnings tolerance eyes]}]
  (str "creature " creature ": " (count segments) " segments, " (count joints)
       " joints (tolerance " (format "%.3f" (double tolerance)) ")\n\n"
       (table [[:name "segment"] [:mass "mass"] [:shape "shape"] [:volume "volume"]
               [:hull-points "hull points"]]
              (for [{:keys [shape pieces] :as s} segments]
                (cond-> s pieces (assoc :shape (str (name shape) " "
                                                    (str/join "+" (map name pieces)))))))
       "\n\n"
       (table [[:name "joint"] [:type "type"] [:class "jBullet"] [:first "first"]
               [:second "second"] [:pivot "pivot (Blender)"] [:gap "distances"]
               [:limits "limits"]]
              (for [{:keys [segments distances limits] :as j} joints]
                (assoc j :first (first segments) :second (second segments)
                       :gap (mapv distances segments)
                       :limits (str/join " " (for [[k v] (sort limits)]
                                               (str (name k) " " (pr-str v)))))))
       "\n\n"
       (when (seq eyes)
         (str (table [[:name "eye"] [:kind "kind"] [:segment "segment"] [:distance "distance"]
                      [:size "image"] [:view "field of view"]]
                     (for [{:keys [resolution fov size] :as e} eyes]
                       (assoc e :size (str/join "x" resolution)
                              :view (if fov
                                      (format "%.1f x %.1f degrees" (double (first fov)) (double (second fov)))
                                      (format "%.2f x %.2f units" (double (first size)) (double (second size)))))))
              "\n\n"))
       (if (seq warnings)
         (str "warnings:\n" (str/join "\n" (map #(str "- " (:message %)) warnings)))
         "no warnings")))

(def ^:private frames-per-second
  "Simulated frames a second: the ratchet timer's step is 1/60 s."
  60)

(def ^:private cli-options
  [["-c" "--creature NAME" "the creature: worm or hand"
    :default "worm"
    :validate [#(contains? creatures %)
               (str "must be one of " (str/join ", " (sort (keys creatures))))]]
   ["-s" "--seconds SECONDS" "simulated seconds to record offscreen"
    :default 4.0
    :parse-fn parse-double
    :validate [#(and % (< 0 %) (<= % 600))
               "must be a number of seconds, more than 0 and at most 600"]]
   ["-o" "--out FOLDER" "where frames, MP4 and GIF go (default out/CREATURE); with a window, record there"]
   ["-r" "--resolution WxH" "size of the frames, or of the window"
    :default [640 480]
    :default-desc "640x480"
    :parse-fn render/parse-size]
   [nil "--headless" "draw offscreen even when there is a display"]
   [nil "--window" "open a window (needs a display)"]
   [nil "--report" "with a FILE.blend: print what body! builds of it, and stop"]
   [nil "--mjcf OUT.xml" "with a FILE.blend: write it as MuJoCo's MJCF, meshes and OUT-scene.xml (it on a floor) beside it, and stop (see org/export.org)"]
   [nil "--urdf OUT.urdf" "with a FILE.blend: write it as URDF, meshes beside it, and stop (with --mjcf too)"]
   [nil "--cone-strength HOW" "with --mjcf: per-axis (default) bounds each of a cone's three servos by its strength, inscribed by strength / sqrt 3"
    :parse-fn keyword
    :validate [#{:per-axis :inscribed} "must be per-axis or inscribed"]]
   [nil "--friction-cone CONE" "with --mjcf: pyramidal (default, MuJoCo's) or elliptic (Coulomb's, the same in every direction)"
    :parse-fn keyword
    :validate [#{:pyramidal :elliptic} "must be pyramidal or elliptic"]]
   [nil "--eyes" "record what the creature's eyes see under the world (the worm with eyes unless a FILE is given)"]
   [nil "--scale K" "build and show the creature K times its size: auto (the default) is 1, or more for a creature under 1 across (see org/sim.org)"
    :parse-fn #(if (= "auto" %) :auto (parse-double %))
    :validate [#(or (= :auto %) (and % (< 0 % Double/POSITIVE_INFINITY)))
               "must be auto or a positive number"]]
   ["-h" "--help" "say how to use lein run"]])

(defn- usage
  "The help text, around tools.cli's summary of the options."
  [summary]
  (str/join "\n" ["lein run [options] [FILE.blend]: the worm (or the hand, or the"
                  "creature in FILE.blend) falls onto a floor and comes to rest."
                  ""
                  "In a window when there is a display (space fires a ball, G/U gravity on/off,"
                  "H shows the physics, W A S D Q Z and the mouse move the camera, Esc quits);"
                  "otherwise drawn offscreen to PNG frames, an MP4 and a GIF."
                  ""
                  "Options:"
                  summary]))

(defn plan
  "What lein run should do, given its `args` and whether there is a
  `display?`: a map with :action :help, :error (with :message), :report
  (with :file), or :window or :offscreen with :creature, :frames, :out,
  :size, :record? (whether to record frames), :fallback? (whether to
  draw offscreen when the window cannot open), for a creature from a
  file :file, and when given :eyes? and :scale (see `demo-world`)."
  [args display?]
  (let [{:keys [options errors summary arguments]} (cli/parse-opts args cli-options)
        {:keys [creature seconds out resolution headless window help report eyes mjcf urdf
                cone-strength friction-cone scale]} options
        [file & extra] arguments
        creature (cond file (str/replace (.getName (io/file file)) #"\.blend$" "")
                       (and eyes (= creature "worm")) "worm-eyes"
                       :else creature)]
    (cond
      help {:action :help :message (usage summary)}
      errors {:action :error :message (str/join "\n" (conj errors "(lein run --help for help)"))}
      (seq extra) {:action :error :message (str "one creature file at a time, not " (pr-str (vec arguments)))}
      (and scale (or report mjcf urdf))
      {:action :error :message "--scale goes with showing a creature, not with --report, --mjcf or --urdf"}
      (and report (not file)) {:action :error :message "--report needs a FILE.blend"}
      report {:action :report :file file}
      (and (or mjcf urdf) (not file)) {:action :error :message "--mjcf and --urdf need a FILE.blend"}
      (and cone-strength (not mjcf)) {:action :error :message "--cone-strength goes with --mjcf"}
      (and friction-cone (not mjcf)) {:action :error :message "--friction-cone goes with --mjcf"}
      (or mjcf urdf) (cond-> {:action :export :file file :mjcf mjcf :urdf urdf}
                       cone-strength (assoc :cone-strength cone-strength)
                       friction-cone (assoc :friction-cone friction-cone))
      (and headless window) {:action :error :message "--headless and --window contradict each other"}
      (and window (not display?))
      {:action :error
       :message "no display to open a window on (DISPLAY is unset or unreachable); try --headless"}
      :else
      (cond-> {:action (if (and display? (not headless)) :window :offscreen)
               :creature creature
               :frames (max 1 (Math/round (* (double seconds) frames-per-second)))
               :out (or out (str "out/" creature))
               :record? (or (boolean headless) (not display?) (some? out))
               :fallback? (not window)
               :size resolution}
        file (assoc :file file)
        eyes (assoc :eyes? true)
        scale (assoc :scale scale)))))

(defn- still!
  "Copy the last recorded frame in `dir` to NAME.png beside it; return
  its path."
  [dir name]
  (when-let [last-frame (last (render/frames-in dir))]
    (let [still (io/file dir (str name ".png"))]
      (Files/copy (.toPath ^java.io.File last-frame) (.toPath still)
                  ^"[Ljava.nio.file.CopyOption;"
                  (into-array CopyOption [StandardCopyOption/REPLACE_EXISTING]))
      (str still))))

(defn- report-files!
  "Make the still and the videos of the frames in `out`; print where
  everything is."
  [out creature-name]
  (let [frames (count (render/frames-in out))
        still (still! out creature-name)
        videos (render/make-videos! out frames-per-second {:name creature-name})]
    (println "frames: " (str (io/file out "frame-*.png")) (str "(" frames ")"))
    (doseq [[label path] [["picture:" still] ["video:  " (:mp4 videos)] ["GIF:    " (:gif videos)]]
            :when path]
      (println label path))))

(defn- load-planned
  "The creature the plan names, loaded; for a file, its report printed
  once it is built."
  [{:keys [creature file]}]
  (if file (blender/load-blender-model file) (named-creature creature)))

(defn- scenery
  "Something for eyes to see, on the floor `drop` under built `creature`,
  ahead of it along -x: a red box, a blue ball and a yellow box (lit or
  not, they are plain colours; scenery, not physical)."
  [creature drop]
  (let [[[lx ly lz] [_ _ hz]] (demo/bounds creature)
        top (- (double ly) (double drop))
        z (/ (+ (double lz) (double hz)) 2)]
    (util/nodify "scenery"
                 [(util/box 0.4 0.4 0.4 :name "red box" :color ColorRGBA/Red :physical? false
                            :position (Vector3f. (- lx 1.5) (+ top 0.4) (+ z 0.7)))
                  (util/sphere 0.5 :name "blue ball" :color ColorRGBA/Blue :physical? false
                               :position (Vector3f. (- lx 2.5) (+ top 0.5) (- z 1.2)))
                  (util/box 0.6 0.6 0.6 :name "yellow box" :color ColorRGBA/Yellow :physical? false
                            :position (Vector3f. (- lx 4.0) (+ top 0.6) (- z 0.3)))])))

(defn- planned-world
  "[world watched creature] for the plan; a creature from a file has its
  report printed."
  [{:keys [file] :as plan}]
  (let [creature (load-planned plan)
        [w seen] (demo-world creature (some? file) (get plan :scale :auto))]
    (when file
      (println (report-text (body/report creature))))
    (when (:eyes? plan)
      (.attachChild (.getRootNode ^SimpleApplication w) (scenery creature (drop-height creature (some? file)))))
    [w seen creature]))

(defn- record-planned!
  "Record world `w` to the planned folder; with --eyes, with what the
  creature's eyes see under each frame (see cortex.sight)."
  [w creature {:keys [out eyes?]} opts]
  (if eyes?
    (sight/record-with-eyes! w creature out (assoc opts :scale (sim/built-scale creature)))
    (render/record! w out opts)))

(defn- show-offscreen!
  "Draw the demo offscreen for the planned number of frames, recording
  every one in the planned folder, then make the still and videos, and
  say how the body held and settled."
  [{:keys [creature frames out size] :as plan}]
  (let [[w seen body] (planned-world plan)
        [width height] size
        start (System/nanoTime)]
    (println "no window: drawing" (format "%.1f" (/ frames (double frames-per-second)))
             "simulated seconds of" creature "offscreen at" (str width "x" height) "...")
    (record-planned! w body plan {:progress (render/progress-printer frames)})
    (render/run-offscreen! w frames {:size size})
    (let [seconds (/ (- (System/nanoTime) start) 1e9)]
      (println (format "drew and wrote %d frames in %.1f s (%.0f a second)"
                       frames seconds (/ frames seconds))))
    (println (demo/watched @seen))
    (report-files! out creature)))

(defn- show-window!
  "Open the demo in a window and wait until it is closed, recording to
  the planned folder when asked to. When the window cannot even open (a
  display without OpenGL, say) and the plan allows it, draw offscreen
  instead."
  [{:keys [creature out size record? fallback?] :as plan}]
  (let [[w seen body] (planned-world plan)]
    (when record? (record-planned! w body plan {}))
    (println "space: fire a ball | G/U: gravity on/off | H: show physics |"
             "W A S D Q Z, mouse: camera | Esc: quit")
    (try
      (render/await-world! (render/start-window! w {:size size}))
      (println (demo/watched @seen))
      (when record? (report-files! out creature))
      (catch clojure.lang.ExceptionInfo e
        (if (and fallback? (zero? (:frames @w)))
          (do (binding [*out* *err*]
                (println (str "cortex: no window (" (ex-message e) "); drawing offscreen instead")))
              (show-offscreen! plan))
          (throw e))))))

(defn ^:api -main
  "lein run [options]: see `cli-options`, or lein run --help."
  [& args]
  (let [{:keys [action message] :as p} (plan args (render/display?))
        status (try
                 (case action
                   :help (do (println message) 0)
                   :error (do (binding [*out* *err*] (println message)) 2)
                   :report (do (println (report-text (body/report (body/body! (blender/load-blender-model (:file p)) {:strict? false})))) 0)
                   :export (do (doseq [f (export/write! (cortex.plan/plan (blender/load-blender-model (:file p))
                                                                           {:strict? false})
                                                        (:mjcf p) (:urdf p)
                                                        (assoc (select-keys p [:cone-strength :friction-cone])
                                                               :scene true))]
                                 (println "wrote" f))
                               0)
                   :window (do (show-window! p) 0)
                   :offscreen (do (show-offscreen! p) 0))
                 (catch clojure.lang.ExceptionInfo e
                   (binding [*out* *err*]
                     (println "cortex:" (ex-message e)))
                   1))]
    (flush)
    (shutdown-agents)
    (System/exit status)))
