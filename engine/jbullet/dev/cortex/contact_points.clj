;; Generated from org/physics-tab.org by lein tangle: edit the chapter, not this file.
(ns cortex.contact-points
  "The points of a space's contact manifolds after its last step, read
  from jBullet: a measuring tool (see the Physics tab chapter, \"Stepping
  a fixture with its contacts\")."
  (:import (com.bulletphysics.collision.dispatch CollisionObject)
           (com.bulletphysics.collision.narrowphase ManifoldPoint PersistentManifold)
           (com.jme3.bullet PhysicsSpace)
           (javax.vecmath Vector3f)))

(set! *warn-on-reflection* true)

(defn- xyz [^Vector3f v] [(double (.x v)) (double (.y v)) (double (.z v))])

(defn points
  "The manifolds of `space` that hold points: [{:a :b :points [{:on-a
  :on-b :normal (on B) :distance :impulse :lateral :life}]}], in the
  dispatcher's order, the bodies named by `name-of` (of a jME body)."
  [^PhysicsSpace space name-of]
  (let [d (.getDispatcher (.getDynamicsWorld space))]
    (vec (for [i (range (.getNumManifolds d))
               :let [^PersistentManifold m (.getManifoldByIndexInternal d i)]
               :when (pos? (.getNumContacts m))]
           {:a (name-of (.getUserPointer ^CollisionObject (.getBody0 m)))
            :b (name-of (.getUserPointer ^CollisionObject (.getBody1 m)))
            :points (vec (for [j (range (.getNumContacts m))
                               :let [^ManifoldPoint p (.getContactPoint m j)]]
                           {:on-a (xyz (.getPositionWorldOnA p (Vector3f.)))
                            :on-b (xyz (.getPositionWorldOnB p (Vector3f.)))
                            :normal (xyz (.normalWorldOnB p))
                            :distance (double (.getDistance p))
                            :impulse (double (.appliedImpulse p))
                            :lateral (double (.appliedImpulseLateral1 p))
                            :life (.getLifeTime p)}))}))))
