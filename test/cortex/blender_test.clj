(ns cortex.blender-test
  (:require [clojure.test :refer [deftest is testing]]
            [clojure.java.io :as io]
            [cortex.blender :as blender]
            [cortex.blender.mesh :as mesh])
  (:import [com.jme3.scene Spatial Node Geometry]))

(def corpus-dir
  "The shared corpus of old .blend files, beside the project."
  (io/file "../shared/corpus/blend-legacy"))

(defn corpus-files
  "The corpus .blend files, or nil (with a message) when the folder is
  missing."
  []
  (if (.isDirectory corpus-dir)
    (sort-by #(.getName ^java.io.File %)
             (filter #(.endsWith (.getName ^java.io.File %) ".blend") (.listFiles corpus-dir)))
    (println "SKIP: no corpus at" (str corpus-dir))))

(defn node-seq
  "Every spatial under `s`, itself first."
  [^Spatial s]
  (tree-seq #(instance? Node %) #(.getChildren ^Node %) s))

(deftest corpus-files-load
  (doseq [f (corpus-files)]
    (testing (str f)
      (let [root (blender/load-blender-model (str f))]
        (is (instance? Node root))
        (is (seq (filter #(instance? Geometry %) (node-seq root))))))))

(deftest worm-loads-with-properties
  (let [worm (blender/load-blender-model "Models/test-creature/worm.blend")
        seg (.getChild ^Node worm "worm-1")
        geom (first (filter #(instance? Geometry %) (node-seq seg)))]
    (is (some? seg))
    (is (= 1.0 (blender/meta-data seg "mass")))
    (is (= 1.0 (blender/meta-data geom "mass")))
    (is (string? (blender/meta-data (.getChild ^Node worm "worm-joint") "joint")))))
