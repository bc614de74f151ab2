;; Generated from org/util.org by lein tangle: edit the chapter, not this file.
(ns cortex.util-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.util :as util])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math FastMath Quaternion Vector3f)
           (com.jme3.scene Geometry Node)))

(set! *warn-on-reflection* true)

(deftest walking-the-scene-graph
  (let [a (util/box 1 1 1 :name "a" :physical? false)
        b (util/sphere 1 :name "b" :physical? false)
        inner (util/nodify "inner" [b])
        root (util/nodify "root" [a inner])]
    (is (= ["root" "a" "inner" "b"] (map #(.getName %) (util/node-seq root))))
    (is (= "" (.getName (util/nodify []))))
    (is (= 2 (count (filter #(instance? Geometry %) (util/node-seq root)))))))

(deftest shapes
  (let [b (util/box 1 2 3 :mass 4 :position (Vector3f. 1 2 3) :name "brick")]
    (is (= "brick" (.getName b)))
    (is (= (Vector3f. 1 2 3) (.getLocalTranslation b)))
    (is (= 4.0 (double (.getMass ^RigidBodyControl (.getControl b RigidBodyControl)))))
    (is (nil? (.getControl (util/box 1 1 1 :physical? false) RigidBodyControl)))))

(defn- near? [^Vector3f a ^Vector3f b] (< (.distance a b) 1e-6))

(deftest blender-and-jme-axes
  (testing "Blender's up (Z) is jME's up (Y); Blender's forward (Y) is jME's -Z"
    (is (near? (Vector3f. 0 1 0) (util/blender-to-jme (Vector3f. 0 0 1))))
    (is (near? (Vector3f. 0 0 -1) (util/blender-to-jme (Vector3f. 0 1 0))))
    (is (near? (Vector3f. 1 0 0) (util/blender-to-jme (Vector3f. 1 0 0)))))
  (testing "the two conversions undo each other"
    (doseq [v [(Vector3f. 1 2 3) (Vector3f. -4.5 0.25 9)]]
      (is (near? v (util/jme-to-blender (util/blender-to-jme v))))
      (is (near? v (util/blender-to-jme (util/jme-to-blender v)))))))

(deftest local-coordinates
  (let [n (doto (Node. "n")
            (.setLocalTranslation 1 0 0)
            (.setLocalRotation (doto (Quaternion.) (.fromAngleAxis FastMath/HALF_PI Vector3f/UNIT_Y)))
            (.updateGeometricState))
        p (util/world-to-local n (Vector3f. 1 0 -1))]
    (is (near? p (Vector3f. 1 0 0)))))

(deftest small-things
  (is (= {:a 2 :b 3} (util/map-vals inc {:a 1 :b 2})))
  (is (= 2.0 (util/dilation 2.0 1.0)))
  (is (= 0.0 (util/dilation 1.0 0)))
  (testing "println-repl writes to the REPL's writer, not to the caller's *out*"
    (let [repl (java.io.StringWriter.)
          caller (java.io.StringWriter.)]
      (with-redefs-fn {#'util/repl-out repl}
        #(binding [*out* caller] (util/println-repl "hi" 1)))
      (is (= "hi 1\n" (str repl)))
      (is (= "" (str caller))))))
