;; Generated from org/literate.org by lein tangle: edit the chapter, not this file.
(ns cortex.tangle-test
  (:require [clojure.test :refer [deftest is testing]]
            [clojure.string :as str]
            [cortex.tangle :as tangle]))

(set! *warn-on-reflection* true)

(deftest header-arguments
  (is (= {:tangle "../src/a.clj" :mkdirp "yes"}
         (tangle/header-args " :tangle ../src/a.clj :mkdirp yes")))
  (is (= {} (tangle/header-args ""))))

(deftest reading-blocks
  (let [org (str "* A heading\n"
                 "#+begin_src clojure :tangle ../src/x.clj\n"
                 "  (ns x)\n"
                 "    (def y 1)\n"
                 "  ,* not a heading\n"
                 "#+end_src\n"
                 "prose\n"
                 "#+BEGIN_SRC clojure\n(comment)\n#+END_SRC\n")
        [a b :as bs] (tangle/blocks "x.org" org)]
    (is (= 2 (count bs)))
    (testing "common indentation and org's comma escapes are removed"
      (is (= "(ns x)\n  (def y 1)\n* not a heading" (:body a))))
    (is (= 2 (:line a)))
    (is (= {} (:args b))))
  (testing "org's -i switch keeps a block's indentation, and is no header argument"
    (let [[a] (tangle/blocks "x.org" (str "#+begin_src java -i :tangle ../A.java\n"
                                          "    int x;\n"
                                          "#+end_src\n"))]
      (is (= "    int x;" (:body a)))
      (is (= {:tangle "../A.java"} (:args a))))))

(deftest unterminated-block
  (let [e (try (tangle/blocks "broken.org" "text\n#+begin_src clojure\n(x)\n")
               nil
               (catch clojure.lang.ExceptionInfo e e))]
    (is (some? e))
    (is (str/includes? (ex-message e) "broken.org:2"))))

(deftest no-drift
  (testing "every file tangled from org/ matches what org/ says"
    (doseq [{:keys [file reason]} (tangle/drift "org")]
      (is (nil? reason) (str file " " reason ": run lein tangle"))))
  (testing "no source file lives outside the book"
    (doseq [f (tangle/untangled "org" ["src" "test" "java" "dev" "spark" "engine"] [".clj" ".java"])]
      (is (nil? f) (str f " is not tangled from any org/ chapter")))))

(deftest generated-files-name-their-chapter
  (is (= ";; Generated from org/world.org by lein tangle: edit the chapter, not this file."
         (tangle/header "org/world.org" "src/cortex/world.clj")))
  (is (str/starts-with? (tangle/header "org/render.org" "java/cortex/SurfacelessContext.java")
                        "// Generated from org/render.org"))
  (testing "a script's #! line stays first"
    (is (= ["#!/bin/sh" "# Generated from org/x.org by lein tangle: edit the chapter, not this file."
            "echo hi"]
           (str/split-lines (#'tangle/with-header "org/x.org" "scripts/x.sh" "#!/bin/sh\necho hi\n")))))
  (testing "every generated file starts by naming the chapter it comes from"
    (let [owners (into {} (for [^java.io.File chapter (tangle/chapters "org")
                                block (tangle/blocks (str chapter) (slurp chapter))
                                :let [^String t (get-in block [:args :tangle])]
                                :when (and t (not= "no" t))]
                            [(.getCanonicalFile (java.io.File. (.getParentFile ^java.io.File chapter)
                                                               ^String t))
                             (.getName chapter)]))]
      (doseq [root ["src" "test" "dev" "java" "spark" "engine"]
              ^java.io.File f (file-seq (java.io.File. ^String root))
              :when (and (.isFile f) (re-find #"\.(clj|java)$" (.getName f)))
              :let [chapter (owners (.getCanonicalFile f))
                    first-line (first (str/split-lines (slurp f)))]]
        (is (and chapter (str/includes? first-line (str "Generated from org/" chapter " by lein tangle")))
            (str f " starts with " (pr-str first-line)))))))

(deftest every-chapter-declares-its-namespace
  (doseq [^java.io.File chapter (tangle/chapters "org")
          :let [text (slurp chapter)
                declared (second (re-find #"(?m)^#\+PROPERTY: header-args:clojure :ns (\S+)\s*$" text))
                defined (set (for [b (tangle/blocks (str chapter) text)
                                   :when (= "clojure" (:language b))
                                   :let [n (second (re-find #"^\(ns\s+([^\s)]+)" (:body b)))]
                                   :when n]
                               n))]]
    (is declared (str (.getName chapter) " lacks a line #+PROPERTY: header-args:clojure :ns NAMESPACE"
                      " naming the namespace its code is evaluated in"))
    (when declared
      (is (contains? defined declared)
          (str (.getName chapter) " declares :ns " declared ", which none of its blocks defines")))))

(deftest every-chapter-is-in-the-index
  (let [index (slurp "org/index.org")]
    (doseq [chapter (tangle/chapters "org")
            :let [name (.getName chapter)]
            :when (not= name "index.org")]
      (is (str/includes? index (str "[[file:" name "]")) (str name " is not listed in org/index.org")))))

(deftest no-block-is-over-80-lines
  (doseq [chapter (tangle/chapters "org")
          {:keys [line body]} (tangle/blocks (str chapter) (slurp chapter))
          :let [n (count (str/split-lines body))]]
    (is (<= n 80) (str (.getName ^java.io.File chapter) ":" line ": a block of " n
                       " lines; split it at a blank line between forms, with prose between"))))
