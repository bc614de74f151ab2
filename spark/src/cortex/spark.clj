;; Generated from org/rollout.org by lein tangle: edit the chapter, not this file.
(ns cortex.spark
  "Rollouts (see cortex.rollout) as an Apache Spark job: local[*] by
  default, any master URL as given, results written as Parquet and CSV
  and returned in order, each equal to what cortex.rollout/rollouts
  gives. Needs the spark profile: lein with-profile +spark ...

  Entry points: `run`, `session`, `schema`, `-main` (for lein run and
  spark-submit)."
  (:require [clojure.edn :as edn]
            [clojure.java.io :as io]
            [clojure.string :as str]
            [cortex.rollout :as r])
  (:import (cortex.spark RolloutFunction RowFunction)
           (org.apache.spark.api.java JavaRDD JavaSparkContext)
           (org.apache.spark.sql Dataset SaveMode SparkSession SparkSession$Builder)
           (org.apache.spark.sql.types DataType DataTypes StructType)
           (org.apache.spark.storage StorageLevel)))

(set! *warn-on-reflection* true)

(def ^:private spark-types
  {:long DataTypes/LongType :double DataTypes/DoubleType
   :boolean DataTypes/BooleanType :string DataTypes/StringType})

(defn schema
  "The Spark schema of a result's row: cortex.rollout/columns, every
  column nullable."
  ^StructType []
  (DataTypes/createStructType
   ^java.util.List (vec (for [[n t] r/columns]
                          (DataTypes/createStructField ^String n ^DataType (spark-types t) true)))))

(defn run-line
  "What an executor does with one spec: EDN [index checked-spec] to EDN
  [index result] (an error is a result, see cortex.rollout/try-rollout)."
  [line]
  (let [[i s] (edn/read-string line)]
    (r/edn [i (r/try-rollout s)])))

(defn row-values
  "EDN [index result] to the values of its row, an Object array."
  [line]
  (let [[i res] (edn/read-string line)]
    (object-array (r/flat-row i res))))

(defn session
  "A SparkSession for `master` (a master URL such as \"local[2]\" or
  \"spark://host:7077\"); when nil, the one spark-submit gave (the
  spark.master property), else local[*]. `conf` is more Spark
  configuration, {key value}. A local master binds to 127.0.0.1."
  (^SparkSession [master] (session master {}))
  (^SparkSession [master conf]
   (let [^SparkSession$Builder b (.appName (SparkSession/builder) "cortex rollouts")
         master (or master (when-not (System/getProperty "spark.master") "local[*]"))
         ;; a local job talks to itself only: over the loopback interface
         local (when (and master (str/starts-with? master "local"))
                 {"spark.driver.bindAddress" "127.0.0.1" "spark.driver.host" "127.0.0.1"})]
     (when master (.master b ^String master))
     (doseq [[k v] (merge local conf)] (.config b (str k) (str v)))
     (.getOrCreate b))))

(defn run
  "Run `specs` (see cortex.rollout) as a Spark job; their results, in
  order, as cortex.rollout/rollouts returns them. Every spec is checked
  before Spark starts. `opts`: :master (see `session`), :conf, :spark
  (a SparkSession to use instead), :out (a folder, local or any URL
  Hadoop writes to: the rows go to OUT/parquet and OUT/csv), :partitions
  (default: one per spec, at most 4 per core Spark has), :collect?
  (false: return nil, for jobs too large for the driver)."
  ([specs] (run specs {}))
  ([specs {:keys [master conf spark out partitions collect?] :or {collect? true}}]
   (let [checked (r/check-specs! specs)]
     (if (empty? checked)
       []
       (let [^SparkSession spark (or spark (session master conf))
             jsc (JavaSparkContext/fromSparkContext (.sparkContext spark))
             lines (vec (map-indexed (fn [i s] (r/edn [i s])) checked))
             slices (or partitions (min (count lines) (* 4 (.defaultParallelism jsc))))
             ^JavaRDD results (-> (.parallelize jsc ^java.util.List lines (int slices))
                                  (.map (RolloutFunction.))
                                  (.persist (StorageLevel/MEMORY_AND_DISK)))]
         (try
           (when out
             (let [^Dataset df (.createDataFrame spark (.map results (RowFunction.)) (schema))]
               (-> df .write (.mode SaveMode/Overwrite) (.parquet (str out "/parquet")))
               (-> df (.coalesce 1) .write (.mode SaveMode/Overwrite)
                   (.option "header" "true") (.option "escape" "\"")
                   (.csv (str out "/csv")))))
           (when collect?
             (->> (.collect results) (map edn/read-string) (sort-by first) (mapv second)))
           (finally (.unpersist results))))))))

(defn -main
  "SPECS.edn OUT [--master URL]: run the specs in SPECS.edn (an EDN
  vector) as a Spark job, write OUT/parquet and OUT/csv, print a line
  per rollout."
  [& args]
  (let [[specs-file out & more] args
        master (second (drop-while #(not= "--master" %) more))]
    (when-not (and specs-file out)
      (binding [*out* *err*]
        (println "usage: cortex.spark SPECS.edn OUT [--master URL]"))
      (System/exit 2))
    (let [specs (edn/read-string (slurp specs-file))
          ^SparkSession spark (session master)]
      (try
        (.setLogLevel (.sparkContext spark) "WARN")
        (let [t0 (System/nanoTime)
              results (run specs {:spark spark :out out})]
          (doseq [[i {:keys [distance energy fell? error]}] (map-indexed vector results)]
            (println (if error
                       (format "%4d  error: %s" i (:message error))
                       (format "%4d  distance %8.3f  energy %9.2f%s" i distance energy
                               (if fell? "  fell" "")))))
          (println (format "%d rollouts in %.1f s on %s; wrote %s/parquet and %s/csv"
                           (count results) (/ (- (System/nanoTime) t0) 1e9)
                           (.master (.sparkContext spark)) out out)))
        (finally (.stop spark))))))
