;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.export.xml
  "XML documents built as data, [tag {attributes} & children], printed
  as indented text (see `xml`)."
  (:require [clojure.string :as str]))

(set! *warn-on-reflection* true)

(defn text [v]
  (cond (sequential? v) (str/join " " (map text v))
        (or (float? v) (ratio? v)) (str (double v))
        (keyword? v) (name v)
        :else (str v)))

(defn- escape [s]
  (-> (str s) (str/replace "&" "&amp;") (str/replace "<" "&lt;")
      (str/replace ">" "&gt;") (str/replace "\"" "&quot;")))

(defn- flatten-children
  "Children as given, with seqs of children spliced in."
  [children]
  (mapcat #(if (seq? %) (flatten-children %) [%]) children))

(defn xml
  "The element `node` ([tag attrs & children], nil children skipped,
  strings written as comments) as indented text."
  ([node] (xml node ""))
  ([node indent]
   (if (string? node)
     (str indent "<!-- " (str/replace node "--" "- -") " -->\n")
     (let [[tag & more] node
           [attrs children] (if (map? (first more)) [(first more) (rest more)] [{} more])
           children (remove nil? (flatten-children children))
           open (str indent "<" (name tag)
                     (str/join (for [[k v] attrs :when (some? v)]
                                 (str " " (name k) "=\"" (escape (text v)) "\""))))]
       (if (empty? children)
         (str open "/>\n")
         (str open ">\n" (str/join (map #(xml % (str indent "  ")) children))
              indent "</" (name tag) ">\n"))))))
