;; Generated from org/index.org by lein tangle: edit the chapter, not this file.
(ns cortex.layers-test
  (:require [clojure.java.shell :as sh]
            [clojure.string :as str]
            [clojure.test :refer [deftest is]]))

(set! *warn-on-reflection* true)

(defn- loaded-after
  "The cortex namespaces a fresh JVM on this classpath has loaded after
  requiring `namespaces`."
  [namespaces]
  (let [form (pr-str `(do (apply require '~namespaces)
                          (prn (sort (filter #(str/starts-with? % "cortex")
                                             (map (comp str ns-name) (all-ns)))))))
        {:keys [exit out err]} (sh/sh "java" "-cp" (System/getProperty "java.class.path")
                                      "clojure.main" "-e"
                                      (str "(require 'clojure.string) " form))]
    (is (zero? exit) err)
    (read-string (last (str/split-lines out)))))

(deftest body-and-world-do-not-load-the-reader
  (let [loaded (set (loaded-after '[cortex.body cortex.world]))]
    (is (contains? loaded "cortex.body"))
    (is (contains? loaded "cortex.world"))
    (is (not-any? #(str/starts-with? % "cortex.blender") loaded)
        (str "the reader was loaded: " (sort loaded)))))
