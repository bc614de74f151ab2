;; Generated from org/proprioception.org by lein tangle: edit the chapter, not this file.
(ns cortex.proprioception-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.joint-fixtures :as f]
            [cortex.proprioception :as p]
            [cortex.blender]
            [cortex.util :as util])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Quaternion Vector3f)
           (com.jme3.scene Node)))

(set! *warn-on-reflection* true)

(defn- control ^RigidBodyControl [creature name]
  (.getControl (body/segment creature name) RigidBodyControl))

(defn- v3 ^Vector3f [[x y z]] (Vector3f. (float x) (float y) (float z)))

(defn- pose!
  "Turn segment `name` of `creature` by the world rotation `q` about the
  world point `pivot`."
  [creature name q pivot]
  (let [c (control creature name)
        loc (.getPhysicsLocation c)
        rel (mapv - [(.x loc) (.y loc) (.z loc)] pivot)
        rot (.getPhysicsRotation c)
        [x y z w] (p/q* q [(.getX rot) (.getY rot) (.getZ rot) (.getW rot)])]
    (.setPhysicsLocation c (v3 (mapv + pivot (p/rotate q rel))))
    (.setPhysicsRotation c (Quaternion. (float x) (float y) (float z) (float w)))))

(defn- hinge [axis] (str "{:type :hinge :limit [-3 3] :axis (Vector3f. " axis ")}"))

(deftest the-build-pose-reads-zero
  (is (= {"worm-joint" {:type :hinge :angle 0.0 :velocity 0.0}}
         (p/proprioception (body/body! (util/load-blender-model f/worm-path)))))
  (let [{:keys [swing twist angular-velocity]}
        (get (p/proprioception (body/body! (f/two-segments "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.3}")))
             "elbow")]
    (is (every? #(< (Math/abs (double %)) 1e-6) (concat swing [twist] angular-velocity)))))

(deftest hinge-angle-against-geometry
  (doseq [[axis blender-axis] [["0 1 0" [0 1 0]] ["0 0 1" [0 0 1]] ["1 0 0" [1 0 0]]
                               ["0 0.6 0.8" [0 0.6 0.8]]]
          angle [-2.5 -0.7 -0.2 0.0 0.3 0.9 2.0]]
    (let [creature (body/body! (f/two-segments (hinge axis)))
          u (p/normalize (p/blender->jme blender-axis))]
      (pose! creature "lower" (p/from-rotation-vector (mapv #(* angle %) u)) [0 0 0])
      (.setAngularVelocity (control creature "lower") (v3 (mapv #(* 0.5 %) u)))
      (let [{read-angle :angle velocity :velocity} (get (p/proprioception creature) "elbow")]
        (testing (str "axis " axis ", angle " angle)
          (is (< (Math/abs (- (double read-angle) angle)) 1e-4))
          (is (< (Math/abs (- (double velocity) 0.5)) 1e-4)))))))

(deftest hinge-sign-unchanged-when-the-segments-swap
  (doseq [[axis blender-axis] [["0 1 0" [0 1 0]] ["1 0 0" [1 0 0]]]
          angle [-0.6 0.25 1.1]]
    (let [readings
          (for [rotation [Quaternion/IDENTITY f/half-turn-about-blender-z]]
            (let [creature (body/body! (f/two-segments (hinge axis) rotation))
                  ;; the unturned empty's axis, in the world
                  w (p/blender->jme blender-axis)]
              (pose! creature "lower" (p/from-rotation-vector (mapv #(* angle %) w)) [0 0 0])
              [(first (:segments (first (body/joint-records creature))))
               (:angle (get (p/proprioception creature) "elbow"))]))
          [[a1 r1] [a2 r2]] readings]
      (testing (str "axis " axis ", angle " angle)
        (is (= ["upper" "lower"] [a1 a2]) "the turn swaps body A and body B")
        (is (< (Math/abs (- (double r1) angle)) 1e-4))
        (is (< (Math/abs (- (double r2) angle)) 1e-4))))))

(deftest cone-swing-and-twist-against-geometry
  (doseq [[sy sz t] [[0.0 0.0 0.4] [0.3 0.0 0.0] [0.0 -0.35 0.0] [0.25 -0.15 0.2] [-0.4 0.3 -0.3]]
          rotation [Quaternion/IDENTITY (f/turned 0.7 [0 0 1])]]
    (let [creature (body/body! (f/two-segments "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.3}"
                                               rotation))
          frame (let [^Quaternion r rotation] [(.getX r) (.getY r) (.getZ r) (.getW r)])
          ;; swing * twist in the joint frame's Blender axes, to jME's world axes
          q-blender (p/q* (p/from-rotation-vector [0 sy sz]) (p/from-rotation-vector [t 0 0]))
          q-world (p/q* frame (p/q* (p/blender->jme q-blender) (p/q-conj frame)))]
      (pose! creature "lower" q-world [0 0 0])
      (let [{:keys [swing twist]} (get (p/proprioception creature) "elbow")]
        (testing (str [sy sz t])
          (is (< (Math/abs (- (double twist) t)) 1e-4))
          (is (every? #(< (Math/abs (double %)) 1e-4) (map - swing [sy sz]))))))))

(deftest a-cone-read-on-primitives-is-read-as-on-vectors
  ;; jme-swing-twist is swing-twist written out: the same numbers to the
  ;; bit, for any rotation, w of either sign, and near the identity
  (let [r (java.util.Random. 20261128)
        g #(- (* 2.0 (.nextDouble r)) 1.0)
        qs (concat [[0.0 0.0 0.0 1.0] [0.0 0.0 0.0 -1.0] [1e-14 -2e-14 0.0 1.0] [0.0 3e-9 -4e-9 1.0]
                    [0.0 0.0 1.0 0.0]]
                   (for [_ (range 20000)
                         :let [[x y z w] [(g) (g) (g) (g)]
                               n (Math/sqrt (+ (* x x) (* y y) (* z z) (* w w)))]]
                     (mapv #(/ (double %) n) [x y z w])))
        differ (remove (fn [[x y z w :as q]]
                         ;; printed, so that -0.0 and 0.0 differ too
                         (= (pr-str (p/swing-twist (p/jme->blender q)))
                            (pr-str (p/jme-swing-twist x y z w))))
                       qs)]
    (is (empty? differ) (str (count differ) " rotations read differently, first " (first differ)))))

(deftest a-creature-without-a-body-is-an-error
  (is (thrown-with-msg? clojure.lang.ExceptionInfo #"has no body yet: call body! first"
                        (p/proprioception (f/two-segments (hinge "0 1 0"))))))
