;; Generated from org/touch.org by lein tangle: edit the chapter, not this file.
(ns cortex.touch
  "Touch: after a physics step, what each segment touches and how hard,
  read from the engine's contact manifolds.

  Entry points: `contacts` (every segment's {:touching #{names}
  :impulse n}, given a PhysicsSpace and the names of its bodies),
  `touch-distance`."
  (:require [cortex.engine :as engine])
  (:import (com.jme3.bullet PhysicsSpace)
           (java.util Map)))

(set! *warn-on-reflection* true)

(def touch-distance
  "How far apart two shapes (with their margins) may be at a contact
  point and still touch, in world units."
  0.005)

(defn- note
  "`acc` with `other` touched by segment `name` with `impulse` added."
  [acc name other impulse]
  (let [{:keys [touching] :as entry} (get acc name)]
    (assoc acc name {:touching (conj touching other)
                     :impulse (+ (double (:impulse entry)) (double impulse))})))

(defn untouched
  "What `contacts` reads for segments touching nothing, for every name
  in `segment-names` (as `contacts` takes them): a simulation keeps it,
  since it is the same at every step."
  [^Map segment-names]
  (zipmap (vals segment-names) (repeat {:touching #{} :impulse 0.0})))

(defn ^:api contacts
  "What each segment touched in the last step of `space`: {name
  {:touching #{other-name ...} :impulse summed-normal-impulse}} for
  every name in `segment-names`, a map (an IdentityHashMap is fastest)
  from each segment's collision object (cortex.engine/collision-object)
  to its name;
  `object-names` names the other bodies, and an object in neither map is
  named by its string. Segments touching nothing read {:touching #{}
  :impulse 0.0}; `start`, when given, is (untouched segment-names)."
  ([space segment-names object-names]
   (contacts space segment-names object-names (untouched segment-names)))
  ([^PhysicsSpace space ^Map segment-names ^Map object-names start]
   (let [name-of (fn [o] (or (.get segment-names o) (.get object-names o) (str o)))]
     (engine/reduce-contacts
      space touch-distance #(.containsKey segment-names %)
      (fn [acc b0 b1 touching? impulse]
        (if touching?
          (let [s0 (.get segment-names b0) s1 (.get segment-names b1)]
            (cond-> acc
              s0 (note s0 (name-of b1) impulse)
              s1 (note s1 (name-of b0) impulse)))
          acc))
      start))))
