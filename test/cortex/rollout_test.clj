;; Generated from org/rollout.org by lein tangle: edit the chapter, not this file.
(ns cortex.rollout-test
  (:require [clojure.edn :as edn]
            [clojure.java.io :as io]
            [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.rollout :as r]
            [cortex.sim :as sim]
            [cortex.blender]
            [cortex.util :as util])
  (:import (com.jme3.scene Node)
           (java.nio.file Files)
           (java.nio.file.attribute FileAttribute)
           (java.util.concurrent CountDownLatch)))

(set! *warn-on-reflection* true)

(def worm
  {:creature "Models/test-creature/worm.blend" :controller 'cortex.rollout/crawl-gait :seconds 10})

(def hand
  {:creature "Models/test-creature/hand.blend" :controller 'cortex.rollout/sine-gait :seconds 2})

(deftest the-worm-crawls-in-a-rollout
  (let [{:keys [distance displacement energy fell? max-tilt final-pose trajectory steps] :as res}
        (r/rollout (assoc worm :trajectory 60))
        [dx _ dz] displacement
        limp (r/rollout (dissoc worm :controller))]
    (is (< dx ((requiring-resolve 'cortex.sim-test/crawl-at-least))) (str "moved " dx " along x"))
    (is (< (Math/abs (double dz)) (/ (Math/abs (double dx)) 2)))
    (is (< (Math/abs (- distance (Math/hypot dx dz))) 1e-12))
    (is (< 10.0 energy 2000.0) (str "energy " energy))
    (is (not fell?))
    (is (< 0.1 max-tilt 1.0) "it arches, it does not roll")
    (is (= 600 steps))
    (is (= #{"worm-1" "worm-2"} (set (keys (:segments final-pose)))))
    (is (= 11 (count trajectory)) "every 60 steps from the first observation: 0 to 600")
    (is (= [0.0 10.0] [(:time (first trajectory)) (:time (peek trajectory))]))
    (is (= res (edn/read-string (r/edn res))) "plain data, exactly through EDN")
    (is (< (:distance limp) 0.05))
    (is (= 0.0 (:energy limp)))))

(deftest rollouts-equal-rollouts-one-at-a-time
  (let [specs (vec (concat (for [seed (range 6)]
                             (assoc worm :seconds 3 :seed seed :start {:shift 0.3 :turn 0.2}))
                           [hand (assoc hand :params {:amplitude 0.5})
                            ;; the first worm again, stepped finer: its own solver is used
                            (assoc worm :seconds 3 :seed 0 :start {:shift 0.3 :turn 0.2}
                                   :solver {:iterations 20 :substeps 2})]))
        alone (mapv r/rollout specs)]
    (is (= 9 (count (set (map :final-pose alone)))) "every spec moved differently")
    (is (= alone (r/rollouts specs {:threads 2})))
    (is (= alone (r/rollouts specs {:threads 3})))
    (is (= alone (r/rollouts specs)))
    (is (= [] (r/rollouts [])))))

(defn- hand-sim-run
  [angle ^CountDownLatch start]
  (let [c (doto ^Node (util/load-blender-model (:creature hand)) (.rotate 0 (float angle) 0.1))
        _ (.countDown start)
        _ (.await start)
        s (sim/simulation (body/body! c) {:floor -2})
        control (r/sine-gait {:amplitude 0.6})]
    (loop [i 0 obs (sim/observe s)]
      (if (< i 90)
        (recur (inc i) (sim/step! s (control obs)))
        (do (sim/destroy! s) (dissoc obs :touch))))))

(deftest simulations-built-and-stepped-on-many-threads-are-the-same
  (let [angles (map #(* 0.4 %) (range 8))
        alone (mapv #(hand-sim-run % (CountDownLatch. 0)) angles)
        start (CountDownLatch. (count angles))
        together (mapv deref (mapv #(future (hand-sim-run % start)) angles))]
    (is (= 8 (count (set alone))))
    (is (= alone together))))

(def calls (atom 0))

(defn counting-gait
  "A controller for the tests: counts its calls."
  [_]
  (fn [_] (swap! calls inc) nil))

(defn- failure [specs]
  (try (r/rollouts specs) nil
       (catch clojure.lang.ExceptionInfo e
         [(ex-message e) (select-keys (ex-data e) [:index :field])])))

(deftest bad-specs-fail-before-any-work
  (reset! calls 0)
  (let [good (assoc worm :controller 'cortex.rollout-test/counting-gait :seconds 1)]
    (doseq [[bad field pattern]
            [[(assoc worm :controller 'no.such/gait) :controller #"cannot load no\.such/gait"]
             [(assoc worm :controller 'cortex.rollout/no-such-gait) :controller #"names no function"]
             [(assoc worm :controller "crawl") :controller #"qualified symbol"]
             [(assoc worm :creature "Models/nowhere.blend") :creature #"Models/nowhere\.blend\" is no file"]
             [(assoc worm :seconds -1) :seconds #"more than 0"]
             [(assoc worm :seconds ##NaN) :seconds #"finite"]
             [(dissoc worm :seconds) :seconds #"not nil"]
             [(assoc worm :seed 1.5) :seed #"integer"]
             [(assoc worm :start {:shift -1}) :start #"not negative"]
             [(assoc worm :params {:frequency 0}) :params #":frequency must be a positive number"]
             [(assoc worm :params {:rise 1.5}) :params #":rise must be a fraction"]
             [(assoc worm :trajectory 0) :trajectory #"positive whole"]
             [(assoc worm :sceonds 3) :sceonds #"unknown key; did you mean :seconds\?"]
             [(assoc worm :solver {:substeps 0}) :solver #":substeps must be a whole number from 1 to 64"]
             [(assoc worm :solver {:iteration 20}) :solver #"did you mean :iterations\?"]
             [(assoc worm :scale 0) :scale #"must be :auto or a positive number, not 0"]
             [(assoc worm :eyes true) :eyes #"rollouts run without eyes.*org/vision\.org"]]]
      (let [[message data] (failure [good bad])]
        (is (= {:index 1 :field field} data) (pr-str bad))
        (is (re-find pattern (str message)) message)
        (is (re-find #"^spec 1, " (str message))))))
  (is (= 0 @calls) "nothing ran")
  (is (thrown-with-msg? clojure.lang.ExceptionInfo #"^spec, :seconds"
                        (r/rollout (assoc worm :seconds 0)))))

(deftest a-small-creature-s-rollout-is-simulated-larger
  (let [small {:creature "test/fixtures/strangers/hand-0.01.blend" :seconds 1}
        scale-of (fn [spec] (let [s (r/simulation (r/check-spec! nil spec))]
                              (try (sim/scale s) (finally (sim/destroy! s)))))]
    (is (= [100.0 1.0 1.0] [(scale-of small) (scale-of (assoc small :scale 1))
                            (scale-of (dissoc worm :controller :params))]))
    (let [result (r/rollout small)]
      (is (nil? (:error result)) (str (:error result)))
      (is (= 60 (:steps result))))))

(deftest a-failing-rollout-is-its-own-row
  (let [dir (Files/createTempDirectory "cortex-rollout" (into-array FileAttribute []))
        broken (str (io/file (str dir) "broken.blend"))
        _ (spit broken "BLENDER? not at all")
        short (assoc worm :seconds 1)
        rows (r/rollouts [short (assoc short :creature broken) (assoc short :seed 2)])]
    (is (= [false true false] (mapv #(contains? % :error) rows)))
    (is (re-find #"broken\.blend" (get-in rows [1 :error :message])))
    (is (= (r/rollout short) (rows 0)))
    (is (every? :final-pose [(rows 0) (rows 2)]))
    (testing "as rows of a table"
      (let [flat (r/flat-row 1 (rows 1))]
        (is (= (count r/columns) (count flat)))
        (is (= broken (flat 2)))
        (is (re-find #"broken\.blend" (nth flat 16))))
      (is (= [0 nil "Models/test-creature/worm.blend" "cortex.rollout/crawl-gait" "nil" 1.0 0]
             (subvec (r/flat-row 0 (rows 0)) 0 7))))))
