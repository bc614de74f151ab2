;; Generated from org/rollout.org by lein tangle: edit the chapter, not this file.
(ns cortex.spark-test
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.rollout :as r]
            [cortex.spark :as spark])
  (:import (java.nio.file Files)
           (java.nio.file.attribute FileAttribute)
           (org.apache.spark.sql Dataset Row SparkSession)))

(set! *warn-on-reflection* true)

(deftest spark-gives-what-rollouts-gives
  (let [dir (str (Files/createTempDirectory "cortex-spark" (into-array FileAttribute [])))
        broken (str (io/file dir "broken.blend"))
        _ (spit broken "not a Blender file")
        worm {:creature "Models/test-creature/worm.blend" :controller 'cortex.rollout/crawl-gait
              :seconds 2 :start {:shift 0.3 :turn 0.2}}
        specs [(assoc worm :seed 1) (assoc worm :seed 2 :id "second")
               (assoc worm :creature broken)
               {:creature "Models/test-creature/hand.blend" :controller 'cortex.rollout/sine-gait
                :seconds 1}
               (assoc worm :seed 3 :params {:frequency 2.0} :trajectory 30)]
        out (str dir "/out")
        ^SparkSession s (spark/session "local[2]" {"spark.ui.enabled" "false"})]
    (try
      (.setLogLevel (.sparkContext s) "WARN")
      (let [results (spark/run specs {:spark s :out out})]
        (is (= "local[2]" (.master (.sparkContext s))))
        (is (= (r/rollouts specs) results) "the same results, bit for bit, in order")
        (is (= [false false true false false] (mapv #(contains? % :error) results)))
        (testing "the Parquet rows"
          (let [rows (.collectAsList ^Dataset (.parquet (.read s) ^"[Ljava.lang.String;"
                                                        (into-array String [(str out "/parquet")])))
                by-index (into {} (for [^Row row rows] [(.getLong row 0) row]))]
            (is (= 5 (count rows)))
            (is (= (map :distance results)
                   (for [i (range 5) :let [^Row row (by-index i)]]
                     (when-not (.isNullAt row 7) (.getDouble row 7)))))
            (is (= "\"second\"" (.getString ^Row (by-index 1) 1)))
            (is (str/includes? (.getString ^Row (by-index 2) 16) "broken.blend"))))
        (testing "the CSV"
          (let [csv (first (filter #(str/ends-with? (.getName ^java.io.File %) ".csv")
                                   (.listFiles (io/file out "csv"))))
                lines (str/split-lines (slurp csv))]
            (is (= (str/join "," (map first r/columns)) (first lines))))))
      (testing "a bad spec fails before Spark runs anything"
        (is (thrown-with-msg? clojure.lang.ExceptionInfo #"^spec 1, :seconds"
                              (spark/run [{:creature "Models/test-creature/worm.blend" :seconds 1}
                                          {:creature "Models/test-creature/worm.blend" :seconds -1}]
                                         {:spark s}))))
      (finally (.stop s)))))
