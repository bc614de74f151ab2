;; Generated from org/test-body.org by lein tangle: edit the chapter, not this file.
(ns cortex.test.body
  "The worlds that show a body being built, step by step: the hand as a
  hologram, the hand solid but in pieces, the hand jointed, and the worm
  that later chapters give senses to. Each is a function returning an
  unstarted world: (render/start-window! (test-worm)) opens a window,
  (world/run-world! (test-worm) 300) runs it headless.

  Entry points: `test-hand-1`, `test-hand-2`, `test-hand-3`,
  `test-worm`."
  (:require [cortex.body :as body]
            [cortex.demo :as demo :refer [hand worm floor setup]]
            [cortex.render :as render]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.math Vector3f)))

(set! *warn-on-reflection* true)

(defn- record-if-asked!
  "Record world `w` into folder `record?` when it names one, into
  out/`world-name` when it is true, not at all when it is false or nil."
  [w record? world-name]
  (when record?
    (render/record! w (if (true? record?) (str "out/" world-name) record?)))
  w)

(defn test-hand-1
  "The hand straight from Blender: it has no physical presence, and
  things pass through it. Records its frames when `record?` is a
  folder (or true, for out/test-hand-1)."
  ([] (test-hand-1 false))
  ([record?]
   (world/world (hand) world/standard-debug-controls
                #(setup (record-if-asked! % record? "test-hand-1"))
                world/no-op)))

(defn test-hand-2
  "The hand made solid, with nothing holding it together: switch on
  gravity (G) and it falls to the floor in pieces. Records its frames
  when `record?` is a folder (or true, for out/test-hand-2)."
  ([] (test-hand-2 false))
  ([record?]
   (world/world (util/nodify [(body/physical! (hand)) (floor)])
                (merge world/standard-debug-controls demo/gravity-control)
                #(setup (world/set-gravity (record-if-asked! % record? "test-hand-2")
                                           Vector3f/ZERO))
                world/no-op)))

(defn test-hand-3
  "The hand with its joints: under gravity (G) it falls as one piece,
  fingers bending only as far as their knuckles allow. H shows the
  joints. Records its frames when `record?` is a folder (or true, for
  out/test-hand-3)."
  ([] (test-hand-3 false))
  ([record?]
   (world/world (util/nodify [(body/body! (hand)) (floor)])
                (merge world/standard-debug-controls demo/debug-control demo/gravity-control)
                #(setup (world/set-gravity (record-if-asked! % record? "test-hand-3")
                                           Vector3f/ZERO))
                world/no-op)))

(defn ^:api test-worm
  "The worm falls onto the floor; space fires a cannon ball at it and H
  shows its joint. Simulated and wall time are shown on screen. Records
  its frames when `record?` is a folder (or true, for out/test-worm)."
  ([] (test-worm false))
  ([record?]
   (world/world (util/nodify [(body/body! (worm)) (floor)])
                (merge world/standard-debug-controls demo/debug-control)
                (fn [w]
                  (record-if-asked! w record? "test-worm")
                  (setup w)
                  (world/speed-up w)
                  (util/display-dilated-time w (.getTimer ^SimpleApplication w)))
                world/no-op)))
