;; Generated from org/evolve.org by lein tangle: edit the chapter, not this file.
(ns cortex.evolve-test
  (:require [clojure.java.io :as io]
            [clojure.test :refer [deftest is testing]]
            [cortex.evolve :as e]
            [cortex.rollout :as r])
  (:import (java.nio.file Files)
           (java.nio.file.attribute FileAttribute)
           (javax.imageio ImageIO)))

(set! *warn-on-reflection* true)

(defn- peak [xs]
  (mapv (fn [x] (- (reduce + (map #(let [d (- %1 %2)] (* d d)) x [0.7 0.2 0.5])))) xs))

(deftest the-strategy-climbs
  (let [h (e/evolve peak {:generations 25 :lambda 10 :mu 3 :start [0.0 1.0 0.0] :sigma 0.2 :seed 4})
        best (:best-ever (peek h))]
    (is (= 25 (count h)))
    (is (> (:fitness best) -0.005) (str "best " best))
    (is (> (:best (peek h)) (:best (first h))))
    (is (= h (e/evolve peak {:generations 25 :lambda 10 :mu 3 :start [0.0 1.0 0.0] :sigma 0.2 :seed 4})))
    (is (not= h (e/evolve peak {:generations 25 :lambda 10 :mu 3 :start [0.0 1.0 0.0] :sigma 0.2 :seed 5})))))

(deftest genes-round-trip
  (is (= [0.0 0.0 0.0] (e/encode {:frequency 0.3 :amplitude 0.05 :rise 0.05})))
  (let [p (e/decode (e/encode e/hand-tuned))]
    (is (every? #(< (Math/abs (- (double (p %)) (double (e/hand-tuned %)))) 1e-12) (keys p)))))

(deftest the-worm-evolves-briefly
  (let [dir (str (Files/createTempDirectory "cortex-evolve" (into-array FileAttribute [])))
        result (atom nil)
        out (with-out-str
              (reset! result (e/learn! {:generations 2 :lambda 4 :mu 2 :starts 1 :seconds 3.0 :seed 1
                                        :threads 2 :out dir :no-video true})))
        {:keys [history best reference files]} @result]
    (is (= 2 (count history)))
    (is (every? #(<= (:mean %) (:best %)) history))
    (is (every? (fn [{:keys [name min max]}] (<= min (best name) max)) e/genes))
    (is (pos? reference) "the hand-tuned gait crawls forwards even in 3 s")
    (is (re-find #"generation   2  best" out))
    (let [img (ImageIO/read (io/file dir "fitness.png"))]
      (is (= [800 480] [(.getWidth img) (.getHeight img)])))
    (is (= 3 (count files)))
    (is (= 3 (count (line-seq (io/reader (io/file dir "history.csv"))))) "a header and two generations")))
