;; Generated from org/api.org by lein tangle: edit the chapter, not this file.
(ns cortex.api-test
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.api :as api]))

(set! *warn-on-reflection* true)

(deftest the-index-is-written-from-the-marks
  (is (= (api/markdown) (slurp api/path))
      "doc/api.md differs from the ^:api marks: run bin/lein run -m cortex.api")
  (let [vs (mapcat second (api/api-vars))]
    (is (< 30 (count vs) 150) (str (count vs) " vars marked"))
    (doseq [v vs]
      (is (not (str/blank? (:doc (meta v)))) (str v " is marked ^:api and has no docstring")))))

(defn- documents []
  (cons (io/file "README.md")
        (sort-by str (filter #(str/ends-with? (str %) ".md") (file-seq (io/file "doc"))))))

(defn- clojure-blocks [text]
  (map second (re-seq #"(?s)```clojure[^\n]*\n(.*?)```" text)))

(defn- called-vars
  "The cortex vars a document's Clojure blocks name, as symbols."
  [text]
  (let [code (str/join "\n" (clojure-blocks text))
        aliases (into {} (for [[_ n a] (re-seq #"\[(cortex[\w.-]*)\s+:as\s+([\w.-]+)" code)]
                           [a n]))]
    (distinct
     (for [[_ q n] (re-seq #"(?<![\w.-])([\w.-]+)/([\w!?*<>=+-]+)" code)
           :let [ns (cond (str/starts-with? q "cortex") q :else (aliases q))]
           :when ns]
       (symbol ns n)))))

(deftest the-front-door-calls-only-the-api
  (let [calls (for [f (documents), s (called-vars (slurp f))] [f s])]
    (is (< 10 (count calls)) "the README and guides call cortex")
    (doseq [[f s] calls
            :let [v (try (requiring-resolve s) (catch Exception _ nil))]]
      (is (some? v) (str f " calls " s ", which does not exist"))
      (when v
        (is (:api (meta v)) (str f " calls " s ", which is not marked ^:api"))))))
