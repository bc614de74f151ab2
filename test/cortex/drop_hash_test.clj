;; Generated from org/physics-trust.org by lein tangle: edit the chapter, not this file.
(ns cortex.drop-hash-test
  (:require [clojure.edn :as edn]
            [clojure.java.io :as io]
            [clojure.pprint :as pprint]
            [clojure.test :refer [deftest is]]
            [cortex.engine :as engine]
            [cortex.physics-tab :as physics-tab]
            [cortex.drops :as drops]
            [cortex.sim :as sim]
            [cortex.util :as util])
  (:import (com.jme3.scene Node)
           (java.security MessageDigest)))

(def ^:private hashes-file "test/fixtures/drop-hashes.edn")

(def ^:private creatures drops/pinned)

(defn- hash-steps
  "The SHA-256, in hex, of the text (step-text i) gives after each of
  600 steps i of simulation `s` (step-text steps it), which is then
  destroyed."
  [s step-text]
  (try
    (let [d (MessageDigest/getInstance "SHA-256")]
      (dotimes [i 600]
        (.update d (.getBytes ^String (step-text i) "UTF-8")))
      (apply str (map #(format "%02x" (bit-and 0xff (long %))) (.digest d))))
    (finally (sim/destroy! s))))

(defn drop-hash
  "The hash of creature `name`'s 10 s drop on the running engine: every
  segment's observation at every one of 600 steps, as text."
  [name]
  (let [[how path opts] (creatures name)
        s (case how
            :markers (let [^Node c (util/load-blender-model path)]
                       (drops/place! c (or opts {}))
                       (sim/simulation c {:floor {:height 0 :friction 1.0}
                                          :observe #{:segments}}))
            :physics-tab (sim/simulation (physics-tab/physics-body! (physics-tab/load-creature path))
                                         {:observe #{:segments}}))]
    (hash-steps s (fn [_] (pr-str (into (sorted-map) (:segments (sim/step! s))))))))

(def ^:private observed
  "Drops pinned with everything observed (joints, segments and touch),
  the creature's muscles acting in every other second: name -> path."
  {"hand/observed" "assets/Models/test-creature/hand.blend"
   "stranger-humanoid/observed" "test/fixtures/strangers/humanoid.blend"})

(defn observed-hash
  "The hash of `observed` drop `name` on the running engine: its every
  observation at every one of 600 steps, as text."
  [name]
  (let [^Node c (util/load-blender-model (observed name))
        _ (drops/place! c {})
        s (sim/simulation c {:floor {:height 0 :friction 1.0}})
        act (into {} (for [[n m] (:muscles s)]
                       [n (if (= :hinge (:type m)) 0.3 [0.2 -0.1 0.3])]))
        sorted #(into (sorted-map) %)]
    (hash-steps s (fn [i]
                    (let [o (sim/step! s (when (odd? (quot (long i) 60)) act))]
                      (pr-str [(sorted (:joints o)) (sorted (:segments o))
                               (sorted (for [[k v] (:touch o)]
                                         [k (update v :touching sort)]))]))))))

(deftest drops-keep-their-hashes
  (let [f (io/file hashes-file)
        stored (if (.exists f) (edn/read-string (slurp f)) {})
        now (into (sorted-map) (concat (for [n (keys creatures)] [n (drop-hash n)])
                                       (for [n (keys observed)] [n (observed-hash n)])))]
    (if (System/getenv "CORTEX_RECORD_DROP_HASHES")
      (spit f (with-out-str
                (pprint/pprint (into (sorted-map)
                                     (for [[e hashes] (assoc stored engine/name now)]
                                       [e (into (sorted-map) hashes)])))))
      (doseq [[n h] now]
        (is (= (get-in stored [engine/name n]) h)
            (str n "'s drop on " engine/label " is not the one recorded in " hashes-file
                 " (see org/physics-trust.org, \"Pinned drops\")"))))))
