;; Generated from org/projection.org by lein tangle: edit the chapter, not this file.
(ns cortex.projection-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.engine :as engine]
            [cortex.projection :as projection])
  (:import (com.jme3.bullet.collision.shapes BoxCollisionShape)
           (com.jme3.bullet.joints HingeJoint PhysicsJoint)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.math Quaternion Vector3f)))

(defn- about ^Quaternion [angle [x y z]]
  (.fromAngleAxis (Quaternion.) (float angle) (.normalizeLocal (Vector3f. (float x) (float y) (float z)))))

(def ^:private hinge {:type :hinge :axis (Vector3f. 0 0 1) :limit [-0.3 0.3]})

(deftest a-hinge-comes-back-to-its-keep
  (let [[trigger keep] (projection/slack :hinge)]
    (doseq [[angle expected] [[0.6 (+ 0.3 keep)] [-1.2 (- -0.3 keep)] [2.5 (+ 0.3 keep)]]]
      (let [q' (projection/corrected hinge (about angle [0 0 1]))]
        (is (< (Math/abs (- (projection/hinge-angle q' (Vector3f. 0 0 1)) expected)) 1e-5)
            (str angle " comes back to " expected))))
    (testing "within the trigger, or within the limits, nothing is done"
      (doseq [angle [0.0 0.29 (+ 0.3 trigger -0.001) (+ -0.3 (- trigger) 0.001)]]
        (is (nil? (projection/corrected hinge (about angle [0 0 1]))) (str angle))))
    (testing "a swing off the axis is kept"
      (let [q (.mult (about 0.2 [1 0 0]) (about 0.6 [0 0 1]))
            q' (projection/corrected hinge q)]
        (is (< (Math/abs (- (projection/hinge-angle q' (Vector3f. 0 0 1)) (+ 0.3 keep))) 1e-5))))))

(deftest a-cone-is-read-back-from-its-angles
  (let [turn (about 0.9 [1 2 3])
        rnd (java.util.Random. 11)]
    (dotimes [_ 20]
      (let [angles [(- (* 6 (.nextDouble rnd)) 3) (- (* 3 (.nextDouble rnd)) 1.5) (- (* 6 (.nextDouble rnd)) 3)]
            back (projection/euler-angles (projection/from-euler angles turn) turn)]
        (is (every? #(< (Math/abs (double %)) 1e-4) (map - angles back)) (pr-str angles back))))
    (testing "a cone past its limits comes back to its keep on each angle past"
      (let [[_ keep] (projection/slack :cone)
            spec {:type :cone :turn turn :limits [0.2 0.5 0.8]}
            q' (projection/corrected spec (projection/from-euler [0.6 -0.1 -1.4] turn))
            [x y z] (projection/euler-angles q' turn)]
        (is (< (Math/abs (- x (+ 0.2 keep))) 1e-4))
        (is (< (Math/abs (- y -0.1)) 1e-4))
        (is (< (Math/abs (- z (- -0.8 keep))) 1e-4))))))

(defn- box-body ^PhysicsRigidBody [mass x]
  (doto (PhysicsRigidBody. (BoxCollisionShape. (Vector3f. 0.45 0.1 0.1)) (float mass))
    (.setPhysicsLocation (Vector3f. (float x) 0 0))))

(defn- angle-of
  "The angle of the hinge between bodies `a` and `b`, whose frames were
  aligned when it was made, about Z."
  ^double [^PhysicsRigidBody a ^PhysicsRigidBody b]
  (projection/hinge-angle (.mult (.inverse (.getPhysicsRotation a)) (.getPhysicsRotation b))
                          (Vector3f. 0 0 1)))

(defn- gap
  ^double [^PhysicsJoint j]
  (let [[^Vector3f pa ^Vector3f pb] (engine/pivots j)
        ^PhysicsRigidBody a (.getBodyA j)
        ^PhysicsRigidBody b (.getBodyB j)]
    (.distance (.add (.getPhysicsLocation a) (.mult (.getPhysicsRotation a) pa))
               (.add (.getPhysicsLocation b) (.mult (.getPhysicsRotation b) pb)))))

(deftest a-bent-chain-is-put-back-from-its-heaviest-end
  ;; b and c are joined to a, the heaviest, by two hinges about Z at
  ;; x = 0.5 and x = 1.5; the first may turn 0.3 rad, the second 1
  (let [a (box-body 5 0) b (box-body 1 1) c (box-body 1 2)
        hinge (fn [p q x]
                (HingeJoint. p q (Vector3f. 0.5 0 0) (Vector3f. -0.5 0 0)
                             (Vector3f. 0 0 1) (Vector3f. 0 0 1)))
        j1 (projection/hold! (hinge a b 0.5) {:type :hinge :frame-a [0 0 0 1] :frame-b [0 0 0 1]
                                              :axis [0 0 1] :limit [-0.3 0.3]})
        j2 (projection/hold! (hinge b c 1.5) {:type :hinge :frame-a [0 0 0 1] :frame-b [0 0 0 1]
                                              :axis [0 0 1] :limit [-1 1]})
        plan (projection/plan [j2 j1])
        [_ keep] (projection/slack :hinge)]
    (testing "the tree: from a, the first hinge carries b and c"
      (is (= [j1 j2] (map :joint plan)))
      (is (= [true true] (map :far-b? plan)))
      (is (= [[b c] [c]] (map :subtree plan))))
    ;; bend the first hinge 0.8 rad, and the second 0.5, about their pivots
    (let [bend (fn [bodies angle ^Vector3f centre]
                 (doseq [^PhysicsRigidBody x bodies
                         :let [d (about angle [0 0 1])]]
                   (.setPhysicsLocation x (.add centre (.mult d (.subtract (.getPhysicsLocation x) centre))))
                   (.setPhysicsRotation x (.mult d (.getPhysicsRotation x)))))]
      (bend [b c] 0.8 (Vector3f. 0.5 0 0))
      (bend [c] 0.5 (.add (.getPhysicsLocation b) (.mult (.getPhysicsRotation b) (Vector3f. 0.5 0 0)))))
    (is (< (Math/abs (- (angle-of a b) 0.8)) 1e-5))
    (is (= 1 (projection/project! plan)) "one joint was past its trigger")
    (is (< (Math/abs (- (angle-of a b) (+ 0.3 keep))) 1e-4) "the first hinge is back at its keep")
    (is (< (Math/abs (- (angle-of b c) 0.5)) 1e-4) "the second keeps its angle")
    (is (< (gap j1) 1e-5))
    (is (< (gap j2) 1e-5))
    (is (< (.length (.getPhysicsLocation a)) 1e-6) "the root did not move")
    (is (zero? (projection/project! plan)) "once back, nothing more to do")))
