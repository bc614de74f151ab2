(ns cortex.repl-test
  (:require [clojure.test :refer [deftest is]]
            [cortex.repl :as repl]
            [nrepl.core :as nrepl]))

(set! *warn-on-reflection* true)

(deftest editors-can-reach-the-server
  (let [server (binding [*out* (java.io.StringWriter.)] (repl/start-server!))]
    (try
      (is (= (str (:port server)) (slurp repl/port-file)))
      (with-open [conn (nrepl/connect :port (:port server))]
        (is (= [3] (nrepl/response-values
                    (nrepl/message (nrepl/client conn 5000) {:op "eval" :code "(+ 1 2)"})))))
      (finally (repl/stop-server! server)))
    (is (not (.exists repl/port-file)))))
