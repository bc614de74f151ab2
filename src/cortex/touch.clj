;; Generated from org/touch.org by lein tangle: edit the chapter, not this file.
(ns cortex.touch
  "Touch: after a physics step, what each segment touches and how hard,
  read from jBullet's contact manifolds.

  Entry points: `contacts` (every segment's {:touching #{names}
  :impulse n}, given a PhysicsSpace and the names of its bodies),
  `touch-distance`."
  (:import (com.bulletphysics.collision.broadphase Dispatcher)
           (com.bulletphysics.collision.narrowphase ManifoldPoint PersistentManifold)
           (com.bulletphysics.dynamics DynamicsWorld)
           (com.jme3.bullet PhysicsSpace)
           (java.util Map)))

(set! *warn-on-reflection* true)

(def touch-distance
  "How far apart two shapes (with their margins) may be at a contact
  point and still touch, in world units."
  0.005)

(defn- manifold-contact
  "[touching? summed-normal-impulse] of the points of manifold `m`."
  [^PersistentManifold m]
  (let [n (.getNumContacts m)]
    (loop [i 0 touching? false impulse 0.0]
      (if (< i n)
        (let [^ManifoldPoint p (.getContactPoint m i)
              d (.getDistance p)
              ;; the solver only solves points in contact (distance <= 0);
              ;; the others keep the impulse of an earlier step
              imp (if (<= d 0.0) (double (.appliedImpulse p)) 0.0)]
          (recur (inc i)
                 (or touching? (<= d (double touch-distance)) (pos? imp))
                 (+ impulse imp)))
        [touching? impulse]))))

(defn- note
  "`acc` with `other` touched by segment `name` with `impulse` added."
  [acc name other impulse]
  (let [{:keys [touching] :as entry} (get acc name)]
    (assoc acc name {:touching (conj touching other)
                     :impulse (+ (double (:impulse entry)) (double impulse))})))

(defn contacts
  "What each segment touched in the last step of `space`: {name
  {:touching #{other-name ...} :impulse summed-normal-impulse}} for
  every name in `segment-names`, a map (an IdentityHashMap is fastest)
  from each segment's jBullet collision object to its name;
  `object-names` names the other bodies, and an object in neither map is
  named by its string. Segments touching nothing read {:touching #{}
  :impulse 0.0}."
  [^PhysicsSpace space ^Map segment-names ^Map object-names]
  (let [^DynamicsWorld world (.getDynamicsWorld space)
        ^Dispatcher dispatcher (.getDispatcher world)
        n (.getNumManifolds dispatcher)
        start (zipmap (vals segment-names) (repeat {:touching #{} :impulse 0.0}))
        name-of (fn [o] (or (.get segment-names o) (.get object-names o) (str o)))]
    (loop [i 0 acc start]
      (if (< i n)
        (let [^PersistentManifold m (.getManifoldByIndexInternal dispatcher i)
              b0 (.getBody0 m) b1 (.getBody1 m)
              s0 (.get segment-names b0) s1 (.get segment-names b1)
              [touching? impulse] (if (or s0 s1) (manifold-contact m) [false 0.0])]
          (recur (inc i)
                 (if touching?
                   (cond-> acc
                     s0 (note s0 (name-of b1) impulse)
                     s1 (note s1 (name-of b0) impulse))
                   acc)))
        acc))))
