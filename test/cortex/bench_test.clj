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
