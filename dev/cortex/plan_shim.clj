;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.plan-shim
  "TEMPORARY: a creature's plan (the format of cortex.plan, issue 26)
  read off a creature body! has built, until cortex.plan/plan exists.
  Entry point: `plan`."
  (:require [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.vision :as vision])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Quaternion Vector3f)
           (com.jme3.scene Geometry Node)))

(set! *warn-on-reflection* true)

(defn- v3 [^Vector3f v] [(double (.x v)) (double (.y v)) (double (.z v))])
(defn- q4 [^Quaternion q] [(double (.getX q)) (double (.getY q)) (double (.getZ q)) (double (.getW q))])

(defn- segment [^Geometry g]
  (let [^RigidBodyControl c (.getControl g RigidBodyControl)
        [pos rot] (body/segment-pose g)
        {:keys [source centre moments rotation]} (.getUserData g "cortex.body/mass")]
    {:id (body/segment-name g) :name (body/segment-name g)
     :mass (double (.getMass c)) :friction (double (.getFriction c))
     :restitution (double (.getRestitution c))
     :angular-damping (double (.getAngularDamping c))
     :position (v3 pos) :rotation (q4 rot) :scale (v3 (.getWorldScale g))
     :inertia (if (= :mesh source)
                {:source :mesh :centre (mapv double centre) :moments (mapv double moments)
                 :rotation (when rotation (q4 rotation))}
                {:source :box})
     :shape {:type :hull :points (engine/hull-points (.getCollisionShape c)) :margin 0.0}}))

(defn plan
  "The plan of `creature`, which body! has built."
  [^Node creature]
  (let [{:keys [tolerance]} (body/report creature)]
    {:plan/version 1 :creature (.getName creature) :tolerance tolerance
     :segments (vec (for [^Geometry g (body/segments creature)
                          :when (.getControl g RigidBodyControl)]
                      (segment g)))
     :joints (vec (for [{:keys [name type description segments pivot rotation distances]}
                        (body/joint-records creature)]
                    {:name name :kind :marker :type type :segments segments
                     :description (cond-> description
                                    (instance? Vector3f (:axis description))
                                    (update :axis v3))
                     :pivot (mapv double pivot) :rotation (mapv double rotation)
                     :distances distances}))
     :eyes (vec (for [{:keys [name spec segment ^RigidBodyControl control
                              ^Vector3f offset ^Quaternion turn]} (vision/eye-records creature)]
                  (let [r (.getPhysicsRotation control)]
                    {:name name :segment segment :spec spec
                     :position (v3 (.add (.mult r offset) (.getPhysicsLocation control)))
                     :rotation (q4 (.mult r turn))})))}))
