;; Generated from org/repl.org by lein tangle: edit the chapter, not this file.
(ns cortex.repl-test
  (:require [clojure.java.io :as io]
            [clojure.java.shell :as sh]
            [clojure.string :as str]
            [clojure.test :refer [deftest is testing use-fixtures]]
            [cortex.repl :as repl]
            [nrepl.core :as nrepl]
            [nrepl.transport :as transport])
  (:import (java.io BufferedReader File)
           (java.lang ProcessBuilder$Redirect ProcessHandle)
           (java.util.concurrent TimeUnit)))

(set! *warn-on-reflection* true)

(def commands
  "What the tests run, as a person would type it."
  {:term "bin/lein term"
   :headless "bin/lein repl :headless"
   :jack-in (str "bin/lein update-in :repl-options assoc :nrepl-middleware"
                 " '[cortex.hello-middleware/wrap-hello]' -- repl :headless")
   :jack-in-term (str "bin/lein update-in :repl-options assoc :nrepl-middleware"
                      " '[cortex.hello-middleware/wrap-hello]' -- term")})

(defn- start-process
  "Start `command` under bash -c in the project folder, with `env`
  added to the environment. Returns {:process p :output StringBuffer}."
  ([command] (start-process command {}))
  ([command env]
   (let [^java.util.List argv ["bash" "-c" command]
         pb (doto (ProcessBuilder. argv)
              (.redirectErrorStream true))
         _ (.putAll (.environment pb) ^java.util.Map env)
         p (.start pb)
         output (StringBuffer.)]
     (doto (Thread. ^Runnable
                    (fn []
                      (let [in (.getInputStream p)
                            buf (byte-array 4096)]
                        (loop []
                          (let [n (.read in buf)]
                            (when (pos? n)
                              (.append output (String. buf 0 n "UTF-8"))
                              (recur)))))))
       (.setDaemon true)
       (.start))
     {:process p :output output})))

(defn- wait-for
  "Wait until the output of `proc` after character `from` matches `re`,
  or `seconds` have passed. Returns the match, or nil."
  ([proc re seconds] (wait-for proc re seconds 0))
  ([{:keys [^StringBuffer output]} re seconds from]
   (let [deadline (+ (System/currentTimeMillis) (* 1000 seconds))]
     (loop []
       (let [text (subs (str output) (min from (.length output)))]
         (or (re-find re text)
             (when (< (System/currentTimeMillis) deadline)
               (Thread/sleep 50)
               (recur))))))))

(defn- type-into!
  "Send `text` to the standard input of `proc`."
  [{:keys [^Process process]} ^String text]
  (doto (.getOutputStream process)
    (.write (.getBytes text "UTF-8"))
    (.flush)))

(defn- stop-process!
  "Stop `proc` and every process under it."
  [{:keys [^Process process]}]
  (let [handles (cons (.toHandle process) (iterator-seq (.iterator (.descendants process))))]
    (doseq [^ProcessHandle h handles] (.destroy h))
    (doseq [^ProcessHandle h handles]
      (try (.get (.onExit h) 10 TimeUnit/SECONDS)
           (catch Exception _ (.destroyForcibly h))))))

