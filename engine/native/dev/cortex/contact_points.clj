;; Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
(ns cortex.contact-points
  "The points of a space's contact manifolds after its last step, read
  from native Bullet: a measuring tool (see the Physics tab chapter,
  \"Stepping a fixture with its contacts\")."
  (:import (com.jme3.bullet PhysicsSpace)
           (com.jme3.bullet.collision ManifoldPoints PersistentManifolds PhysicsCollisionObject)
           (com.jme3.math Vector3f)))

(set! *warn-on-reflection* true)

(defn- xyz [^Vector3f v] [(double (.x v)) (double (.y v)) (double (.z v))])

(defn points
  "The manifolds of `space` that hold points: [{:a :b :points [{:on-a
  :on-b :normal (on B) :distance :impulse :lateral :life}]}], in the
  space's order, the bodies named by `name-of` (of a jME body)."
  [^PhysicsSpace space name-of]
  (vec (for [^long m (.listManifoldIds space)
             :let [n (PersistentManifolds/countPoints m)]
             :when (pos? n)]
         {:a (name-of (PhysicsCollisionObject/findInstance (PersistentManifolds/getBodyAId m)))
          :b (name-of (PhysicsCollisionObject/findInstance (PersistentManifolds/getBodyBId m)))
          :points (vec (for [i (range n)
                             :let [p (PersistentManifolds/getPointId m i)
                                   v (fn [f] (let [out (Vector3f.)] (f p out) (xyz out)))]]
                         {:on-a (v #(ManifoldPoints/getPositionWorldOnA %1 %2))
                          :on-b (v #(ManifoldPoints/getPositionWorldOnB %1 %2))
                          :normal (v #(ManifoldPoints/getNormalWorldOnB %1 %2))
                          :distance (double (ManifoldPoints/getDistance1 p))
                          :impulse (double (ManifoldPoints/getAppliedImpulse p))
                          :lateral (double (ManifoldPoints/getAppliedImpulseLateral1 p))
                          :life (ManifoldPoints/getLifeTime p)}))})))
