;; Generated from org/front-door.org by lein tangle: edit the chapter, not this file.
(ns cortex.examples-test
  "Every Clojure example in README.md and doc/*.md, run, and the results
  the pages show checked. The rules are in org/front-door.org."
  (:require [clojure.edn :as edn]
            [clojure.java.io :as io]
            [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [clojure.walk :as walk])
  (:import (clojure.lang LineNumberingPushbackReader)
           (java.io File PushbackReader StringReader)))

(set! *warn-on-reflection* true)

(defn pages
  "The pages whose examples are run: README.md, then doc/*.md by name,
  as paths from the project folder."
  []
  (cons "README.md"
        (->> (.listFiles (io/file "doc"))
             (map #(.getName ^File %))
             (filter #(str/ends-with? % ".md"))
             sort
             (map #(str "doc/" %)))))

(defn- strip-indent
  "`line` without up to `n` leading spaces."
  [line n]
  (subs line (min n (count (re-find #"^ *" line)))))

(defn fences
  "The fenced code blocks of Markdown `text`, in order, as maps of :info
  (the info string, such as \"clojure\" or \"clojure untested — opens a
  window\"), :line (the opening fence's line, counting from 1), :start
  (the line of the block's first line) and :code (its lines, less the
  fence's indentation)."
  [text]
  (loop [lines (map-indexed (fn [i l] [(inc i) l]) (str/split-lines text))
         open nil
         out []]
    (if-let [[[n line] & more] (seq lines)]
      (if open
        (if (re-matches (re-pattern (str " *" (:fence open) "`*\\s*")) line)
          (recur more nil (conj out (-> open
                                        (assoc :code (str/join "\n" (:lines open)))
                                        (dissoc :lines :fence :indent))))
          (recur more (update open :lines conj (strip-indent line (:indent open))) out))
        (if-let [[_ indent fence info] (re-matches #"( *)(```+)\s*([^`]*?)\s*" line)]
          (recur more {:info info :line n :start (inc n) :fence fence
                       :indent (count indent) :lines []}
                 out)
          (recur more nil out)))
      (if open
        (throw (ex-info (str "the fence at line " (:line open) " is never closed")
                        {:line (:line open)}))
        out))))

(defn kind
  "What is done with a fence of info string `info`: :run (a Clojure
  example), :untested (declared not to be run), :other (sh, text, any
  language but Clojure), or :unknown (clj, or clojure followed by
  anything but untested: a mistake, which fails the test)."
  [info]
  (let [[lang word] (str/split (str/trim info) #"\s+" 3)]
    (cond
      (#{"clj" "cljc"} lang) :unknown
      (not= "clojure" lang) :other
      (nil? word) :run
      (= "untested" word) :untested
      :else :unknown)))

(defrecord Decimal [value places text])

(defn- decimal
  "The number written as `text`, with the decimal places it was written
  to: 0.28 has 2, 1e-5 has 5, 1.5e3 has -2."
  [^String text]
  (let [[_ fraction exponent] (re-matches #"[+-]?\d+(?:\.(\d*))?(?:[eE]([+-]?\d+))?" text)]
    (->Decimal (Double/parseDouble text)
               (- (count fraction) (if exponent (Long/parseLong exponent) 0))
               text)))

(def ^:private decimal-token
  #"[+-]?\d+\.\d*(?:[eE][+-]?\d+)?|[+-]?\d+[eE][+-]?\d+")

(defn- tag-decimals
  "EDN `text` with every floating-point number outside strings written
  as #example/decimal \"TEXT\"."
  [text]
  (str/replace text #"\"(?:\\.|[^\"\\])*\"|[^\s,\[\]{}()\"]+"
               (fn [token]
                 (if (re-matches decimal-token token)
                   (str "#example/decimal \"" token "\"")
                   token))))

(defn read-expected
  "The value the EDN `text` after an arrow shows, its floating-point
  numbers Decimals. It must be one complete form, with nothing after it
  but comments. Never evaluated."
  [text]
  (binding [*read-eval* false]
    (let [r (PushbackReader. (StringReader. (tag-decimals text)))
          opts {:eof ::eof :readers {'example/decimal decimal}}
          v (edn/read opts r)]
      (when (= ::eof v)
        (throw (ex-info "no value after the arrow" {:text text})))
      (when-not (= ::eof (edn/read opts r))
        (throw (ex-info (str "more than one value after the arrow: " text) {:text text})))
      v)))

(def relative-tolerance
  "How far from a number after ~> a value may be, relative to it."
  0.05)

(defn- plain
  "`x` with every Decimal in it back to its double."
  [x]
  (walk/postwalk #(if (instance? Decimal %) (:value %) %) x))

(defn- number-matches?
  [mode expected actual]
  (and (number? actual)
       (let [a (double actual)
             decimal? (instance? Decimal expected)
             e (double (if decimal? (:value expected) expected))]
         (case mode
           :approx (<= (Math/abs (- a e)) (* (double relative-tolerance) (Math/abs e)))
           :exact (if decimal?
                    (<= (Math/abs (- a e))
                        (* 0.5 (Math/pow 10.0 (- (long (:places expected)))) (+ 1.0 1e-9)))
                    (== expected actual))))))

(defn matches?
  "Whether `actual` is what `expected` (from `read-expected`) shows, by
  `mode`: :exact (;; =>) or :approx (;; ~>). Numbers by
  `number-matches?`; maps key by key, with the same keys; vectors and
  lists element by element (Java's maps and lists too); anything else
  by =."
  [mode expected actual]
  (cond
    (or (instance? Decimal expected) (number? expected))
    (number-matches? mode expected actual)
    (map? expected)
    (and (instance? java.util.Map actual)
         (= (set (keys (plain expected))) (set (keys actual)))
         (every? (fn [[k v]] (matches? mode v (get actual (plain k)))) expected))
    (sequential? expected)
    (and (or (sequential? actual) (instance? java.util.List actual))
         (= (count expected) (count actual))
         (every? true? (map #(matches? mode %1 %2) expected actual)))
    :else (= (plain expected) actual)))

(def ^:private arrow #"^;+\s*(=>|~>)\s?(.*)$")

(defn- skip-space!
  "Read past whitespace, commas and comments in `r`; return the
  comments as [line text], text from its first ;."
  [^LineNumberingPushbackReader r]
  (loop [comments []]
    (let [c (.read r)]
      (cond
        (= -1 c) comments
        (or (Character/isWhitespace c) (= c (int \,))) (recur comments)
        (= c (int \;)) (let [line (.getLineNumber r)
                             text (str ";" (.readLine r))]
                         (recur (conj comments [line text])))
        :else (do (.unread r c) comments)))))

(defn- expectation
  "The first arrow among `comments` (see `skip-space!`), the comments
  after a form, or nil: {:mode :line :lines :text}, the text being what
  follows the arrow, continued on the comment lines right after it
  while the value is incomplete; with :error when it cannot be read."
  [comments]
  (when-let [i (first (keep-indexed (fn [i [_ t]] (when (re-find arrow t) i)) comments))]
    (let [[line t] (nth comments i)
          [_ sign first-text] (re-find arrow t)]
      (loop [text first-text
             lines [line]
             more (drop (inc i) comments)]
        (let [[next-line next-text] (first more)
              result (try (read-expected text) nil
                          (catch Exception e
                            (if (and (str/includes? (str (ex-message e)) "EOF")
                                     next-line
                                     (= (inc (peek lines)) next-line)
                                     (not (re-find arrow next-text)))
                              ::incomplete
                              e)))]
          (if (= ::incomplete result)
            (recur (str text "\n" (str/replace next-text #"^;+\s?" ""))
                   (conj lines next-line)
                   (rest more))
            (cond-> {:mode (if (= "=>" sign) :exact :approx) :line line :lines lines :text text}
              result (assoc :error result))))))))

(defn- abbreviated
  "`x` printed for a report, at most `n` characters."
  [x n]
  (let [s (binding [*print-length* 12 *print-level* 5] (pr-str x))]
    (if (> (count s) n) (str (subs s 0 n) " ...") s)))

(defn run-block
  "Evaluate the Clojure of `block` (see `fences`) form by form in the
  namespace `the-ns`, checking each value an arrow after a form shows.
  Returns a result for every arrow and every failure: maps of :line (the
  form's line on its page), :block (the block's fence line), :form and
  :status, one of :ok, :mismatch (with :mode, :expected and :actual),
  :error (the form threw; nothing after it is run) and :bad-arrow (an
  arrow that cannot be read or is never checked)."
  [block the-ns]
  (let [padded (str (str/join (repeat (dec (:start block)) "\n")) (:code block))
        r (LineNumberingPushbackReader. (StringReader. padded))
        at (fn [m] (assoc m :block (:line block)))
        arrow-lines (set (for [[i l] (map-indexed vector (str/split-lines (:code block)))
                               :when (re-find #"^\s*;+\s*(=>|~>)" l)]
                           (+ (:start block) i)))
        unchecked (fn [used]
                    (for [l (sort (remove used arrow-lines))]
                      (at {:status :bad-arrow :line l
                           :message (str "an arrow that is never checked: before the first form,"
                                         " inside a form, or a second after one form")})))]
    (binding [*ns* the-ns
              *warn-on-reflection* false]
      (skip-space! r)
      (loop [results [] used #{}]
        (let [start (.getLineNumber r)
              form (read {:eof ::eof :read-cond :allow} r)]
          (if (= ::eof form)
            (into results (unchecked used))
            (let [outcome (try {:value (eval form)}
                               (catch Throwable t {:thrown t}))
                  {:keys [mode text error lines] :as exp} (expectation (skip-space! r))
                  base (at {:line start :form (abbreviated form 300)})
                  used (into used lines)]
              (cond
                (:thrown outcome)
                (let [^Throwable t (:thrown outcome)]
                  (conj results (assoc base :status :error :thrown t
                                       :message (str (.getName (class t)) ": " (ex-message t)))))
                (nil? exp) (recur results used)
                error (recur (conj results (assoc base :status :bad-arrow :expected text
                                                  :message (ex-message error)))
                             used)
                :else
                (let [ok? (matches? mode (read-expected text) (:value outcome))]
                  (recur (conj results (assoc base :status (if ok? :ok :mismatch)
                                              :mode mode :expected text
                                              :actual (abbreviated (:value outcome) 600)))
                         used))))))))))

(defn- page-ns
  "A fresh namespace for the examples of `page`, referring what the
  REPL's user namespace refers: clojure.core, clojure.repl and
  clojure.pprint."
  [page]
  (let [n (symbol (str "cortex.examples." (str/replace page #"[^A-Za-z0-9]+" "-")))]
    (when (find-ns n) (remove-ns n))
    (binding [*ns* (create-ns n)]
      (refer-clojure)
      (require 'clojure.repl 'clojure.pprint)
      (refer 'clojure.repl)
      (refer 'clojure.pprint)
      *ns*)))

(defn run-page
  "Run every Clojure example of Markdown `text`, the page `page`, in
  order, in one fresh namespace: the results of `run-block`, each with
  :page. A form that throws ends the page. A fence of unknown kind (see
  `kind`) is a result of status :bad-fence."
  [page text]
  (let [the-ns (page-ns page)]
    (try
      (loop [[block & more] (fences text) results []]
        (if-not block
          results
          (case (kind (:info block))
            :unknown (recur more (conj results {:page page :block (:line block) :line (:line block)
                                                :status :bad-fence
                                                :message (str "a fence with info string "
                                                              (pr-str (:info block))
                                                              ": write clojure, or clojure untested")}))
            (:other :untested) (recur more results)
            :run (let [rs (map #(assoc % :page page) (run-block block the-ns))
                       results (into results rs)]
                   (if (some #(= :error (:status %)) rs)
                     results
                     (recur more results))))))
      (finally (remove-ns (ns-name the-ns))))))

(defn describe
  "A result that failed, as a line or two to act on."
  [{:keys [page line block form status message mode expected actual]}]
  (str page ":" line (when (not= line block) (str " (the block at line " block ")"))
       (when form (str ": " form))
       (if (= :mismatch status)
         (str "\n  shows " (if (= :approx mode) "~> " "=> ") expected
              "\n  gives " actual)
         (str "\n  " (name status) ": " message))))

(def untested
  "Why each untested example is not run: page to reasons, in order."
  {"doc/repl.md" ["show! opens a window, and (reset) writes the source files again from org/"]})

(defn- delete-tree! [^File f]
  (when (.isDirectory f)
    (run! delete-tree! (.listFiles f)))
  (.delete f))

(defn with-own-tmpdir
  "Call `f` with the system property java.io.tmpdir set to a fresh
  folder of its own, and afterwards delete that folder and put the
  property back."
  [f]
  (let [before (System/getProperty "java.io.tmpdir")
        dir (.toFile (java.nio.file.Files/createTempDirectory
                      "cortex-examples" (make-array java.nio.file.attribute.FileAttribute 0)))]
    (try
      (System/setProperty "java.io.tmpdir" (str dir))
      (f)
      (finally
        (System/setProperty "java.io.tmpdir" before)
        (delete-tree! dir)))))

(deftest every-example-runs
  (with-own-tmpdir
    (fn []
      (doseq [page (pages)]
        (testing page
          (doseq [result (run-page page (slurp page))]
            (is (= :ok (:status result)) (describe result))))))))

(deftest every-untested-example-is-declared
  (testing "every page declared exists"
    (doseq [page (keys untested)]
      (is (.isFile (io/file page)) (str page " is declared in org/front-door.org but missing"))))
  (doseq [page (pages)
          :let [blocks (filter #(= :untested (kind (:info %))) (fences (slurp page)))
                reasons (get untested page [])]]
    (is (= (count reasons) (count blocks))
        (str page " has " (count blocks) " untested examples; org/front-door.org declares "
             (count reasons)))
    (doseq [[reason block] (map vector reasons blocks)]
      (testing (str page ":" (:line block) " is not run: " reason)
        (is (some? (binding [*read-eval* false]
                     (read-string {:read-cond :allow} (str "[" (:code block) "\n]"))))
            "it is still well-formed Clojure")))))

(def ^:private test-page
  (str/join "\n" ["# A page"
                  ""
                  "```clojure"
                  "(def x 1.2345)"
                  "x"
                  ";; => 1.23"
                  "x ;; => 1.2"
                  "(+ x 1)"
                  ";; ~> 2.3"
                  "{:a [x 2] :b \"s\"}"
                  ";; => {:a [1.235"
                  ";;         2]"
                  ";;     :b \"s\"}"
                  "(let [y 2]"
                  "  ;; => 3"
                  "  y)"
                  ";; => 3"
                  "```"
                  ""
                  "```sh"
                  "rm -rf /"
                  "```"
                  ""
                  "   ```clojure untested — opens a window"
                  "   (boom)"
                  "   ```"
                  ""
                  "```clj"
                  "(boom)"
                  "```"
                  ""
                  "```clojure"
                  "#{\"floor\"}"
                  ";; => #{\"floor\"}"
                  "(/ 1 0)"
                  ";; => 1"
                  "(never)"
                  "```"]))

(deftest the-harness-checks-what-it-should
  (is (= [:run :other :untested :unknown :run] (map (comp kind :info) (fences test-page))))
  (is (= "(boom)" (:code (nth (fences test-page) 2))) "a fence's indentation is taken off")
  (let [results (run-page "test.md" test-page)]
    (is (= [[5 :ok] [7 :ok] [8 :ok] [10 :ok] [14 :mismatch] [15 :bad-arrow] [28 :bad-fence]
            [33 :ok] [35 :error]]
           (map (juxt :line :status) results)))
    (testing "a failure names the page, the line, the block and the form"
      (is (= "test.md:14 (the block at line 3): (let [y 2] y)\n  shows => 3\n  gives 2"
             (describe (nth results 4)))))
    (is (nil? (find-ns 'cortex.examples.test-md)) "the page's namespace is gone")))

(deftest numbers-are-checked-as-written
  (doseq [[mode text actual ok?] [[:exact "0.28" 0.276 true]
                                  [:exact "0.28" 0.2849 true]
                                  [:exact "0.28" 0.2851 false]
                                  [:exact "2.0" 1.96 true]
                                  [:exact "0.0" -0.04 true]
                                  [:exact "1e-5" 1.4e-5 true]
                                  [:exact "1e-5" 1.6e-5 false]
                                  [:exact "3" 3.0 true]
                                  [:exact "3" 3.01 false]
                                  [:approx "100" 104.9 true]
                                  [:approx "100" 105.1 false]
                                  [:approx "0.49" 0.47 true]
                                  [:approx "0.0" 1e-9 false]
                                  [:exact "[0.5 {:a 1.25}]" (list 0.54 {:a 1.2549}) true]
                                  [:exact "[0.5 {:a 1.25}]" [0.5 {:a 1.2551}] false]
                                  [:exact "{:a 1}" {:a 1 :b 2} false]
                                  [:exact "[\"a\" 0.5]" (java.util.ArrayList. ["a" 0.54]) true]
                                  [:exact "{1 \"worm-1\"}" {1 "worm-1"} true]
                                  [:exact "#{\"floor\"}" #{"floor"} true]
                                  [:exact "\"0.5\"" "0.5" true]
                                  [:exact "\"0.5\"" 0.5 false]]]
    (is (= ok? (matches? mode (read-expected text) actual))
        (str (if (= :exact mode) "=> " "~> ") text " against " (pr-str actual))))
  (testing "an arrow shows one value, read and never evaluated"
    (is (thrown? Exception (read-expected "about 3")))
    (is (thrown? Exception (read-expected "#=(+ 1 2)")))))
