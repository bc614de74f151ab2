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
    (is (= {} (:args b)))))

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
    (doseq [f (tangle/untangled "org" ["src" "test" "java" "dev"] [".clj" ".java"])]
      (is (nil? f) (str f " is not tangled from any org/ chapter")))))

(deftest every-chapter-is-in-the-index
  (let [index (slurp "org/index.org")]
    (doseq [chapter (tangle/chapters "org")
            :let [name (.getName chapter)]
            :when (not= name "index.org")]
      (is (str/includes? index (str "[[file:" name "]")) (str name " is not listed in org/index.org")))))
