;; Generated from org/bench.org by lein tangle: edit the chapter, not this file.
(ns cortex.bench-test
  (:require [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.bench :as bench]
            [cortex.bench.creatures :as creatures]
            [cortex.blender-bench :as blender-bench]
            [cortex.body :as body])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.scene Geometry)))

(set! *warn-on-reflection* true)

(defn- boxes-apart?
  "Whether two segment descriptions' boxes are at least `d` apart along
  some axis."
  [a b d]
  (some (fn [i] (>= (- (Math/abs (double (- ((:center a) i) ((:center b) i))))
                       ((:half a) i) ((:half b) i))
                    (- d 1e-9)))
        (range 3)))

(deftest generated-descriptions
  (doseq [make [creatures/chain creatures/tree]
          n [1 2 10 23]
          :let [{:keys [segments joints] :as d} (make n)
                names (set (map :name segments))]]
    (testing (str (:name d))
      (is (= n (count segments) (count names)))
      (is (= (dec n) (count joints)))
      (testing "every joint joins two existing segments, every segment but the first is joined to its parent once"
        (is (every? #(every? names (:between %)) joints))
        (is (= (disj names "seg-0") (set (map (comp second :between) joints)))))
      (testing "no two segments touch: every pair is at least the gap apart"
        (is (every? true? (for [a segments b segments :when (neg? (compare (:name a) (:name b)))]
                            (boolean (boxes-apart? a b creatures/gap)))))))))

(deftest the-tree-branches-and-mixes-joints
  (let [{:keys [joints]} (creatures/tree 100)
        parents (frequencies (map (comp first :between) joints))]
    (is (= 24 (count (filter #(= 2 %) (vals parents))))
        "25 spine segments; all but the last branch into the next one and a rib")
    (is (= #{:point :hinge :cone} (set (map :kind joints))))))

(defn- joined-pairs
  "The pairs of segment names the Bullet joints of a built creature join."
  [creature]
  (let [controls (for [^Geometry g (body/segments creature)]
                   [(.getControl g RigidBodyControl) (.getName g)])
        name-of (into {} controls)]
    (set (for [[^RigidBodyControl c _] controls
               j (cortex.engine/joints c)]
           #{(name-of (.getBodyA j)) (name-of (.getBodyB j))}))))

(deftest body!-joins-what-the-generator-placed
  (doseq [d [(creatures/chain 12) (creatures/tree 13)]]
    (let [c (doto (creatures/creature d 2) (body/body!))]
      (is (= (count (:segments d)) (count (body/segments c))))
      (is (= (set (map (comp set :between) (:joints d))) (joined-pairs c)) (:name d)))))

(deftest build-splits-measure-a-whole-body
  (let [c (creatures/creature (creatures/chain 6))
        s (bench/build-splits! c)]
    (is (= 5 (:joints s)))
    (is (every? #(and (number? %) (>= % 0)) (map s [:physical :targets :connect])))
    (is (= 5 (count (joined-pairs c))))))

(deftest statistics
  (is (= 2 (bench/median [3 1 2])))
  (is (= 2.5 (bench/median [4 1 2 3])))
  (is (nil? (bench/median [])))
  (is (< (Math/abs (- 2.0 (bench/fit-exponent (for [n [10 100 1000]] [n (* 3 n n)])))) 1e-9))
  (is (< 1.0 (bench/nlogn-exponent [10 100 300 1000]) 1.5))
  (is (nil? (bench/fit-exponent [[10 1.0]]))))

(deftest rollouts-are-measured
  (let [[worm hand spark] (bench/run-rollouts! {:worm 2 :hand 1 :runs 1})]
    (is (= ["worm" "hand"] (map :creature [worm hand])))
    (is (every? :same? [worm hand]) "1 and 2 threads give the same results")
    (is (every? #(pos? (:rate-1 %)) [worm hand]))
    (is (< 0.0 (:mb-per-world worm) 50.0))
    (is (or (:skipped spark) (:same? spark)))))

(deftest output
  (is (= "a,\"b,c\",\"say \"\"hi\"\"\"\n" (bench/csv [["a" "b,c" "say \"hi\""]])))
  (let [t (bench/table [["name" :n] ["x" :x]] [{:n "a" :x 1} {:n "b" :skipped "why"}])]
    (is (str/includes? t "(why)"))
    (is (= 4 (count (str/split-lines t))))))

(defn table-starts
  "Where the tables of the markdown `lines` begin, counting from 0: each
  fenced block whose info string is empty or text, and the first line
  of each run of lines starting with |."
  [lines]
  (loop [i 0 fenced? false piped? false out []]
    (if (= i (count lines))
      out
      (let [line (nth lines i)
            [fence info] (re-matches #"\s*```\s*(\S*).*" line)]
        (cond
          fence (if fenced?
                  (recur (inc i) false false out)
                  (recur (inc i) true false (if (#{"" "text"} info) (conj out i) out)))
          fenced? (recur (inc i) true false out)
          (str/starts-with? line "|") (recur (inc i) false true (if piped? out (conj out i)))
          :else (recur (inc i) false false out))))))

(defn unlabelled-tables
  "The tables of the markdown `text` with no line Command: `...` in the
  `n` lines before them, or no Engine: or Measured: YYYY-MM-DD there:
  [line first-line] of each, counting lines from 1."
  [text n]
  (let [lines (vec (str/split-lines text))]
    (vec (for [i (table-starts lines)
               :let [before (str/join "\n" (subvec lines (max 0 (- i n)) i))]
               :when (not (and (re-find #"(?m)^Command: `[^`]+`" before)
                               (re-find #"Engine: \S" before)
                               (re-find #"Measured: \d{4}-\d{2}-\d{2}" before)))]
           [(inc i) (nth lines i)]))))

(deftest unlabelled-tables-are-found
  (let [label "Command: `bin/lein bench`; Engine: jBullet; Measured: 2026-11-26\n"]
    (is (= [[2 "```"]] (unlabelled-tables "text\n```\n1 2\n```\n" 4)))
    (is (= [[1 "| a | b |"]] (unlabelled-tables "| a | b |\n| 1 | 2 |\n" 4)))
    (is (= [] (unlabelled-tables (str label "\n```\n1 2\n```\n") 4)))
    (is (= [] (unlabelled-tables "```sh\nbin/lein bench\n```\n" 4)) "a command is not a table")
    (is (= [[9 "```"]] (unlabelled-tables (str label "\n```\n1\n```\n\nmore\n\n```\n2\n```\n") 4))
        "each table needs its own label")
    (is (= [[2 "```"]] (unlabelled-tables "Command: `x`; Engine: jBullet\n```\n1\n```\n" 4))
        "a table without its date")))

(deftest every-table-of-figures-names-its-command
  (let [text (slurp "doc/performance.md")]
    (is (seq (table-starts (str/split-lines text))))
    (is (= [] (unlabelled-tables text 4))
        (str "each table of doc/performance.md needs, in the four lines before it, "
             "Command: `the command that prints it`, Engine: and Measured: YYYY-MM-DD"))))

(defn- source-files
  "The source files (Clojure, Java, EDN) under the folders `roots`."
  [roots]
  (for [root roots
        ^java.io.File f (file-seq (java.io.File. ^String root))
        :when (and (.isFile f) (re-find #"\.(clj|cljc|java|edn)$" (.getName f)))]
    f))

(deftest nothing-requires-the-notebook
  (let [folder (str "notebook" "/")]
    (is (= [] (vec (for [^java.io.File f (source-files ["src" "test" "dev" "java" "engine" "spark"])
                         :when (str/includes? (slurp f) folder)]
                     (str f))))
        "no source file names the notebook")
    (is (= [] (vec (for [^java.io.File f (file-seq (java.io.File. "notebook"))
                         :when (and (.isFile f) (str/includes? (slurp f) ":tangle"))]
                     (str f))))
        "no notebook file has a block to tangle")))
