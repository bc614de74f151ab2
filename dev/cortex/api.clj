;; Generated from org/api.org by lein tangle: edit the chapter, not this file.
(ns cortex.api
  "The public API index, doc/api.md, written from the ^:api marks on
  the library's vars.

  Entry points: `api-vars` (the marked vars, by namespace),
  `markdown` (the index as text), `-main` (write doc/api.md)."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]))

(set! *warn-on-reflection* true)

(def path "Where the index is written." "doc/api.md")

(defn library-namespaces
  "The library's namespaces, loaded, in name order: every file under
  src/, and cortex.engine (the engine on the classpath)."
  []
  (let [root (io/file "src")
        names (cons "cortex.engine"
                    (for [^java.io.File f (file-seq root)
                          :let [p (str (.relativize (.toPath root) (.toPath f)))]
                          :when (str/ends-with? p ".clj")]
                      (-> p (str/replace #"\.clj$" "") (str/replace "/" ".") (str/replace "_" "-"))))]
    (doseq [n names] (require (symbol n)))
    (sort-by (comp str ns-name) (map (comp the-ns symbol) names))))

(defn api-vars
  "[namespace [var ...]] for each library namespace with vars marked
  ^:api, the vars in name order."
  []
  (for [n (library-namespaces)
        :let [vs (->> (vals (ns-publics n))
                      (filter #(:api (meta %)))
                      (sort-by #(str (:name (meta %)))))]
        :when (seq vs)]
    [n vs]))

(defn first-sentence
  "The first sentence of `doc` (up to a full stop that ends a word),
  on one line; or its first paragraph when it has none."
  [doc]
  (let [para (first (str/split (str/trim (str doc)) #"\n\s*\n"))
        one-line (str/replace para #"\s*\n\s*" " ")]
    (or (second (re-find #"^(.*?[a-z0-9)`'\]\"]\.)(\s|$)" one-line))
        one-line)))

(defn- calls
  "How var `v` is called: each arglist as a call, or its name for a
  value."
  [v]
  (let [{:keys [name arglists]} (meta v)]
    (if (seq arglists)
      (str/join " " (for [args arglists]
                      (str "`(" (str/join " " (cons name (map pr-str args))) ")`")))
      (str "`" name "`"))))

(defn markdown
  "The API index as Markdown."
  []
  (str "# cortex's public API\n\n"
       "What a user calls, namespace by namespace: the vars marked `^:api`, "
       "each with the first sentence of its docstring. Written by "
       "`bin/lein run -m cortex.api` from the marks in the code "
       "(see `org/api.org`); do not edit it by hand.\n"
       (str/join
        (for [[n vs] (api-vars)]
          (str "\n## " (ns-name n) "\n\n"
               (first-sentence (:doc (meta n))) "\n\n"
               (str/join (for [v vs]
                           (str "- " (calls v) ": " (first-sentence (:doc (meta v))) "\n"))))))))

(defn -main
  "Write doc/api.md."
  [& _]
  (spit path (markdown))
  (println "wrote" path (str "(" (reduce + (map (comp count second) (api-vars))) " vars)"))
  (shutdown-agents))
