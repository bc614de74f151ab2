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
            [cortex.render :as render]
            [cortex.demo :as demo]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.math Vector3f)
           (java.nio.file CopyOption Files StandardCopyOption)))

(set! *warn-on-reflection* true)

(def creatures
  "The creatures lein run can show, by name: functions that load them."
  {"worm" demo/worm
   "hand" demo/hand})

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
  body here) falls onto a floor under gravity; see cortex.demo/stage.
  Returns [world watched], where watched is an atom of what
  cortex.demo/watch measures."
  ([creature] (demo-world creature false))
  ([creature file?]
   (let [built (body/body! creature)
         [watch seen] (demo/watch built)]
     [(demo/stage built (drop-height built file?) watch) seen])))

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
  [{:keys [creature segments joints warnings tolerance]}]
  (str "creature " creature ": " (count segments) " segments, " (count joints)
       " joints (tolerance " (format "%.3f" (double tolerance)) ")\n\n"
       (table [[:name "segment"] [:mass "mass"] [:hull-points "hull points"]
               [:hull-volume "hull volume"]]
              segments)
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
  draw offscreen when the window cannot open) and, for a creature from
  a file, :file."
  [args display?]
  (let [{:keys [options errors summary arguments]} (cli/parse-opts args cli-options)
        {:keys [creature seconds out resolution headless window help report]} options
        [file & extra] arguments
        creature (if file (str/replace (.getName (io/file file)) #"\.blend$" "") creature)]
    (cond
      help {:action :help :message (usage summary)}
      errors {:action :error :message (str/join "\n" (conj errors "(lein run --help for help)"))}
      (seq extra) {:action :error :message (str "one creature file at a time, not " (pr-str (vec arguments)))}
      (and report (not file)) {:action :error :message "--report needs a FILE.blend"}
      report {:action :report :file file}
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
        file (assoc :file file)))))

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
  (if file (util/load-blender-model file) (named-creature creature)))

(defn- planned-world
  "[world watched] for the plan; a creature from a file has its report
  printed."
  [{:keys [file] :as plan}]
  (let [creature (load-planned plan)
        [w seen] (demo-world creature (some? file))]
    (when file
      (println (report-text (body/report creature))))
    [w seen]))

(defn- show-offscreen!
  "Draw the demo offscreen for the planned number of frames, recording
  every one in the planned folder, then make the still and videos, and
  say how the body held and settled."
  [{:keys [creature frames out size] :as plan}]
  (let [[w seen] (planned-world plan)
        [width height] size
        start (System/nanoTime)]
    (println "no window: drawing" (format "%.1f" (/ frames (double frames-per-second)))
             "simulated seconds of" creature "offscreen at" (str width "x" height) "...")
    (render/record! w out {:progress (render/progress-printer frames)})
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
  (let [[w seen] (planned-world plan)]
    (when record? (render/record! w out))
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

(defn -main
  "lein run [options]: see `cli-options`, or lein run --help."
  [& args]
  (let [{:keys [action message] :as p} (plan args (render/display?))
        status (try
                 (case action
                   :help (do (println message) 0)
                   :error (do (binding [*out* *err*] (println message)) 2)
                   :report (do (println (report-text (body/report (body/body! (util/load-blender-model (:file p)) {:strict? false})))) 0)
                   :window (do (show-window! p) 0)
                   :offscreen (do (show-offscreen! p) 0))
                 (catch clojure.lang.ExceptionInfo e
                   (binding [*out* *err*]
                     (println "cortex:" (ex-message e)))
                   1))]
    (flush)
    (shutdown-agents)
    (System/exit status)))
