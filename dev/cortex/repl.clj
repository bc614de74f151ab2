(ns cortex.repl
  "What `lein repl` runs in cortex: an nREPL server for editors and a
  plain Clojure REPL in the terminal. Leiningen's own REPL client comes
  only from Clojars, which the machines cortex is built on cannot
  reach; the nREPL server needs nothing but the nrepl jar Debian ships."
  (:require [clojure.java.io :as io]
            [clojure.main :as main]
            [nrepl.server :as nrepl]))

(set! *warn-on-reflection* true)

(def port-file
  "Where editors look for the port of a project's nREPL server."
  (io/file ".nrepl-port"))

(defn start-server!
  "Start an nREPL server on a free port of 127.0.0.1 and write its port
  to .nrepl-port. Returns the server."
  []
  (let [server (nrepl/start-server :bind "127.0.0.1")]
    (spit port-file (str (:port server)))
    (println (str "nREPL server started on port " (:port server)
                  " on host 127.0.0.1 - nrepl://127.0.0.1:" (:port server)))
    server))

(defn stop-server!
  "Stop `server` and remove .nrepl-port."
  [server]
  (nrepl/stop-server server)
  (io/delete-file port-file true))

(defn -main
  "lein repl            a REPL here, and an nREPL server for editors
   lein repl :headless  only the server, until the process is stopped"
  [& args]
  (let [server (start-server!)]
    (if (some #{":headless"} args)
      @(promise)
      (try
        (main/repl :init (fn []
                           (in-ns 'user)
                           (apply require main/repl-requires)))
        (finally
          (stop-server! server)
          (shutdown-agents))))))
