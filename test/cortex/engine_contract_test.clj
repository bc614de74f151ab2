;; Generated from org/engine-contract.org by lein tangle: edit the chapter, not this file.
(ns cortex.engine-contract-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.engine :as engine]
            [cortex.engine-contract :as contract])
  (:import (com.jme3.bullet.joints PhysicsJoint)))

(defn- arities
  "The number of arguments of each of `v`'s arglists, or :value."
  [v]
  (if (fn? @v)
    (vec (sort (map count (:arglists (meta v)))))
    :value))

(deftest the-engine-keeps-the-contract
  (let [publics (ns-publics 'cortex.engine)]
    (doseq [[sym [want what]] contract/provides]
      (testing (str sym ", " what)
        (is (contains? publics sym) (str engine/label " has no " sym))
        (when-let [v (publics sym)]
          (is (= want (arities v)) (str engine/label "'s " sym))
          (is (some? (:doc (meta v))) (str engine/label "'s " sym " says what it does")))))))

(deftest what-every-engine-computes-alike
  (is (#{:jbullet :native} engine/name))
  (is (string? engine/label))
  (is (pos-int? engine/solver-iterations))
  (is (isa? engine/six-dof-class PhysicsJoint))
  (is (<= 0.0 (engine/hull-margin) 0.001) "a hull's skin is at most a thousandth")
  (testing "a hull's volume, whatever its points' order and however many lie on a face"
    (let [cube (for [x [0 2] y [0 3] z [0 4]] [x y z])
          face-centres [[1 0 2] [1 3 2] [0 1.5 2] [2 1.5 2] [1 1.5 0] [1 1.5 4]]]
      (is (< (Math/abs (- 24.0 (engine/hull-volume cube))) 1e-4))
      (is (< (Math/abs (- 24.0 (engine/hull-volume (reverse (concat face-centres cube))))) 1e-4))
      (is (< (Math/abs (- (/ 24.0 6) (engine/hull-volume [[0 0 0] [2 0 0] [0 3 0] [0 0 4]]))) 1e-4))
      (is (zero? (engine/hull-volume [[0 0 0] [1 0 0] [0 1 0]])) "three points")
      (is (zero? (engine/hull-volume [[0 0 0] [1 0 0] [0 1 0] [1 1 0] [0.5 0.5 0]])) "a flat square"))))
