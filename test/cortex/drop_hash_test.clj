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

(def ^:private creatures
  "name -> [how it is made, path]"
  (array-map
   "worm" [:markers "assets/Models/test-creature/worm.blend"]
   "hand" [:markers "assets/Models/test-creature/hand.blend"]
   "worm-eyes" [:markers "assets/Models/test-creature/worm-eyes.blend"]
   "quadruped" [:markers "test/fixtures/designer/quadruped.blend"]
   "humanoid" [:markers "test/fixtures/humanoid/humanoid.blend"]
   "humanoid-heavy-hands" [:markers "test/fixtures/humanoid/humanoid-heavy-hands.blend"]
   "stranger-hand" [:markers "test/fixtures/strangers/hand.blend"]
   "stranger-humanoid" [:markers "test/fixtures/strangers/humanoid.blend"]
   "stranger-worm-eye" [:markers "test/fixtures/strangers/worm-eye.blend"]
   ;; the seed's one hull a segment, as every creature was built before
   ;; shapes were chosen: these keep the hashes they had then
   "hand/hulls" [:markers "assets/Models/test-creature/hand.blend" {:shapes :hull}]
   "quadruped/hulls" [:markers "test/fixtures/designer/quadruped.blend" {:shapes :hull}]
   "stranger-hand/hulls" [:markers "test/fixtures/strangers/hand.blend" {:shapes :hull}]
   "stranger-humanoid/hulls" [:markers "test/fixtures/strangers/humanoid.blend" {:shapes :hull}]
   "physics" [:physics-tab "test/fixtures/blend/b45/physics.blend"]
   "ragdoll" [:physics-tab "test/fixtures/physics-sim/ragdoll.blend"]))

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
    (try
      (let [d (MessageDigest/getInstance "SHA-256")]
        (dotimes [_ 600]
          (.update d (.getBytes (pr-str (into (sorted-map) (:segments (sim/step! s)))) "UTF-8")))
        (apply str (map #(format "%02x" (bit-and 0xff (long %))) (.digest d))))
      (finally (sim/destroy! s)))))

(deftest drops-keep-their-hashes
  (let [f (io/file hashes-file)
        stored (if (.exists f) (edn/read-string (slurp f)) {})
        now (into (sorted-map) (for [n (keys creatures)] [n (drop-hash n)]))]
    (if (System/getenv "CORTEX_RECORD_DROP_HASHES")
      (spit f (with-out-str
                (pprint/pprint (into (sorted-map)
                                     (for [[e hashes] (assoc stored engine/name now)]
                                       [e (into (sorted-map) hashes)])))))
      (doseq [[n h] now]
        (is (= (get-in stored [engine/name n]) h)
            (str n "'s drop on " engine/label " is not the one recorded in " hashes-file
                 " (see org/physics-trust.org, \"Pinned drops\")"))))))
