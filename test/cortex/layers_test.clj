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

(deftest the-step-loop-loads-neither-the-reader-nor-the-renderer
  (let [loaded (set (loaded-after '[cortex.sim]))]
    (is (contains? loaded "cortex.sim"))
    (is (not-any? #(or (str/starts-with? % "cortex.blender") (= % "cortex.render")
                       (= % "cortex.sight") (= % "cortex.physics-tab"))
                  loaded)
        (str "requiring cortex.sim loaded " (sort loaded)))))

(defn- required
  "The namespaces the ns form at the head of `file` requires."
  [^java.io.File file]
  (let [[_ _ & clauses] (binding [*read-eval* false]
                          (with-open [r (java.io.PushbackReader. (clojure.java.io/reader file))]
                            (read r)))]
    (for [[k & specs] clauses :when (= :require k)
          spec specs]
      (if (sequential? spec) (first spec) spec))))

(deftest no-tool-requires-a-test
  (let [tools (for [dir ["dev" "engine/jbullet/dev" "engine/native/dev"]
                    ^java.io.File f (file-seq (java.io.File. ^String dir))
                    :when (str/ends-with? (.getName f) ".clj")]
                f)]
    (is (< 10 (count tools)) "the tools are found")
    (doseq [f tools]
      (is (not-any? #(str/ends-with? (name %) "-test") (required f)) (str f)))))
