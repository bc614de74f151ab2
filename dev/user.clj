;; Generated from org/repl.org by lein tangle: edit the chapter, not this file.
(ns user
  "The REPL's home. clojure.repl and clojure.pprint are referred (doc,
  source, apropos, pst, pprint, ...), and:

    (reset)                        write src/ test/ dev/ java/ again from
                                   org/ and reload what changed
    (creature \"worm\")             a creature: worm, hand, or a .blend file
    (show! \"worm\")                it falls onto a lit floor in a window;
                                   returns the world at once
    (stop!)                        stop the world show! started
    (record! \"worm\" \"out/worm\" 4) 4 s of that, offscreen, as PNG, MP4, GIF

  cortex is loaded only when a helper is called, so that loading this
  namespace, which every JVM of the project does, loads none of it."
  (:require [clojure.java.io :as io]
            [clojure.pprint :refer :all]
            [clojure.repl :refer :all]
            [clojure.string :as str]))

(set! *warn-on-reflection* true)

(defn- compiled-ahead?
  "Whether namespace `n` was loaded from a class compiled ahead of time
  that is newer than its source."
  [n]
  (let [path (-> (name (ns-name n)) (str/replace "-" "_") (str/replace "." "/"))
        class-file (io/resource (str path "__init.class"))
        source (io/resource (str path ".clj"))]
    (boolean (and class-file source
                  (= "file" (.getProtocol ^java.net.URL class-file) (.getProtocol ^java.net.URL source))
                  (> (.lastModified (io/file class-file)) (.lastModified (io/file source)))))))

(defn- hold-compiled!
  "Tell tools.namespace not to reload the loaded namespaces that are
  compiled ahead of time (see `compiled-ahead?`), and to reload again
  those held before whose source is now newer. Returns the names of
  those held."
  []
  (let [load-key :clojure.tools.namespace.repl/load]
    (doall
     (for [n (all-ns)
           :let [ahead? (and (str/starts-with? (name (ns-name n)) "cortex")
                             (compiled-ahead? n))
                 held? (::held (meta n))]
           :when (or ahead? held?)]
       (if ahead?
         (do (alter-meta! n assoc load-key false ::held true) (ns-name n))
         (do (alter-meta! n dissoc load-key ::held) nil))))))

(defn reset
  "Write src/, test/, dev/ and java/ again from the chapters in org/,
  then reload every namespace of src/ and dev/cortex/ whose file changed
  since the last reset (the first time, all of them), keeping the
  current namespace's aliases pointing at the reloaded namespaces.
  Returns :ok, or the exception that stopped the reload."
  []
  (let [written ((requiring-resolve 'cortex.tangle/tangle!) "org")
        here *ns*
        aliases (into {} (for [[a n] (ns-aliases here)] [a (ns-name n)]))]
    (doseq [f written] (println "wrote" f))
    (when (some #(str/ends-with? % ".java") written)
      (println "A Java class changed: start a new REPL to compile it."))
    ((requiring-resolve 'clojure.tools.namespace.repl/set-refresh-dirs) "src" "dev/cortex")
    (when-let [held (seq (remove nil? (hold-compiled!)))]
      (println "Not reloaded, compiled ahead of time in target/classes (lein clean removes them):"
               (str/join ", " (sort held))))
    (doseq [a (keys aliases)] (ns-unalias here a))
    (try ((requiring-resolve 'clojure.tools.namespace.repl/refresh))
         (finally
           (doseq [[a n] aliases
                   :let [target (find-ns n)]
                   :when (and target (not (contains? (ns-aliases here) a)))]
             (.addAlias ^clojure.lang.Namespace here a target))))))

(defonce ^{:doc "An atom holding the world show! started last."} shown (atom nil))

(defn creature
  "A creature, loaded but not yet given its body: \"worm\" or \"hand\",
  or the path of a .blend file."
  [name-or-file]
  (if (str/ends-with? (str name-or-file) ".blend")
    ((requiring-resolve 'cortex.blender/load-blender-model) name-or-file)
    ((requiring-resolve 'cortex.main/named-creature) name-or-file)))

(defn- staged
  "The world of `c` (see `creature`: a name, a file or a loaded
  creature) falling onto a lit floor, as lein run shows it."
  [c]
  (first ((requiring-resolve 'cortex.main/demo-world) (if (string? c) (creature c) c))))

(defn stop!
  "Stop the world show! started, if it is running. Returns it."
  []
  (when-let [w @shown]
    ((requiring-resolve 'cortex.world/stop!) w)))

(defn show!
  "Stop the world shown before, then start `c` (a name, a file or a
  loaded creature) falling onto a lit floor in a window, and return its
  world at once (also kept in `shown`). Options as for
  cortex.render/start-window!: :size [width height], :fps."
  ([c] (show! c {}))
  ([c options]
   (stop!)
   (let [w (staged c)]
     ((requiring-resolve 'cortex.render/start-window!) w options)
     (reset! shown w))))

(defn record!
  "Record `seconds` (default 4) of `c` (a name, a file or a loaded
  creature) falling onto a lit floor, offscreen at 640x480, into folder
  `dir`: PNG frames, then an MP4 and a GIF when ffmpeg is installed.
  Returns {:mp4 path :gif path}, or nil without ffmpeg."
  ([c dir] (record! c dir 4))
  ([c dir seconds]
   (let [w (staged c)
         frames (long (Math/round (* 60.0 seconds)))]
     ((requiring-resolve 'cortex.render/record!)
      w dir {:progress ((requiring-resolve 'cortex.render/progress-printer) frames)})
     ((requiring-resolve 'cortex.render/run-offscreen!) w frames {:size [640 480]})
     ((requiring-resolve 'cortex.render/make-videos!) dir 60))))
