;; Generated from org/repl.org by lein tangle: edit the chapter, not this file.
(ns cortex.repl
  "lein term: a terminal REPL for machines where Leiningen's own REPL
  client (REPLy, published only on Clojars) cannot be had. Clojure's
  own REPL in the terminal, where Ctrl-C interrupts the evaluation and
  never the JVM, and beside it an nREPL server for editors, built from
  the project's :repl-options as `lein repl` builds it, so that the
  middleware editors inject is served. Line editing is rlwrap's:
  bin/lein term.

  Entry points: `-main` (what lein term runs), `start-server!`,
  `stop-server!`, `handler`, `terminal!`."
  (:require [clojure.java.io :as io]
            [clojure.main :as main]
            [nrepl.server :as nrepl])
  (:import (clojure.lang Compiler$CompilerException ExceptionInfo)
           (java.io FileNotFoundException)
           (sun.misc Signal SignalHandler)))

(set! *warn-on-reflection* true)

(def port-file
  "Where editors look for the port of a project's nREPL server."
  (io/file ".nrepl-port"))

(defn- middleware
  "The var a middleware symbol names (its namespace loaded first), or
  the value of any other form."
  [m]
  (if (symbol? m)
    (do (when-let [n (namespace m)] (require (symbol n)))
        (or (find-var m)
            (throw (ex-info (str "no nREPL middleware called " m) {:middleware m}))))
    (eval m)))

(defn handler
  "The nREPL handler `lein repl` would build from these :repl-options:
  the var :nrepl-handler names, or nREPL's default handler with the
  :nrepl-middleware added."
  [{:keys [nrepl-handler nrepl-middleware]}]
  (if nrepl-handler
    (middleware nrepl-handler)
    (apply nrepl/default-handler (map middleware nrepl-middleware))))

(defn start-server!
  "Start an nREPL server for these :repl-options (:host, default
  127.0.0.1, :port, default any free one, and the handler's options),
  write its port to .nrepl-port and say where it is, as `lein repl`
  does. Returns the server."
  ([] (start-server! {}))
  ([{:keys [host port] :as options}]
   (let [host (or host "127.0.0.1")
         server (nrepl/start-server :bind host :port (or port 0) :handler (handler options))]
     (spit port-file (str (:port server)))
     (println (str "nREPL server started on port " (:port server) " on host " host
                   " - nrepl://" host ":" (:port server)))
     server)))

(defn stop-server!
  "Stop `server` and remove .nrepl-port."
  [server]
  (nrepl/stop-server server)
  (io/delete-file port-file true))

(def ^:private grace-ms
  "How long an evaluation has to answer Ctrl-C before its thread is
  stopped."
  1000)

(defn- stop-thread!
  "Stop `thread` with Thread.stop; false where the JVM refuses it."
  [^Thread thread]
  (try (.stop thread) true
       (catch UnsupportedOperationException _ false)))

(defn- interrupter
  "A SIGINT handler for the REPL running on `thread`: `evaluating`
  holds the number of the evaluation in progress, or nil at the prompt;
  (prompt) prints the prompt."
  ^SignalHandler [^Thread thread evaluating prompt]
  (reify SignalHandler
    (handle [_ _]
      (if-let [n @evaluating]
        (do (.interrupt thread)
            (doto (Thread. ^Runnable
                           (fn []
                             (Thread/sleep (long grace-ms))
                             (when (and (= n @evaluating) (not (stop-thread! thread)))
                               (binding [*out* *err*]
                                 (println "\nThe evaluation ignores interrupts, and this Java"
                                          "cannot stop its thread."))))
                           "cortex Ctrl-C")
              (.setDaemon true)
              (.start)))
        (do (println)
            (prompt)
            (flush))))))

(defn- interrupted?
  "Whether `e` is what an interrupt or a stopped thread throws."
  [^Throwable e]
  (let [root (main/root-cause e)]
    (or (instance? InterruptedException root) (instance? ThreadDeath root))))

(defn- caught
  "Print what an evaluation threw, as Clojure's REPL does, except that
  an interrupt is one line: the message of the ex-info that reported
  it, if any (\"interrupted: the world was stopped after 300 frames\")."
  [^Throwable e]
  (if (interrupted? e)
    (let [top (if (instance? Compiler$CompilerException e) (.getCause e) e)]
      (binding [*out* *err*]
        (println (cond (instance? ExceptionInfo top) (str "Interrupted: " (ex-message top))
                       (instance? ThreadDeath (main/root-cause e))
                       "Stopped: the evaluation did not answer the interrupt within a second."
                       :else "Interrupted."))))
    (main/repl-caught e)))

(defn terminal!
  "Run Clojure's REPL on this thread, reading the terminal, until end
  of input (Ctrl-D), with Ctrl-C interrupting evaluations (see
  `interrupter`). Options, from :repl-options: :init-ns (default user)
  and :init, a form evaluated first."
  [{:keys [init-ns init] :or {init-ns 'user}}]
  (let [thread (Thread/currentThread)
        evaluating (atom nil)
        evaluations (atom 0)
        here (atom (create-ns init-ns))
        prompt #(print (str (ns-name @here) "=> "))
        previous (Signal/handle (Signal. "INT") (interrupter thread evaluating prompt))]
    (try
      (main/repl
       :init (fn []
               (try (require init-ns) (catch FileNotFoundException _))
               (in-ns init-ns)
               (apply require main/repl-requires)
               (when init (eval init)))
       :prompt (fn [] (reset! here *ns*) (prompt))
       :eval (fn [form]
               (Thread/interrupted)
               (reset! evaluating (swap! evaluations inc))
               (try (eval form)
                    (finally
                      (reset! evaluating nil)
                      (Thread/interrupted))))
       :caught caught)
      (finally (Signal/handle (Signal. "INT") previous)))))

(defn -main
  "lein term: start the nREPL server, then the REPL in the terminal; when
  the REPL reads end of input (Ctrl-D), stop the server and leave.
  `options` is the project's :repl-options, printed (the alias in
  project.clj passes them)."
  ([] (-main "{}"))
  ([options]
   (let [options (binding [*read-eval* false] (read-string options))]
     ;; the names Clojure's REPL gives typed code, for errors and for
     ;; the sessions of the nREPL server, which start with these bindings
     (binding [*file* "NO_SOURCE_PATH" *source-path* "NO_SOURCE_FILE"]
       (let [server (start-server! options)]
         (println (str "Clojure " (clojure-version)
                       " in cortex: Ctrl-C interrupts an evaluation, Ctrl-D leaves."))
         (try (terminal! options)
              (finally
                ;; leaving: a Ctrl-C now (or one the terminal delivers
                ;; late) must not turn a clean exit into the JVM's 130
                (Signal/handle (Signal. "INT") SignalHandler/SIG_IGN)
                (stop-server! server))))))
   (shutdown-agents)
   (System/exit 0)))
