;; Generated from org/literate.org by lein tangle: edit the chapter, not this file.
(ns cortex.tangle
  "Write the source files that the org/ chapters hold, or check that
  they are already written.

  A chapter is an org file; each `#+begin_src LANG :tangle PATH` block
  belongs to the file at PATH, relative to the chapter's folder, as
  org-babel reads it. Blocks bound for one file are joined in the order
  they appear, with one blank line between them, under a first line
  that names the chapter (see `header`). Emacs is not needed."
  (:require [clojure.java.io :as io]
            [clojure.string :as str])
  (:import (java.io File)))

(set! *warn-on-reflection* true)

(defn header-args
  "Read org-babel header arguments, such as \":tangle ../src/a.clj
  :mkdirp yes\", into a map from keyword to string."
  [s]
  (loop [tokens (remove str/blank? (str/split (str/trim (or s "")) #"\s+"))
         k nil
         args {}]
    (if-let [[t & more] (seq tokens)]
      (if (str/starts-with? t ":")
        (recur more (keyword (subs t 1)) (assoc args (keyword (subs t 1)) ""))
        (recur more k (if k (update args k #(str/trim (str % " " t))) args)))
      args)))

(defn- unescape
  "Org escapes a line inside a block that would read as a heading or a
  keyword with a leading comma; take that comma away."
  [line]
  (str/replace line #"^(\s*),(\*|#\+)" "$1$2"))

(defn- dedent
  "Remove the indentation that every non-blank line shares."
  [lines]
  (let [widths (for [l lines :when (not (str/blank? l))]
                 (count (re-find #"^ *" l)))
        n (if (seq widths) (apply min widths) 0)]
    (map #(if (str/blank? %) "" (subs % n)) lines)))

(defn- switches
  "The switches before a block's header arguments, such as -i in
  \"-i :tangle ../a.java\"."
  [args]
  (set (take-while #(not (str/starts-with? % ":"))
                   (remove str/blank? (str/split (str/trim (or args "")) #"\s+")))))

(defn blocks
  "The source blocks of an org document, in order, as maps of
  :language, :args (header arguments), :line (where the block begins,
  counting from 1) and :body (its text, without the indentation its
  lines share unless the block has org's -i switch). `source` names the
  document in errors."
  [source text]
  (loop [lines (map-indexed (fn [i l] [(inc i) l]) (str/split-lines text))
         open nil
         out []]
    (if-let [[[n line] & more] (seq lines)]
      (if open
        (if (re-matches #"(?i)\s*#\+end_src\s*" line)
          (recur more nil
                 (conj out (assoc (dissoc open :keep-indentation?) :body
                                  (str/join "\n" (cond-> (:lines open)
                                                   (not (:keep-indentation? open)) dedent)))))
          (recur more (update open :lines conj (unescape line)) out))
        (if-let [[_ lang args] (re-matches #"(?i)\s*#\+begin_src\s+(\S+)(.*)" line)]
          (recur more {:language lang :args (header-args args) :line n :lines []
                       :keep-indentation? (contains? (switches args) "-i")}
                 out)
          (recur more nil out)))
      (if open
        (throw (ex-info (str source ":" (:line open)
                             ": source block has no #+end_src")
                        {:file source :line (:line open)}))
        (mapv #(dissoc % :lines) out)))))

(defn- target
  "The file a block tangles to, resolved against the chapter's folder,
  or nil when the block is not tangled."
  [chapter block]
  (let [t (get-in block [:args :tangle])]
    (cond
      (or (nil? t) (= t "no")) nil
      (or (str/blank? t) (= t "yes"))
      (throw (ex-info (str chapter ":" (:line block)
                           ": name the file to tangle to (:tangle PATH)")
                      {:file (str chapter) :line (:line block)}))
      :else (.getCanonicalFile (io/file (.getParentFile (io/file chapter)) t)))))

(def ^:private comment-starts
  "How a line comment starts, by file extension; # for any other."
  {"clj" ";;" "cljc" ";;" "cljs" ";;" "edn" ";;" "java" "//" "c" "//" "js" "//"})

(defn header
  "The first line of the file `target` generated from `chapter`: a
  comment naming the chapter (as org/NAME.org) and asking that the
  chapter be edited instead."
  [chapter target]
  (let [ext (second (re-find #"\.([^./]+)$" (str target)))
        chapter (io/file chapter)]
    (str (get comment-starts ext "#") " Generated from "
         (.getName (.getParentFile (.getAbsoluteFile chapter))) "/" (.getName chapter)
         " by lein tangle: edit the chapter, not this file.")))

(defn- with-header
  "`text`, the contents of `target`, with its header line first (after
  a #! line, if it starts with one)."
  [chapter target ^String text]
  (let [[first-line more] (str/split text #"\n" 2)]
    (if (str/starts-with? text "#!")
      (str first-line "\n" (header chapter target) "\n" more)
      (str (header chapter target) "\n" text))))

(defn chapters
  "The org chapters in folder `dir`, in name order."
  [dir]
  (->> (.listFiles (io/file dir))
       (filter #(str/ends-with? (.getName ^File %) ".org"))
       (sort-by #(.getName ^File %))))

(defn tangled
  "Map from each target file to the text the chapters in `dir` give it.
  A file claimed by two chapters is an error: one chapter owns a file."
  [dir]
  (let [parts (for [chapter (chapters dir)
                    block (blocks (str chapter) (slurp chapter))
                    :let [f (target chapter block)]
                    :when f]
                [f (str chapter) (:body block)])]
    (doseq [[f owners] (group-by first parts)
            :let [names (distinct (map second owners))]
            :when (> (count names) 1)]
      (throw (ex-info (str f " is tangled from more than one chapter: "
                           (str/join ", " names))
                      {:file (str f) :chapters names})))
    (into (sorted-map)
          (for [[f ps] (group-by first parts)]
            [f (with-header (second (first ps)) f
                 (str (str/join "\n\n" (map #(nth % 2) ps)) "\n"))]))))

(defn drift
  "The target files whose contents differ from what the chapters in
  `dir` say, as maps of :file and :reason."
  [dir]
  (for [[f text] (tangled dir)
        :let [reason (cond (not (.exists ^File f)) "missing"
                           (not= text (slurp f)) "differs from org")]
        :when reason]
    {:file (str f) :reason reason}))

(defn untangled
  "Source files under the folders `roots` with an extension in `exts`
  that no chapter in `dir` writes: code that lives outside the book."
  [dir roots exts]
  (let [known (set (keys (tangled dir)))]
    (for [root roots
          ^File f (file-seq (io/file root))
          :when (and (.isFile f)
                     (some #(str/ends-with? (.getName f) %) exts)
                     (not (known (.getCanonicalFile f))))]
      (str f))))

(defn tangle!
  "Write every target file of the chapters in `dir`; return the files
  whose contents changed."
  [dir]
  (doall
   (for [[f text] (tangled dir)
         :when (not (and (.exists ^File f) (= text (slurp f))))]
     (do (io/make-parents f)
         (spit f text)
         (str f)))))

(defn -main
  "lein tangle          write src/, test/, dev/ and java/ from org/
   lein tangle --check  exit 1 when any of them differs from org/"
  [& args]
  (if (= ["--check"] args)
    (let [d (drift "org")]
      (doseq [{:keys [file reason]} d] (println file reason))
      (System/exit (if (seq d) 1 0)))
    (doseq [f (tangle! "org")]
      (println "wrote" f))))
