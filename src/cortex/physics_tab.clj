;; Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
(ns cortex.physics-tab
  "Build a creature from Blender's own rigid body physics: every object
  with a Rigid Body (Physics tab) becomes a jBullet rigid body, every
  Rigid Body Constraint a jBullet joint between the two objects it
  names, placed and turned as the constraint object is. No custom
  property is needed. The work is done by cortex.rigid-body and
  cortex.constraint, through a plan (see cortex.plan).

  Entry points: `load-creature` (a .blend file with its Physics tab
  settings, any of its scenes), `physics-body!` (build the bodies and
  joints of the Rigid Body World, simulated as Blender's world says),
  `build!` (the same, returning what was built), `warnings` (what
  could not be built as Blender would), `broken-joints` (the joints
  that broke), and, from the namespaces that do the work,
  `world-settings` (the file's Rigid Body World), `simulation-settings`
  (its gravity, substeps, solver iterations and time scale, as data),
  `gravity` (its gravity as a jME vector), `rigid-body` and
  `rigid-body-constraint` (an object's settings), `rigid-body!`,
  `rigid-bodies!`, `constraint!`, `constraints!`."
  (:require [cortex.blender :as blender]
            [cortex.constraint :as constraint]
            [cortex.plan :as plan]
            [cortex.rigid-body :as rigid-body]
            [cortex.segment :as segment]
            [cortex.util :as util])
  (:import (com.jme3.scene Node)))

(set! *warn-on-reflection* true)

(util/export-vars cortex.rigid-body rigid-body rigid-body-constraint rigid-body-objects
        constraint-objects body-spatial collision-shape rigid-body! rigid-bodies!)
(util/export-vars cortex.constraint constraint-frame limits hinge-limit locked constraint-joint
        constraint! constraints! ^:api world-settings gravity substep-length
        ^:api simulation-settings simulation-key)

(defn ^:api warnings
  "The warnings, as text, of the Physics tab's part of `creature`'s plan
  (see `build!`): what could not be built as Blender would."
  [^Node creature]
  (vec (for [w (get-in (segment/record creature) [:plan :warnings])
             :when (= :physics-tab (:kind w))]
         (:message w))))

(defn ^:api broken-joints
  "The joints of `creature` (built by `physics-body!`) that broke so far:
  constraint object name -> the substep (counted from the world's
  start) after which it broke."
  [^Node creature]
  (into {} (get-in (segment/record creature) [:built :broken])))

(defn build!
  "Give `creature` (a Node loaded from Blender) the body Blender's Physics
  tab describes: its plan (see cortex.plan/plan, with :physics-tab?
  true) built. Rigid bodies, then joints for its rigid body
  constraints, of the objects Blender simulates (the Rigid Body World's
  collections), or of every object with settings when `opts` has
  :all-rigid-bodies? true. A creature that also has custom-property
  joints (a \"joints\" empty, see cortex.body) gets those too, with
  cortex's segments for its other Geometries, between the two. The
  creature's Node gets a control that applies the world's
  `simulation-settings` to the space it joins (unless :simulation?
  false) and breaks joints that reach their breaking threshold. Returns
  {:creature :bodies :joints :warnings :simulation :broken}: the
  reports of `rigid-body!` and `constraint!`, every warning (text), the
  settings applied, and a map (a java.util.Map, filled in as the world
  runs) of the joints broken so far, constraint object name -> substep."
  ([creature] (build! creature {}))
  ([^Node creature opts]
   (plan/build! creature (plan/plan creature (assoc opts :physics-tab? true)))
   (let [{:keys [plan built]} (segment/record creature)]
     {:creature creature :bodies (:bodies built) :joints (:constraints built)
      :warnings (warnings creature) :simulation (:world plan) :broken (:broken built)})))

(defn ^:api physics-body!
  "Like `cortex.body/body!`, for a creature made in Blender's Physics
  tab: build it (see `build!`, which takes the same `opts`; its
  warnings are logged) and return the creature."
  ([creature] (physics-body! creature {}))
  ([^Node creature opts]
   (build! creature opts)
   creature))

(defn ^:api load-creature
  "Load the .blend file at `path` as a creature, with cortex's reader,
  which leaves every object's Blender physics on its Node (see
  `rigid-body`, `rigid-body-constraint`) and the scene's Rigid Body
  World on the scene Node (see `world-settings`); not yet physical.
  `opts` as for cortex.blender/load-blender-model: {:scene \"Game\"}
  loads that scene."
  (^Node [path] (load-creature path {}))
  (^Node [path opts] (blender/load-blender-model path opts)))
