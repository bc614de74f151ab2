;; Generated from org/blender-scene.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender-scene-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.blender.math :as m]
            [cortex.util :as util]))

(set! *warn-on-reflection* true)

(defn- close?
  "Are two matrices (vectors of rows) equal within `tol`?"
  [a b tol]
  (every? true? (map (fn [x y] (<= (Math/abs (- (double x) (double y))) (double tol)))
                     (flatten a) (flatten b))))

(deftest euler-orders-compose
  (testing "XYZ turns about X first"
    (is (close? (m/mat-mul (m/euler->mat3 [0 0 0.3] 1) (m/euler->mat3 [0.2 0 0] 1))
                (m/euler->mat3 [0.2 0 0.3] 1) 1e-12)))
  (testing "a quaternion and its axis-angle agree"
    (is (close? (m/quat->mat3 [(Math/cos 0.4) 0 (Math/sin 0.4) 0])
                (m/axis-angle->mat3 [0 1 0] 0.8) 1e-12))))

(deftest one-change-of-axes
  (is (= m/y-up
         (let [^com.jme3.math.Matrix3f a util/blender-axes]
           (vec (for [i (range 3)] (vec (for [j (range 3)] (double (.get a (int i) (int j)))))))))))
