;; Generated from org/physics-trust.org by lein tangle: edit the chapter, not this file.
(ns cortex.compare
  "cortex's side of scripts/compare/humanoid_compare.py: the humanoid
  and a 100-segment chain dropped in cortex.sim, timed, written as JSON.

  Entry points: `-main` (lein run -m cortex.compare [OUT.json] [runs];
  lein run -m cortex.compare costs [runs]), `step-costs` (where a
  step's time goes), `json`."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [cortex.body :as body]
            [cortex.engine]
            [cortex.render :as render]
            [cortex.sim :as sim]
            [cortex.util :as util])
  (:import (java.lang.management ManagementFactory)
           (com.jme3.scene Node)))

(set! *warn-on-reflection* true)

(def ^:private floor-z
  "Where MuJoCo's floor is under the fixture (its feet at 0)."
  -0.10703)

(defn- cpu-ns ^long []
  (.getCurrentThreadCpuTime (ManagementFactory/getThreadMXBean)))

(defn- timed-run
  "Build `make`'s creature (sleeping off), step warm-up then `steps`
  steps; [steps-per-cpu-second final-observation fastest-speed]."
  [make floor warm-up steps]
  (let [c (body/body! ^Node (make) {:sleeping-thresholds [0 0]})
        s (sim/simulation c {:floor {:height floor :friction 1.0} :observe #{}})
        speed (fn [o] (apply max (for [[_ {:keys [velocity]}] (:segments o)]
                                   (Math/sqrt (reduce + (map #(* % %) velocity))))))
        fastest (atom 0.0)]
    (dotimes [_ warm-up] (sim/step! s) (swap! fastest max (speed (sim/observe s #{:segments}))))
    (let [t0 (cpu-ns)]
      (dotimes [_ steps] (sim/step! s))
      (let [t (/ (- (cpu-ns) t0) 1e9)]
        [(/ steps t) (sim/observe s #{:segments}) @fastest s]))))

(defn- picture!
  "Draw simulation `s` as it is now, offscreen, from the side (as
  `cortex.sim/world` places its camera), into the PNG `file`; `file`."
  [s file]
  ;; creatures made in code (the chain) have no material to draw with
  (.depthFirstTraversal
   ^com.jme3.scene.Node (:root s)
   (reify com.jme3.scene.SceneGraphVisitor
     (visit [_ spatial]
       (when (and (instance? com.jme3.scene.Geometry spatial)
                  (nil? (.getMaterial ^com.jme3.scene.Geometry spatial)))
         (.setMaterial ^com.jme3.scene.Geometry spatial
                       (doto (com.jme3.material.Material. (util/asset-manager)
                                                          "Common/MatDefs/Light/Lighting.j3md")
                         (.setBoolean "UseMaterialColors" true)
                         (.setColor "Diffuse" com.jme3.math.ColorRGBA/Orange)
                         (.setColor "Ambient" com.jme3.math.ColorRGBA/Brown)))))))
  (let [dir (str (java.nio.file.Files/createTempDirectory
                  "cortex-compare" (make-array java.nio.file.attribute.FileAttribute 0)))
        ;; where the creature lies now (its Geometries brought up to date
        ;; from its bodies before the world takes the scene)
        ^com.jme3.bounding.BoundingBox b (do (sim/sync! s)
                                             (.getWorldBound ^com.jme3.scene.Node (:creature s)))
        c (.getCenter b)
        r (max 1.2 (.getXExtent b) (.getZExtent b))
        frame-on (fn [^com.jme3.app.SimpleApplication w]
                   ;; a sky, and the camera as far off as the creature is long
                   (.setBackgroundColor (.getViewPort w) (com.jme3.math.ColorRGBA. 0.55 0.7 0.9 1))
                   (doto (.getCamera w)
                     (.setLocation (.add c (com.jme3.math.Vector3f. (* 0.6 r) (* 0.9 r) (* 2.2 r))))
                     (.lookAt c com.jme3.math.Vector3f/UNIT_Y)))
        w (sim/world s (constantly nil) frame-on)]
    (render/record! w dir {:progress nil})
    (render/run-offscreen! w 3 {:size [480 360]})
    (io/make-parents file)
    (io/copy (io/file dir "frame-000003.png") (io/file file))
    file))

(defn- median [xs] (nth (sort xs) (quot (count xs) 2)))

(defn measure
  "The numbers humanoid_compare.py reads, over `runs` runs."
  [runs]
  (let [humanoid #(util/load-blender-model "test/fixtures/humanoid/humanoid.blend")
        chain #((requiring-resolve 'cortex.bench.creatures/creature)
                ((requiring-resolve 'cortex.bench.creatures/chain) 100) 1.0)
        h (vec (repeatedly runs #(timed-run humanoid floor-z 1000 10000)))
        c (vec (repeatedly runs #(timed-run chain -0.2 1000 10000)))
        height (fn [obs seg floor] (- (double (second (get-in obs [:segments seg :position]))) floor))]
    {:engine (str "cortex (" cortex.engine/label ")")
     :image (picture! (nth (peek h) 3) (str "out/compare/cortex-humanoid-" (name cortex.engine/name) ".png"))
     :chain_image (picture! (nth (peek c) 3) (str "out/compare/cortex-chain-" (name cortex.engine/name) ".png"))
     :settings (str cortex.engine/solver-iterations " solver iterations, projection"
                    ", cones as 6-DOF, mesh mass properties, sleeping off")
     :humanoid {:steps_per_s (median (map first h))
                :final_torso_height (height (second (peek h)) "torso" floor-z)
                :max_speed (apply max (map #(nth % 2) h))}
     :chain {:steps_per_s (median (map first c))
             :final_height (median (for [[_ obs] c]
                                     (/ (reduce + (for [[_ {[_ y] :position}] (:segments obs)] (+ y 0.2)))
                                        (count (:segments obs)))))}}))

(defn json
  "`x` (maps, sequences, strings, keywords, numbers, nil) as JSON text."
  [x]
  (cond (map? x) (str "{" (str/join ", " (for [[k v] x] (str (json (name k)) ": " (json v)))) "}")
        (sequential? x) (str "[" (str/join ", " (map json x)) "]")
        (keyword? x) (json (name x))
        (string? x) (str "\"" (str/replace x "\"" "\\\"") "\"")
        (nil? x) "null"
        :else (str x)))

(def ^:private cost-settings
  "What step-costs takes apart: the humanoid floating (no contacts) or
  lying where it fell, at the defaults or at one iteration without
  projection."
  [["floating, defaults" {:gravity [0 0 0]}]
   ["floating, 1 iteration, no projection" {:gravity [0 0 0] :solver {:iterations 1 :projection false}}]
   ["lying, defaults" {:floor {:height floor-z :friction 1.0}}]
   ["lying, 1 iteration, no projection" {:floor {:height floor-z :friction 1.0}
                                         :solver {:iterations 1 :projection false}}]])

(defn step-costs
  "Microseconds of CPU a step of the humanoid takes in each of
  `cost-settings` (sleeping off; 1,000 steps, then 5,000 timed), the
  median of `runs` interleaved runs: [[label us] ...]."
  [runs]
  (let [one (fn [opts]
              (let [c (body/body! ^Node (util/load-blender-model "test/fixtures/humanoid/humanoid.blend")
                                  {:sleeping-thresholds [0 0]})
                    s (sim/simulation c (assoc opts :observe #{}))]
                (dotimes [_ 1000] (sim/step! s))
                (let [t0 (cpu-ns)]
                  (dotimes [_ 5000] (sim/step! s))
                  (/ (- (cpu-ns) t0) 5000 1e3))))
        timings (apply map vector (for [_ (range runs)] (mapv (comp one second) cost-settings)))]
    (mapv (fn [[label] ts] [label (median ts)]) cost-settings timings)))

(defn -main
  "lein run -m cortex.compare [OUT.json] [runs]
  lein run -m cortex.compare costs [runs]"
  [& [out runs]]
  (if (= "costs" out)
    (do (println cortex.engine/name "- microseconds a step of the humanoid, sleeping off:")
        (doseq [[label us] (step-costs (Long/parseLong (or runs "3")))]
          (println (format "%-40s %6.1f" label (double us))))
        (shutdown-agents))
    (let [out (or out "out/bench/cortex-humanoid.json")
          m (measure (Long/parseLong (or runs "3")))]
      (io/make-parents out)
      (spit out (json m))
      (println (json m))
      (println "wrote" out)
      (shutdown-agents))))
