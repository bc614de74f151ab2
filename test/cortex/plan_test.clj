;; Generated from org/plan.org by lein tangle: edit the chapter, not this file.
(ns cortex.plan-test
  (:require [clojure.edn :as edn]
            [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.drops :as drops]
            [cortex.muscle :as muscle]
            [cortex.physics-tab :as physics-tab]
            [cortex.plan :as plan]
            [cortex.segment :as segment]
            [cortex.sim :as sim]
            [cortex.util :as util])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.scene Node)))

(def ^:private creatures
  "The pinned drops (cortex.drops/pinned) whose plans are checked: one of
  each kind, without the seed's hulls."
  (select-keys drops/pinned ["worm" "hand" "worm-eyes" "quadruped" "humanoid" "stranger-hand"
                             "stranger-worm-eye" "physics" "ragdoll"]))

(defn- fresh
  "Creature `name`, loaded and placed as the pinned drops place it (its
  lowest point 1 m above the floor), not yet built."
  ^Node [name]
  (let [[how path] (creatures name)
        c (util/load-blender-model path)]
    (when (= :markers how) (drops/lift! c))
    c))

(defn- built
  "Creature `name` built the usual way (`:usual`), or from its plan
  after the plan went through text (`:from-text`)."
  ^Node [name way]
  (let [[how] (creatures name)
        c (fresh name)
        tab? (= :physics-tab how)]
    (case way
      :usual (if tab? (physics-tab/physics-body! c) (body/body! c))
      :from-text (plan/build! c (edn/read-string
                                 (pr-str (plan/plan c {:physics-tab? tab?})))))))

(defn- drop-text
  "Every segment's observation at each of `steps` steps of `creature`'s
  fall onto the floor the pinned drops use, as text."
  [^Node creature tab? steps]
  (let [s (sim/simulation creature (cond-> {:observe #{:segments}}
                                     (not tab?) (assoc :floor {:height 0 :friction 1.0})))]
    (try
      (apply str (repeatedly steps #(pr-str (into (sorted-map) (:segments (sim/step! s))))))
      (finally (sim/destroy! s)))))

(deftest a-plan-is-data
  (doseq [name (keys creatures)
          :let [tab? (= :physics-tab (first (creatures name)))
                c (fresh name)
                p (plan/plan c {:physics-tab? tab?})]]
    (testing name
      (is (= p (edn/read-string (pr-str p))) "the plan reads back equal")
      (is (not-any? #(instance? Float %) (tree-seq coll? seq p)) "no Float in the plan")
      (is (every? #(nil? (.getControl ^com.jme3.scene.Spatial % RigidBodyControl))
                  (util/node-seq c))
          "planning made no rigid body")
      (is (pos? (count (:segments p))))
      (is (every? #(or (:kept? %) (and (= 3 (count (:position %))) (= 4 (count (:rotation %)))))
                  (:segments p))
          "every segment the plan makes says where it is")
      (is (= (count (:segments p)) (count (set (map :id (:segments p))))) "segment ids are unique"))))

(deftest a-plan-through-text-builds-the-same-creature
  (doseq [name (keys creatures)
          :let [tab? (= :physics-tab (first (creatures name)))]]
    (testing name
      (is (= (drop-text (built name :usual) tab? 120)
             (drop-text (built name :from-text) tab? 120))))))

(deftest the-plan-is-what-was-built
  (let [c (body/body! (fresh "worm-eyes"))
        {:keys [plan built]} (segment/record c)
        r (body/report c)]
    (is (= (map :name (:joints plan)) (map :name (:joints r))))
    (is (= (count (:segments plan)) (count (:segments built)) (count (:segments r))))
    (is (= (mapv :name (:eyes plan)) (mapv :name (:eyes r))))
    (is (every? #(identical? (:control %) (.getControl ^com.jme3.scene.Spatial (:geom %) RigidBodyControl))
                (:segments built)))))

(deftest a-simulated-creature-has-the-joints-its-plan-has
  (doseq [name ["ragdoll" "physics" "worm-eyes"]
          :let [tab? (= :physics-tab (first (creatures name)))
                c (built name :usual)
                {:keys [plan]} (segment/record c)
                s (sim/simulation c {:observe #{}})]]
    (try
      (is (= (+ (count (:joints plan)) (count (filter :enabled? (:constraints plan))))
             (count (.getJointList ^com.jme3.bullet.PhysicsSpace (:space s))))
          (str name ": one joint in the space for each in its plan"))
      (is (pos? (count (.getJointList ^com.jme3.bullet.PhysicsSpace (:space s)))))
      (finally (sim/destroy! s)))))

(deftest a-plan-says-each-joint-s-muscle
  (doseq [name ["hand" "quadruped" "worm"]
          :let [c (fresh name)
                p (plan/plan c {:physics-tab? false})
                planned (into {} (map (juxt :name :muscle)) (:joints p))
                built (muscle/muscles (body/body! c))]]
    (is (= (set (keys planned)) (set (keys built))) name)
    (doseq [[n {:keys [strength kp kd type]}] built
            :let [m (planned n)
                  ;; cortex.muscle gives a cone's gains in Blender's axis order
                  order (if (= type :hinge) identity (fn [[x y z]] [x z y]))
                  close? (fn close? [a b]
                           (if (sequential? a)
                             (every? true? (map close? a b))
                             (<= (Math/abs (- (double a) (double b)))
                                 (* 1e-4 (max 1.0 (Math/abs (double b)))))))]]
      (is (close? (:strength m) strength) (str name " " n))
      (is (close? (order (:kp m)) kp) (str name " " n))
      (is (close? (order (:kd m)) kd) (str name " " n)))))

(deftest a-plan-from-another-creature-is-refused-by-name
  (let [p (plan/plan (fresh "worm"))
        hand (fresh "hand")
        e (try (plan/build! hand p) nil (catch clojure.lang.ExceptionInfo e e))]
    (is (some? e))
    (is (re-find #"the plan's segment .* is not where the plan says" (ex-message e)))))

(deftest modifiers-are-applied-or-said
  (let [f "test/fixtures/modifiers/modifiers.blend"
        e (try (body/body! (util/load-blender-model f)) nil
               (catch clojure.lang.ExceptionInfo e e))
        p (plan/plan (util/load-blender-model f) {:strict? false})
        volume (into {} (map (juxt :name :volume)) (:segments (body/report (body/body! (util/load-blender-model f)
                                                                                        {:strict? false}))))]
    (is (= [[:far-joint "fin-root"]] (mapv (juxt :kind :joint) (:doubts (ex-data e)))))
    (is (re-find #"joint \"fin-root\" is 0\.0250 from torso and 0\.100 from fin" (str (ex-message e))))
    (is (re-find #"\(note: segment \"fin\" is built without its modifiers or shape keys \(Mirror: Mirror, it bisects\)"
                 (str (ex-message e))))
    (is (= [[:modifiers "fin" [{:name "Mirror" :kind "Mirror" :why "it bisects"}]]
            [:modifiers "head" [{:name "Subdivision" :kind "Subsurf"}]]]
           (mapv (juxt :kind :segment :modifiers) (filter #(= :modifiers (:kind %)) (:warnings p)))))
    (is (= [:modifiers :modifiers :far-joint] (mapv :kind (:warnings p))))
    (is (< (Math/abs (- (double (volume "torso")) 0.12)) 1e-6) (str "torso " (volume "torso")))
    (is (< (Math/abs (- (double (volume "leg")) 0.008)) 1e-6) (str "leg " (volume "leg")))))
