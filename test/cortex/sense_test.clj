;; Generated from org/sense.org by lein tangle: edit the chapter, not this file.
(ns cortex.sense-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.sense :as sense]
            [cortex.util :as util])
  (:import (com.jme3.scene Node)))

(set! *warn-on-reflection* true)

(deftest finding-marker-nodes
  (let [markers (util/nodify "joints" [(Node. "j1") (Node. "j2")])
        creature (util/nodify "creature" [(util/nodify "body" [markers])])
        joints (sense/sense-nodes "joints")]
    (is (= ["j1" "j2"] (map #(.getName %) (joints creature))))
    (testing "a creature without the node has no markers"
      (is (empty? ((sense/sense-nodes "eyes") creature))))
    (testing "a Geometry of that name is not a parent of markers"
      (is (empty? ((sense/sense-nodes "eyes")
                   (util/nodify [(util/box 1 1 1 :name "eyes" :physical? false)])))))))

(deftest reading-meta-data
  (let [geom (util/box 1 1 1 :name "segment" :physical? false)
        object (doto (util/nodify "segment" [geom]) (.setUserData "mass" (float 2)))]
    (is (= (float 2) (sense/meta-data object "mass")))
    (testing "a Geometry answers for its object"
      (is (= (float 2) (sense/meta-data geom "mass"))))
    (testing "its own value wins"
      (.setUserData geom "mass" (float 3))
      (is (= (float 3) (sense/meta-data geom "mass"))))
    (is (nil? (sense/meta-data geom "joint")))))
