;; Generated from org/physics-trust.org by lein tangle: edit the chapter, not this file.
(ns cortex.compare
  "cortex's side of scripts/compare/humanoid_compare.py: the humanoid
  and a 100-segment chain dropped in cortex.sim, timed, written as JSON.

  Entry points: `-main` (lein run -m cortex.compare [OUT.json] [runs];
  lein run -m cortex.compare costs [runs]; lein trampoline run -m
  cortex.compare serve: `serve`, runs one at a time as the script asks),
  `step-costs` (where a step's time goes), `json`."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [cortex.body :as body]
            [cortex.engine]
            [cortex.render :as render]
            [cortex.sim :as sim]
            [cortex.blender]
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
  "Build `make`'s creature (sleeping off) in a simulation observing
  `observe` (#{} for nothing; cortex.sim's observations otherwise), step
  warm-up then `steps` steps with no actions. {:steps-per-s (by the wall
  clock, as the Python side times its engines) :cpu-steps-per-s (by the
  stepping thread's CPU time) :fastest (the largest segment speed during
  the warm-up) :sim}."
  [make floor observe warm-up steps]
  (let [c (body/body! ^Node (make) {:sleeping-thresholds [0 0]})
        s (sim/simulation c {:floor {:height floor :friction 1.0} :observe observe})
        speed (fn [o] (apply max (for [[_ {:keys [velocity]}] (:segments o)]
                                   (Math/sqrt (reduce + (map #(* % %) velocity))))))
        fastest (atom 0.0)]
    (dotimes [_ warm-up] (sim/step! s) (swap! fastest max (speed (sim/observe s #{:segments}))))
    (let [t0 (System/nanoTime)
          c0 (cpu-ns)]
      (dotimes [_ steps] (sim/step! s))
      (let [c1 (cpu-ns)
            t1 (System/nanoTime)]
        {:steps-per-s (/ steps (/ (- t1 t0) 1e9))
         :cpu-steps-per-s (/ steps (/ (- c1 c0) 1e9))
         :fastest @fastest
         :sim s}))))

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


(defn- median
  "The middle of `xs` (the upper of the two for an even count): this
  chapter comes before the benchmark chapter's cortex.bench/median."
  [xs]
  (nth (sort xs) (quot (count xs) 2)))

(defn- humanoid [] (util/load-blender-model "test/fixtures/humanoid/humanoid.blend"))

(defn- chain-100 []
  ((requiring-resolve 'cortex.bench.creatures/creature)
   ((requiring-resolve 'cortex.bench.creatures/chain) 100) 1.0))

(defn- torso-height
  "The torso's centre of mass above the floor at `floor`: both humanoids'
  torso origins are MuJoCo's torso centre of mass."
  [obs floor]
  (- (double (second (get-in obs [:segments "torso" :position]))) floor))

(defn- mean-height
  "The segments' mean height above the floor at `floor`."
  [obs floor]
  (/ (reduce + (for [[_ {[_ y] :position}] (:segments obs)] (- (double y) floor)))
     (count (:segments obs))))

(def ^:private settings
  (str cortex.engine/solver-iterations " solver iterations, projection"
       ", cones as 6-DOF, mesh mass properties, sleeping off"))

(defn measure
  "The numbers humanoid_compare.py reads (--cortex-json), over `runs`
  runs (steps a second by the stepping thread's CPU time)."
  [runs]
  (let [run (fn [make floor] (timed-run make floor #{} 1000 10000))
        h (vec (repeatedly runs #(run humanoid floor-z)))
        c (vec (repeatedly runs #(run chain-100 -0.2)))
        final (fn [r] (sim/observe (:sim r) #{:segments}))]
    {:engine (str "cortex (" cortex.engine/label ")")
     :image (picture! (:sim (peek h)) (str "out/compare/cortex-humanoid-" (name cortex.engine/name) ".png"))
     :chain_image (picture! (:sim (peek c)) (str "out/compare/cortex-chain-" (name cortex.engine/name) ".png"))
     :settings settings
     :humanoid {:steps_per_s (median (map :cpu-steps-per-s h))
                :final_torso_height (torso-height (final (peek h)) floor-z)
                :max_speed (apply max (map :fastest h))}
     :chain {:steps_per_s (median (map :cpu-steps-per-s c))
             :final_height (median (for [r c] (mean-height (final r) -0.2)))}}))

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
   ["lying, no projection" {:floor {:height floor-z :friction 1.0} :solver {:projection false}}]
   ["lying, 1 iteration, no projection" {:floor {:height floor-z :friction 1.0}
                                         :solver {:iterations 1 :projection false}}]])

(def ^:private cost-humanoids
  "The humanoids step-costs measures: the clipped one, and the one built
  as MuJoCo's is."
  ["test/fixtures/humanoid/humanoid.blend" "test/fixtures/strangers/humanoid.blend"])

(defn step-costs
  "Microseconds of CPU a step of each of `cost-humanoids` takes in each
  of `cost-settings` (sleeping off; 1,000 steps, then 5,000 timed), the
  median of `runs` interleaved runs: [[label us-clipped us-mujoco-shaped] ...]."
  [runs]
  (let [one (fn [path opts]
              (let [c (body/body! ^Node (util/load-blender-model path) {:sleeping-thresholds [0 0]})
                    s (sim/simulation c (assoc opts :observe #{}))]
                (dotimes [_ 1000] (sim/step! s))
                (let [t0 (cpu-ns)]
                  (dotimes [_ 5000] (sim/step! s))
                  (/ (- (cpu-ns) t0) 5000 1e3))))
        cases (for [path cost-humanoids [_ opts] cost-settings] [path opts])
        timings (apply map vector (for [_ (range runs)] (mapv #(apply one %) cases)))
        medians (vec (map median timings))
        n (count cost-settings)]
    (vec (for [[i [label]] (map-indexed vector cost-settings)]
           [label (medians i) (medians (+ n i))]))))

(def serve-cases
  "What `serve` drops: name -> [make floor height]. The humanoid built
  as MuJoCo's is (one closed piece per MuJoCo geom, overlapping at the
  joints) and the clipped one stand with their feet at 0, MuJoCo's floor
  under them (MuJoCo's start); the chain lies with its lowest point 1 m
  above its floor."
  {"humanoid-mujoco" [#(util/load-blender-model "test/fixtures/strangers/humanoid.blend")
                      floor-z torso-height]
   "humanoid-clipped" [humanoid floor-z torso-height]
   "chain-100" [chain-100 -0.2 mean-height]})

(def ^:private observed
  "What a simulation \"with observations\" returns each step."
  #{:joints :segments :touch})

(defn- engine-jars
  "The jars the engine's classes came from (their names carry the
  versions): jME's Bullet API and, on jBullet, jBullet itself."
  []
  (vec (for [c ["com.jme3.bullet.PhysicsSpace" "com.bulletphysics.dynamics.DiscreteDynamicsWorld"]
             :let [k (try (Class/forName c) (catch ClassNotFoundException _ nil))]
             :when k]
         (.getName (io/file (.getPath (.getLocation (.getCodeSource (.getProtectionDomain ^Class k)))))))))

(defn serve
  "Runs one at a time, as humanoid_compare.py asks on standard input, so
  that it can interleave them with MuJoCo's and PyBullet's (and the other
  engine's JVM). Every answer is one line, \"@@ \" and JSON (other lines
  on standard output are not answers). First {:ready true ...}; then, per
  line read:
    run CASE off|observed WARMUP STEPS   one `timed-run` of `serve-cases`'
                                         CASE, without or with observations
    picture CASE FILE                    the last run of CASE as it lies, a PNG
    quit"
  []
  (let [kept (atom {})
        say (fn [m] (println (str "@@ " (json m))) (flush))]
    (say {:ready true :engine cortex.engine/label :name cortex.engine/name :settings settings
          :java (System/getProperty "java.version") :jars (engine-jars)})
    (loop []
      (when-let [line (read-line)]
        (let [[cmd a b c d] (str/split (str/trim line) #"\s+")]
          (when-not (= "quit" cmd)
            (try
              (case cmd
                "run" (let [[make floor height] (or (serve-cases a)
                                                    (throw (ex-info (str "no case " a) {})))
                            r (timed-run make floor (if (= "observed" b) observed #{})
                                         (Long/parseLong c) (Long/parseLong d))
                            obs (sim/observe (:sim r) #{:segments})]
                        (when-let [old (@kept a)] (sim/destroy! old))
                        (swap! kept assoc a (:sim r))
                        (say {:case a :observe b :steps_per_s (:steps-per-s r)
                              :cpu_steps_per_s (:cpu-steps-per-s r) :max_speed (:fastest r)
                              :final_height (height obs floor)}))
                "picture" (say {:case a :picture (str (picture! (or (@kept a)
                                                                    (throw (ex-info (str "no run of " a) {})))
                                                                b))})
                (say {:error (str "unknown command: " line)}))
              (catch Throwable t (say {:error (str t)})))
            (recur)))))))

(defn -main
  "lein run -m cortex.compare [OUT.json] [runs]
  lein run -m cortex.compare costs [runs]
  lein trampoline run -m cortex.compare serve"
  [& [out runs]]
  (cond
    (= "serve" out) (do (serve) (shutdown-agents) (System/exit 0))
    (= "costs" out)
    (do (println cortex.engine/name "- microseconds a step of the humanoid, sleeping off:")
        (println (format "%-40s %8s %14s" "" "clipped" "MuJoCo-shaped"))
        (doseq [[label a b] (step-costs (Long/parseLong (or runs "3")))]
          (println (format "%-40s %8.1f %14.1f" label (double a) (double b))))
        (shutdown-agents))
    :else
    (let [out (or out "out/bench/cortex-humanoid.json")
          m (measure (Long/parseLong (or runs "3")))]
      (io/make-parents out)
      (spit out (json m))
      (println (json m))
      (println "wrote" out)
      (shutdown-agents))))