(defn- port-in
  "The port an nREPL server in `proc` says it listens on."
  [proc seconds]
  (some-> (wait-for proc #"nREPL server started on port (\d+)" seconds) second Long/parseLong))

(defn- port-file-says
  "What .nrepl-port holds once it holds something, waiting up to
  `seconds`: Leiningen prints the port a moment before it writes the
  file, as an editor that polls the file would see."
  [seconds]
  (let [file (File. ".nrepl-port")
        deadline (+ (System/currentTimeMillis) (* 1000 seconds))]
    (loop []
      (let [text (when (.exists file) (str/trim (slurp file)))]
        (if (or (seq text) (> (System/currentTimeMillis) deadline))
          text
          (do (Thread/sleep 50) (recur)))))))

(defn- start-xvfb
  "Start Xvfb on a free display. Returns {:process p :display \":N\"},
  or nil when Xvfb cannot be started."
  []
  (try
    (let [^java.util.List argv ["Xvfb" "-displayfd" "1" "-screen" "0" "1024x768x24"
                                "-nolisten" "tcp" "-noreset"]
          p (-> (ProcessBuilder. argv)
                (.redirectError ProcessBuilder$Redirect/DISCARD)
                (.start))
          number (future (.readLine ^BufferedReader (io/reader (.getInputStream p))))]
      (if-let [n (deref number 20000 nil)]
        {:process p :display (str ":" (str/trim n))}
        (do (.destroy p) nil)))
    (catch java.io.IOException _ nil)))

(defn- read-until
  "Read messages from `conn` until one satisfies `done?` or `seconds`
  pass. Returns those read, in order."
  [conn done? seconds]
  (let [deadline (+ (System/currentTimeMillis) (* 1000 seconds))]
    (loop [seen []]
      (let [left (- deadline (System/currentTimeMillis))
            msg (when (pos? left) (transport/recv conn (min left 1000)))
            seen (cond-> seen msg (conj msg))]
        (if (or (and msg (done? msg)) (not (pos? left)))
          seen
          (recur seen))))))

(defn- request
  "Send `msg` (given an id) on `conn` and return the messages that
  answer it, up to its `done`."
  ([conn msg] (request conn msg 60))
  ([conn msg seconds]
   (let [id (str (random-uuid))]
     (transport/send conn (assoc msg :id id))
     (filterv #(= id (:id %))
              (read-until conn #(and (= id (:id %)) (some #{"done"} (:status %))) seconds)))))

(defn- evaluate
  "Evaluate `code` through `conn`: {:values [...] :out \"...\" :err \"...\"}."
  ([conn code] (evaluate conn code {}))
  ([conn code msg]
   (let [answers (request conn (merge {:op "eval" :code code} msg))]
     {:values (mapv read-string (keep :value answers))
      :out (apply str (keep :out answers))
      :err (apply str (keep :err answers))})))

(defn- value
  "The value of `code` evaluated through `conn`; an ex-info with the
  server's complaint when there is none."
  [conn code]
  (let [{:keys [values err]} (evaluate conn code)]
    (if (seq values)
      (last values)
      (throw (ex-info (str "no value from " code ": " err) {})))))

(defn- new-session
  "A new nREPL session on `conn`."
  [conn]
  (some :new-session (request conn {:op "clone"})))

(def ^:private shared (atom nil))

(defn- server
  "{:port p :display d}: the port of the shared nREPL server (see
  `commands`, :jack-in) and the Xvfb display it sees, starting both if
  needed."
  []
  (or (:server @shared)
      (let [xvfb (start-xvfb)
            proc (start-process (:jack-in commands) (if xvfb {"DISPLAY" (:display xvfb)} {}))
            port (port-in proc 180)]
        (swap! shared assoc :xvfb xvfb :proc proc)
        (when-not port
          (throw (ex-info (str "the nREPL server did not start:\n" (:output proc)) {})))
        (:server (swap! shared assoc :server {:port port :display (:display xvfb)})))))

(defn- around-all
  "Keep .nrepl-port as it was; stop the shared server and Xvfb after the
  tests."
  [f]
  (let [port-file (io/file ".nrepl-port")
        before (when (.exists port-file) (slurp port-file))]
    (try (f)
         (finally
           (let [{:keys [proc xvfb]} @shared]
             (some-> proc stop-process!)
             (some-> xvfb stop-process!)
             (reset! shared nil))
           (if before (spit port-file before) (io/delete-file port-file true))))))

(use-fixtures :once around-all)

(defn- connect
  "A connection to the shared nREPL server, or, given a port, to that
  one's."
  (^java.io.Closeable [] (connect (:port (server))))
  (^java.io.Closeable [port] (nrepl/connect :port port)))

(deftest injected-middleware-answers
  (with-open [conn (connect)]
    (is (= "from cortex" (some :hello (request conn {:op "hello"}))))
    (is (contains? (set (keys (some :ops (request conn {:op "describe"})))) :hello))))

(deftest doc-works-in-a-plain-session
  (with-open [conn (connect)]
    (is (= "user" (some :ns (request conn {:op "eval" :code "(doc map)"}))))
    (is (str/includes? (:out (evaluate conn "(doc map)")) "clojure.core/map"))
    (is (= 'user (value conn "(ns-name *ns*)")))))

(deftest errors-name-the-repl
  (with-open [conn (connect)]
    (let [{:keys [err]} (evaluate conn "(/ 1 0)")]
      (is (str/includes? err "Divide by zero"))
      (is (str/includes? err "(REPL:1)"))
      (is (not (str/includes? err "form-init")) err))
    (let [{:keys [err]} (evaluate conn "(let [x] x)")]
      (is (str/includes? err "(REPL:1:1)"))
      (is (not (str/includes? err "form-init")) err))))

(deftest interrupting-a-world-stops-it
  (with-open [conn (connect)
              watcher (connect)]
    (value watcher "(require '[cortex.world :as world] '[cortex.util :as util])")
    (value watcher (str "(def interrupted-world (world/world (util/nodify []) {} world/no-op"
                        " (fn [_ _] (Thread/sleep 1))))"))
    (let [session (new-session conn)
          id "run-for-ever"]
      (transport/send conn {:op "eval" :id id :session session
                            :code "(world/run-world! interrupted-world 100000000)"})
      (let [deadline (+ (System/currentTimeMillis) 20000)]
        (while (and (< (value watcher "(:frames @interrupted-world)") 10)
                    (< (System/currentTimeMillis) deadline))
          (Thread/sleep 50)))
      (is (<= 10 (value watcher "(:frames @interrupted-world)")) "the world ran")
      (let [iid (str (random-uuid))
            _ (transport/send conn {:op "interrupt" :session session :interrupt-id id :id iid})
            answers (read-until conn #(and (= iid (:id %)) (some #{"done"} (:status %))) 20)]
        (is (some #(and (= id (:id %)) (some #{"interrupted"} (:status %))) answers)
            (pr-str answers)))
      (let [deadline (+ (System/currentTimeMillis) 10000)]
        (while (and (value watcher "(world/running? interrupted-world)")
                    (< (System/currentTimeMillis) deadline))
          (Thread/sleep 50)))
      (is (false? (value watcher "(world/running? interrupted-world)")))
      (is (false? (value watcher "(.isAlive ^Thread (:thread @interrupted-world))")))
      (is (< (value watcher "(:frames @interrupted-world)") 100000000)))))

(deftest a-world-prints-to-the-client
  (with-open [conn (connect)]
    (value conn "(require '[cortex.world :as world] '[cortex.util :as util])")
    (is (= :started
           (value conn (str "(do (def talking-world"
                            "       (world/world (util/nodify []) {} world/no-op"
                            "         (fn [w _] (when (= 30 (:frames @w))"
                            "                     (println \"hello from the world's thread\")"
                            "                     (world/stop! w)))))"
                            "     (world/start! talking-world)"
                            "     :started)"))))
    (let [later (read-until conn #(some-> (:out %) (str/includes? "world's thread")) 20)]
      (is (some #(some-> (:out %) (str/includes? "hello from the world's thread")) later)
          (pr-str later)))
    (is (false? (value conn "(do (world/await! talking-world 10000) (world/running? talking-world))")))))

(defn- worm-green?
  "Whether an [r g b] colour is the worm's green, lit or shaded: the
  floor's grey and the blue sky are not."
  [[r g b]]
  (and (> g (+ r 25)) (> g (+ b 25))))

(deftest a-window-on-xvfb
  (let [{:keys [display]} (server)]
    (is display "Xvfb could not be started: bin/lein installs it (Debian's xvfb)")
    (when display
      (with-open [conn (connect)]
        (value conn "(require '[cortex.render :as render] '[cortex.world :as world])")
        (value conn (str "(do (def window-frame (promise))"
                         "    (defn rgb [^java.awt.image.BufferedImage im x y]"
                         "      (let [p (.getRGB im (int x) (int y))]"
                         "        [(bit-and 0xff (bit-shift-right p 16)) (bit-and 0xff (bit-shift-right p 8))"
                         "         (bit-and 0xff p)]))"
                         "    (defn grab-thirtieth [w worm]"
                         "      (render/grab-frames! w"
                         "        (fn [im]"
                         "          (when (and (= 30 (:frames @w)) (not (realized? window-frame)))"
                         "            (let [cam (.getCamera w)"
                         "                  s (.getScreenCoordinates cam (.getCenter (.getWorldBound worm)))"
                         "                  x (Math/round (.x s)) y (- (.getHeight cam) 1 (Math/round (.y s)))]"
                         "              (deliver window-frame"
                         "                {:at [x y] :size [(.getWidth im) (.getHeight im)]"
                         "                 :patch (vec (for [dx (range -2 3) dy (range -2 3)]"
                         "                               (rgb im (+ x dx) (+ y dy))))"
                         "                 :corners [(rgb im 2 2) (rgb im (- (.getWidth im) 3) (- (.getHeight im) 3))]}))))))"
                         "    :ok)"))
        (let [started (value conn (str "(let [worm (creature \"worm\")"
                                       "      w (#'user/staged worm)"
                                       "      _ (grab-thirtieth w worm)"
                                       "      start (System/nanoTime)]"
                                       "  (render/start-window! w {:size [320 240]})"
                                       "  (reset! shown w)"
                                       "  (/ (- (System/nanoTime) start) 1e9))"))]
          (is (< started 1.0) (str "start-window! took " started " s")))
        (let [{:keys [at size patch corners] :as frame}
              (value conn "(deref window-frame 60000 :no-frame)")]
          (is (map? frame) (str "no frame came from the window: " frame))
          (when (map? frame)
            (is (= [320 240] size))
            (is (<= (* 0.6 (count patch)) (count (filter worm-green? patch)))
                (str "the colours where the worm is, " at ": " patch))
            (is (not-any? worm-green? corners) (str "sky and floor: " corners))))
        (testing "the X server shows the window while the world runs"
          (is (str/includes? (value conn "(:out (clojure.java.shell/sh \"xwininfo\" \"-root\" \"-tree\"))")
                             "\"cortex\"")))
        (let [stopped (value conn (str "(let [start (System/nanoTime)]"
                                       "  (stop!)"
                                       "  (/ (- (System/nanoTime) start) 1e9))"))]
          (is (< stopped 1.0) (str "stop! took " stopped " s")))
        (testing "stopped, the window is gone and the world's thread has ended"
          (is (not (str/includes? (value conn "(:out (clojure.java.shell/sh \"xwininfo\" \"-root\" \"-tree\"))")
                                  "\"cortex\"")))
          (is (false? (value conn "(world/running? @shown)")))
          (is (false? (value conn "(.isAlive ^Thread (:thread @@shown))")))
          (is (nil? (value conn "(some-> (:error @@shown) ex-message)"))))))))

(deftest user-loads-no-cortex
  (let [form (str "(prn [(sort (filter #(.startsWith (str %) \"cortex\") (map ns-name (all-ns))))"
                  "      (mapv #(some? (ns-resolve 'user %)) '[doc source pst pprint reset show! record!])])")
        {:keys [exit out err]} (sh/sh "java" "-cp" (System/getProperty "java.class.path")
                                      "clojure.main" "-e" form)]
    (is (zero? exit) err)
    (let [[loaded resolved] (read-string (last (str/split-lines out)))]
      (is (empty? loaded) (str "loading user loaded " (vec loaded)))
      (is (every? true? resolved)))))

(def ^:private reset-code
  "(reset), with a failure as its message rather than an exception."
  "(let [r (reset)] (if (instance? Throwable r) (clojure.main/err->msg r) r))")

(deftest reset-reloads
  (with-open [conn (connect)]
    (let [{:keys [values out err]} (evaluate conn reset-code)]
      (is (= [:ok] values) (str out err))
      (is (not (str/includes? out "wrote")) out))
    (is (= :ok (value conn reset-code)) "and again, with nothing changed")))

(deftest the-terminal-repl
  (let [proc (start-process (str "script -qfec 'stty cols 100 rows 40; exec " (:term commands)
                                 "' /dev/null")
                            {"TERM" "xterm"})
        mark (fn [] (.length ^StringBuffer (:output proc)))
        answer (fn [text re seconds]
                 (let [from (mark)]
                   (type-into! proc text)
                   (wait-for proc re seconds from)))]
    (try
      (is (wait-for proc #"Ctrl-D leaves" 180) (str (:output proc)))
      (is (port-in proc 1) "an nREPL server runs beside it")
      (is (answer "(str \"A\" \"B\")\n" #"\"AB\"" 20))
      (is (answer "(doc map)\n" #"clojure.core/map" 20))
      (let [from (mark)]
        (type-into! proc "(Thread/sleep 60000)\n")
        (Thread/sleep 2000)
        (is (answer "\u0003" #"Interrupted" 10) "Ctrl-C interrupts a sleep")
        (is (nil? (re-find #"Thread/sleep 60000\)[\s\S]*Exception" (subs (str (:output proc)) from)))))
      (is (answer "(str \"C\" \"D\")\n" #"\"CD\"" 20) "and the REPL answers again")
      (type-into! proc "(loop [] (recur))\n")
      (Thread/sleep 2000)
      (is (answer "\u0003" #"Stopped" 10) "a loop that never waits is stopped")
      (is (answer "(str \"E\" \"F\")\n" #"\"EF\"" 20))
      (is (answer "\u001b[A\n" #"\"EF\"" 20) "Up brings the last form back")
      (type-into! proc "\u0003")
      (Thread/sleep 500)
      (is (answer "(str \"G\" \"H\")\n" #"\"GH\"" 20) "Ctrl-C at the prompt changes nothing")
      (type-into! proc "\u0004")
      (is (.waitFor ^Process (:process proc) 30 TimeUnit/SECONDS) "Ctrl-D leaves")
      (is (= 0 (.exitValue ^Process (:process proc))) (str (:output proc)))
      (finally (stop-process! proc)))))

(deftest the-terminal-repl-serves-injected-middleware
  (let [proc (start-process (:jack-in-term commands))]
    (try
      (let [port (port-in proc 180)]
        (is port (str (:output proc)))
        (when port
          (with-open [conn (connect port)]
            (is (= "from cortex" (some :hello (request conn {:op "hello"}))))
            (is (str/includes? (:out (evaluate conn "(doc map)")) "clojure.core/map")))))
      (.close (.getOutputStream ^Process (:process proc)))
      (is (.waitFor ^Process (:process proc) 30 TimeUnit/SECONDS) "end of input leaves")
      (finally (stop-process! proc)))))

(deftest lein-repl-headless
  (let [proc (start-process (:headless commands))]
    (try
      (let [port (port-in proc 180)]
        (is port (str (:output proc)))
        (when port
          (is (= (str port) (port-file-says 20)) "editors find it in .nrepl-port")
          (with-open [conn (connect port)]
            (is (= 3 (value conn "(+ 1 2)")))
            (is (= 'user (value conn "(ns-name *ns*)"))))))
      (finally (stop-process! proc)))))

(deftest the-terminal-repls-server
  (let [server (binding [*out* (java.io.StringWriter.)]
                 (repl/start-server! {:nrepl-middleware '[cortex.hello-middleware/wrap-hello]}))]
    (try
      (is (= (str (:port server)) (slurp repl/port-file)))
      (with-open [conn (connect (:port server))]
        (is (= 3 (value conn "(+ 1 2)")))
        (is (= "from cortex" (some :hello (request conn {:op "hello"})))))
      (finally (repl/stop-server! server)))
    (is (not (.exists ^File repl/port-file)))))

(deftest the-readme-shows-only-tested-commands
  (let [readme (slurp "README.md")
        start (str/index-of readme "## Working at the REPL")
        section (when start
                  (let [end (str/index-of readme "\n## " (inc start))]
                    (subs readme start (or end (count readme)))))
        shown (for [[_ block] (re-seq #"(?s)```sh\n(.*?)```" (or section ""))
                    line (str/split-lines block)
                    :let [command (str/trim (str/replace line #"\s+#.*$" ""))]
                    :when (seq command)]
                command)]
    (is section "the README has a section \"Working at the REPL\"")
    (is (seq shown))
    (doseq [command shown]
      (is (contains? (set (vals commands)) command)
          (str "the README shows a command no test runs: " command)))))

(deftest the-readme-repl-examples-run
  (let [readme (slurp "README.md")
        start (str/index-of readme "## Working at the REPL")
        section (subs readme start (or (str/index-of readme "\n## " (inc start)) (count readme)))
        blocks (map second (re-seq #"(?s)```clojure\n(.*?)```" section))]
    (is (seq blocks))
    (with-open [conn (connect)]
      (doseq [block blocks]
        (let [answers (request conn {:op "eval" :code block} 180)]
          (is (not-any? #(some #{"eval-error"} (:status %)) answers)
              (str "the README's\n" block "\nfailed: " (apply str (keep :err answers)))))))))
