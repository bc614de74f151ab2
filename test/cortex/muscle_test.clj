;; Generated from org/muscle.org by lein tangle: edit the chapter, not this file.
(ns cortex.muscle-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.joint-fixtures :as f]
            [cortex.muscle :as m]
            [cortex.proprioception :as p]
            [cortex.sim :as sim]
            [cortex.engine :as engine]
            [cortex.blender]
            [cortex.util :as util])
  (:import (com.jme3.math Quaternion)))

(set! *warn-on-reflection* true)

(def elbow "{:type :hinge :limit [-0.3 1.0] :axis (Vector3f. 0 0 1)}")

(defn- angles
  "The elbow's angle after each of `n` steps of `s` with `action`."
  [s n action]
  (vec (for [_ (range n)] (get-in (sim/step! s {"elbow" action}) [:joints "elbow" :angle]))))

(deftest torque-drives-a-hinge-to-its-limit-and-it-holds
  (doseq [[desc rotation] [[elbow Quaternion/IDENTITY]
                           [elbow f/half-turn-about-blender-z]
                           ["{:type :hinge :limit [-0.5 0.2] :axis (Vector3f. 0 1 0)}"
                            (f/turned 0.4 [1 0 0])]]
          gravity [[0 0 0] [0 -9.81 0]]
          [sign k] [[1 1] [-1 0]]]
    (let [s (sim/simulation (f/two-segments desc rotation) {:gravity gravity})
          strength (:strength ((:muscles s) "elbow"))
          limit (:limit (body/read-joint desc))
          as (angles s 180 (* sign 10 strength))
          target (double (limit k))]
      (testing (str desc " turned " rotation ", gravity " gravity ", pushing " sign)
        (is (< (Math/abs (- (peek as) target)) 0.05) "reaches and rests at the limit")
        (is (every? #(<= (* sign (- % target)) 0.05) as) "never passes it by more than 0.05")))))

(deftest the-worm-holds-its-limits-on-the-floor
  (let [s (sim/simulation (util/load-blender-model f/worm-path) {:floor 0})
        strength (:strength ((:muscles s) "worm-joint"))]
    (doseq [sign [1 -1]]
      (let [as (vec (for [_ (range 120)]
                      (get-in (sim/step! s {"worm-joint" (* sign strength)})
                              [:joints "worm-joint" :angle])))]
        (is (< (Math/abs (- (* sign (peek as)) (/ Math/PI 4))) 0.05))
        (is (every? #(<= (* sign %) (+ (/ Math/PI 4) 0.05)) as))))))

(deftest strength-clamps
  (let [ms (m/muscles (body/body! (f/two-segments "{:type :hinge :limit [-1 1] :axis (Vector3f. 0 0 1) :strength 2.5}")))]
    (is (= 2.5 (:strength (ms "elbow"))))
    (is (= {"elbow" 2.5} (m/efforts ms {"elbow" 100})))
    (is (= {"elbow" -2.5} (m/efforts ms {"elbow" -1e9})))
    (is (= {"elbow" 1.0} (m/efforts ms {"elbow" 1})))
    (is (<= (Math/abs (double (get (m/efforts ms {"elbow" {:target 3.0}}) "elbow"))) 2.5)))
  (let [ms (m/muscles (body/body! (f/two-segments "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.3 :strength 2}")))
        [x y z] (get (m/efforts ms {"elbow" [3 0 4]}) "elbow")]
    (is (< (Math/abs (- (Math/sqrt (+ (* x x) (* y y) (* z z))) 2.0)) 1e-12))
    (is (< (Math/abs (- (/ x z) 0.75)) 1e-12) "scaled, not cut per axis"))
  (testing "by default twice what holds the lighter segment out: 2 g m d, d = 1"
    (is (< (Math/abs (- (:strength ((m/muscles (body/body! (f/two-segments elbow))) "elbow"))
                        (* 2 9.81 1 1)))
           1e-5)))
  (testing "a bad strength in the description names the joint"
    (is (thrown-with-msg? clojure.lang.ExceptionInfo #"joint \"elbow\": :strength must be"
                          (m/muscles (body/body! (f/two-segments "{:type :hinge :limit [-1 1] :strength -2}")))))))

(deftest a-pd-target-holds-against-gravity
  (doseq [target [0.4 -0.2 0.0]]
    (let [s (sim/simulation (f/two-segments "{:type :hinge :limit [-1.5 1.5] :axis (Vector3f. 0 1 0)}"
                                            Quaternion/IDENTITY [0 1] 0)
                            {:gravity [0 -9.81 0]})
          as (angles s 300 {:target target})]
      (testing (str "target " target)
        (is (every? #(< (Math/abs (- (double %) (double target))) 0.02) (subvec as 240)))))))

(deftest a-cone-has-a-gain-per-axis
  (let [cone "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.3}"
        {:keys [kp kd inertia strength]} ((m/muscles (body/body! (f/two-segments cone))) "elbow")
        twist (/ (/ (+ 0.16 0.16) 12) 2)
        swing (/ (+ (/ (+ 3.61 0.16) 12) 1) 2)
        near? (fn [a b tolerance] (< (Math/abs (- (double a) (double b))) tolerance))]
    (is (near? (inertia 0) twist 1e-4))
    (is (every? #(near? % swing 1e-3) (rest inertia)))
    (is (every? true? (map #(near? %1 (min (/ strength 0.02) (* %2 900)) 1e-9) kp inertia)))
    (is (near? (kp 0) 12.0 0.05))
    (is (> (kp 1) (* 40 (kp 0))))
    (is (every? pos? kd)))
  (let [s (sim/simulation (f/two-segments "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.3}"
                                          Quaternion/IDENTITY [0 1] 0)
                          {:gravity [0 -9.81 0]})
        swings (vec (for [_ (range 300)]
                      (let [[a b] (get-in (sim/step! s {"elbow" {:target [0 0 0]}}) [:joints "elbow" :swing])]
                        (Math/sqrt (+ (* a a) (* b b))))))]
    (is (every? #(< % 0.03) (subvec swings 240)) (str "swing " (peek swings))))
  (testing "an action may give a gain per axis, checked like one"
    (let [s (sim/simulation (f/two-segments "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.3}"))]
      (is (map? (sim/step! s {"elbow" {:target [0 0.1 0] :kp [1 2 3] :kd 0.5}})))
      (is (thrown-with-msg? clojure.lang.ExceptionInfo #"joint \"elbow\": :kp must be .* or three of them"
                            (sim/step! s {"elbow" {:target [0 0.1 0] :kp [1 -2 3]}}))))))

(deftest a-pd-target-settles-floating-free
  (let [s (sim/simulation (util/load-blender-model f/worm-path) {:gravity [0 0 0]})
        obs (vec (for [_ (range 120)] (sim/step! s {"worm-joint" {:target 0.5}})))]
    (doseq [o (subvec obs 110)
            :let [{:keys [angle velocity]} (get-in o [:joints "worm-joint"])]]
      (is (< (Math/abs (- (double angle) 0.5)) 1e-3) (str "angle " angle))
      (is (< (Math/abs (double velocity)) 1e-2) (str "velocity " velocity)))))

(deftest muscles-are-internal
  (let [s (sim/simulation (f/chain 6 0) {:gravity [0 0 0]})
        muscles (:muscles s)
        masses (into {} (for [[n rb] (:segments s)] [n (/ 1.0 (engine/inverse-mass rb))]))
        actions (fn [t] (into {} (for [[i [n {:keys [type strength]}]] (map-indexed vector (sort muscles))]
                                   [n (let [a (* strength (Math/sin (+ (* 7 t) i)))]
                                        (if (= type :hinge) a [a (* 0.5 a) (- a)]))])))
        obs (last (for [i (range 120)] (sim/step! s (actions (/ i 60.0)))))
        spin (apply max (for [[_ {:keys [angular-velocity]}] (:segments obs)]
                          (Math/sqrt (p/dot angular-velocity angular-velocity))))
        momentum (apply mapv + (for [[n {:keys [velocity]}] (:segments obs)]
                                 (mapv #(* (masses n) %) velocity)))]
    (is (> spin 0.1) "the muscles did move the segments")
    (is (< (Math/sqrt (p/dot momentum momentum)) 1e-3))))

(deftest a-torque-turns-a-segment-as-newton-says
  (doseq [k [1 4]]
    (let [c (body/body! (f/two-segments "{:type :hinge :limit [-3 3] :axis (Vector3f. 0 0 1)}"
                                        Quaternion/IDENTITY [0 1] 0)
                        {:angular-damping 0.0 :sleeping-thresholds [0 0]})
          s (sim/simulation c {:gravity [0 0 0] :observe #{:joints} :solver {:substeps k}})
          o (last (repeatedly 30 #(sim/step! s {"elbow" 1.0})))
          moment (+ (/ (+ (* 1.9 1.9) (* 0.4 0.4)) 12.0) 1.0)
          want (/ 0.5 moment)
          w (double (get-in o [:joints "elbow" :velocity]))]
      (is (< (Math/abs (- (Math/abs w) want)) (* 1e-3 want))
          (str k " substeps: turning at " w " rad/s after 0.5 s, Newton's " want)))))

(deftest a-held-hand-stays-where-it-lies
  (let [s (sim/simulation (util/load-blender-model f/hand-path)
                          {:floor {:height 0 :friction 1.0} :observe #{:segments}})
        hold (into {} (for [[n {:keys [type]}] (:muscles s)]
                        [n {:target (if (= type :hinge) 0.0 [0.0 0.0 0.0])}]))
        palm (fn [steps] (get-in (last (repeatedly steps #(sim/step! s hold))) [:segments "palm" :position]))
        at-3 (palm 180)
        at-8 (palm 300)
        moved (Math/sqrt (reduce + (map #(let [d (- (double %1) (double %2))] (* d d)) at-8 at-3)))]
    (is (< moved 0.01) (str "the held palm moved " moved " between 3 s and 8 s"))))

(deftest bad-actions-are-refused-whole
  (let [s (sim/simulation (f/chain 4 0) {:gravity [0 0 0]})
        fresh (sim/simulation (f/chain 4 0) {:gravity [0 0 0]})
        good {"joint-seg-2" 1.0}]
    (doseq [[bad joint pattern] [[{"no-such-joint" 1.0} "no-such-joint" #"no such joint"]
                                 [{"joint-seg-2" [1 2 3]} "joint-seg-2" #"hinge joint takes"]
                                 [{"joint-seg-1" 1.0} "joint-seg-1" #"point joint takes"]
                                 [{"joint-seg-3" 2.0} "joint-seg-3" #"cone joint takes"]
                                 [{"joint-seg-2" Double/NaN} "joint-seg-2" #"finite"]
                                 [{"joint-seg-2" Double/POSITIVE_INFINITY} "joint-seg-2" #"finite"]
                                 [{"joint-seg-3" [0 Double/NaN 0]} "joint-seg-3" #"finite"]
                                 [{"joint-seg-2" {:target Double/NaN}} "joint-seg-2" #"finite"]
                                 [{"joint-seg-2" {:target 0.1 :kp -1}} "joint-seg-2" #":kp"]
                                 [{"joint-seg-3" [1 2]} "joint-seg-3" #"cone joint takes"]]]
      (let [e (try (sim/step! s (merge good bad)) nil
                   (catch clojure.lang.ExceptionInfo e e))]
        (testing (pr-str bad)
          (is (some? e))
          (is (= joint (:joint (ex-data e))))
          (is (re-find (re-pattern (str "joint \"" joint "\": ")) (ex-message e)))
          (is (re-find pattern (ex-message e)))
          (is (zero? (sim/steps s)) "no step taken"))))
    (testing "no torque was left behind: stepping both now gives the same"
      (is (= (sim/step! fresh) (sim/step! s))))))
