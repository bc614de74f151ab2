;; Generated from org/repl.org by lein tangle: edit the chapter, not this file.
(ns cortex.hello-middleware
  "An nREPL middleware for the REPL tests, injected the way editors
  inject theirs: it answers the op \"hello\"."
  (:require [nrepl.middleware :refer [set-descriptor!]]
            [nrepl.misc :refer [response-for]]
            [nrepl.transport :as transport]))

(set! *warn-on-reflection* true)

(defn wrap-hello
  "Answer {:op \"hello\"} with {:hello \"from cortex\"}."
  [handler]
  (fn [{:keys [op transport] :as msg}]
    (if (= "hello" op)
      (transport/send transport (response-for msg :status :done :hello "from cortex"))
      (handler msg))))

(set-descriptor! #'wrap-hello
                 {:handles {"hello" {:doc "Says hello." :requires {} :returns {"hello" "a greeting"}}}})
