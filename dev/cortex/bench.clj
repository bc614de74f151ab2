;; Generated from org/bench.org by lein tangle: edit the chapter, not this file.
(ns cortex.bench
  "lein bench: how long cortex takes to build bodies (split into hulls,
  joint search and joint creation) and how fast it simulates them
  against bare Bullet, with the growth of each with creature size.
  Prints tables and writes them to target/bench/ as CSV and EDN."
  (:require [clojure.java.io :as io]
            [clojure.pprint :as pprint]
            [clojure.string :as str]
            [cortex.bench.creatures :as creatures]
            [cortex.blender-bench :as blender-bench]
            [cortex.body :as body]
            [cortex.sim :as sim]
            ;; the eyes' rows see through cortex.sight, which cortex.sim
            ;; does not load
            [cortex.sight]
            [cortex.blender]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.bounding BoundingBox)
           (com.jme3.bullet PhysicsSpace)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.bullet.objects PhysicsRigidBody)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Node)
           (java.lang.management ManagementFactory)))

(set! *warn-on-reflection* true)

(defn median
  "The middle value of `xs` (the mean of the two middle ones when there
  is an even number of them), or nil when there are none."
  [xs]
  (let [s (vec (sort xs)) n (count s)]
    (cond (zero? n) nil
          (odd? n) (s (quot n 2))
          :else (/ (+ (s (dec (quot n 2))) (s (quot n 2))) 2.0))))

(defn fit-exponent
  "The slope k of the least-squares line through (log n, log t) for the
  [n t] `points`: t grows like n^k. Nil with fewer than two sizes or a
  non-positive time."
  [points]
  (let [ps (filter (fn [[n t]] (and (pos? n) t (pos? t))) points)
        xs (map #(Math/log (double (first %))) ps)
        ys (map #(Math/log (double (second %))) ps)
        k (count ps)]
    (when (and (>= k 2) (> (count (distinct xs)) 1))
      (let [mx (/ (reduce + xs) k) my (/ (reduce + ys) k)]
        (/ (reduce + (map #(* (- %1 mx) (- %2 my)) xs ys))
           (reduce + (map #(let [d (- % mx)] (* d d)) xs)))))))

(defn nlogn-exponent
  "The exponent `fit-exponent` finds for a cost of exactly n log n over
  the sizes `ns`: the most a cost no worse than n log n should show."
  [ns]
  (fit-exponent (for [n ns] [n (* n (Math/log n))])))

(defn- now ^long [] (System/nanoTime))

(defn- ms-since [^long t0] (/ (- (System/nanoTime) t0) 1e6))

(defn- cpu-now
  "CPU time the calling thread has used, in ns: unlike the wall clock,
  it does not count the time other programs had the processor."
  ^long []
  (.getCurrentThreadCpuTime (ManagementFactory/getThreadMXBean)))

(defn- stamp
  "The wall clock and the thread's CPU clock now, [wall-ns cpu-ns]."
  []
  [(now) (cpu-now)])

(defn timed
  "Call (f); return [milliseconds-it-took value]."
  [f]
  (let [t0 (now) v (f)] [(ms-since t0) v]))

(defn- settle!
  "Collect garbage before a measured run, so the run does not pay for
  the garbage of the one before it."
  []
  (System/gc)
  (Thread/sleep 20))

(defn- body-fn
  "The function cortex.body currently defines as `sym`, or nil."
  [sym]
  (some-> (ns-resolve 'cortex.body sym) deref))

(defn find-targets!
  "The pair of segments each of `joints` joins, found the way joints!
  finds them: with one segment index for the creature when cortex.body
  has one, else with joint-targets, joint by joint."
  [^Node creature joints]
  (.updateGeometricState creature)
  (let [index-of (body-fn 'segment-index)
        near (body-fn 'targets-near)]
    (if (and index-of near)
      (let [index (index-of creature)]
        (mapv #(near index %) joints))
      (mapv #(body/joint-targets creature %) joints))))

(defn build-splits!
  "Build `creature`'s body the way body! does, timing each part: a map
  of :physical (hulls and rigid bodies), :targets (finding every joint's
  two segments) and :connect (making the Bullet joints), in ms, and the
  number of :joints."
  [^Node creature]
  (let [[physical _] (timed #(body/physical! creature))
        joints (vec (body/joints creature))
        [targets pairs] (timed #(find-targets! creature joints))
        [connect _] (timed #(mapv (fn [joint [a b]] (body/connect a b joint)) joints pairs))]
    {:physical physical :targets targets :connect connect :joints (count joints)}))

(defn measure-build!
  "Median build times of the creatures `make` returns (a fresh, unbuilt
  creature per call) over `runs` runs after `warmup` runs: :physical,
  :targets, :connect, their :sum and :body (body! timed whole), in ms."
  [make {:keys [warmup runs]}]
  (let [run! (fn []
               (settle!)
               (let [s (build-splits! (make))
                     c (make)
                     _ (settle!)
                     [whole _] (timed #(body/body! c))]
                 (assoc s :sum (+ (:physical s) (:targets s) (:connect s)) :body whole)))]
    (dotimes [_ warmup] (run!))
    (let [samples (vec (repeatedly runs run!))]
      (into {:runs runs :joints (:joints (first samples))}
            (for [k [:physical :targets :connect :sum :body]]
              [k (median (map k samples))])))))

(def blender-creatures
  "The creatures designed in Blender, by name."
  {"worm" "Models/test-creature/worm.blend"
   "hand" "Models/test-creature/hand.blend"})

(defn blender-loader
  "The function that loads a .blend file as a creature, or nil when
  cortex has none yet."
  []
  (some #(try (some-> (requiring-resolve %) deref) (catch Throwable _ nil))
        ['cortex.util/load-blender-model 'cortex.blender/load-blender-model]))

(defn blender-maker
  "A function making a fresh copy of the Blender creature `name` per
  call, or nil when it cannot be loaded; the reason is in the map's
  :skipped."
  [name]
  (if-let [load (blender-loader)]
    (try (let [path (blender-creatures name)]
           (load path)
           {:make #(load path)})
         (catch Throwable t {:skipped (str "cannot load: " (ex-message t))}))
    {:skipped "no Blender reader in cortex yet"}))

(def earth
  "Gravity, in units per second squared."
  (Vector3f. 0 -9.81 0))

(def fps
  "Steps per simulated second, in both the cortex world and bare Bullet."
  60)

(defn floor-under
  "A static box whose top lies one unit below the lowest point of
  `creature` and reaches five units past it on every side."
  [^Node creature]
  (.updateGeometricState creature)
  (let [^BoundingBox b (.getWorldBound creature)
        c (.getCenter b)
        top (- (.y c) (.getYExtent b) 1)]
    (util/box (+ 5 (.getXExtent b)) 0.5 (+ 5 (.getZExtent b))
              :position (Vector3f. (.x c) (- top 0.5) (.z c))
              :mass 0 :name "floor")))

(defn throughput
  "Simulated seconds per second of the clock `clock` (0 for wall, 1 for
  CPU) from `stamps`, the [wall-ns cpu-ns] at the start of each of a
  run's steps of 1/fps s, leaving out the first tenth as warm-up."
  ([stamps] (throughput stamps 0))
  ([stamps clock]
   (let [skip (quot (count stamps) 10)
         first-t (nth (nth stamps skip) clock)
         last-t (nth (peek stamps) clock)
         steps (- (count stamps) 1 skip)]
     (when (and (pos? steps) (> last-t first-t))
       (/ (/ steps (double fps)) (/ (- last-t first-t) 1e9))))))

(defn- body-states
  "Where each rigid body of `creature` is and how it is turned: the
  numbers two equal simulations must agree on."
  [creature]
  (vec (for [^Geometry g (body/segments creature)
             :let [^RigidBodyControl c (.getControl g RigidBodyControl)]
             :when c]
         [(.getPhysicsLocation c) (.getPhysicsRotation c)])))

(defn cortex-run!
  "Build a creature from `make`, drop it on a floor in a cortex world and
  run `frames` frames headless. Returns the frames' :stamps and the
  bodies' final :states."
  [make frames]
  (let [creature (doto ^Node (make) (body/body!))
        stamps (java.util.ArrayList.)
        w (world/world (util/nodify [creature (floor-under creature)]) {}
                       #(world/set-gravity % earth)
                       (fn [_ _] (.add stamps (stamp))))]
    (world/run-world! w frames)
    {:stamps (vec stamps) :states (body-states creature)}))

(defn bare-space
  "A Bullet space made as BulletAppState makes one and set up as
  cortex's worlds are: the step loop's own (`cortex.sim/physics-space`)."
  ^PhysicsSpace []
  (sim/physics-space))

(defn- step-bare!
  "Put the bodies under `root` into a new bare space, under earth's
  gravity as a world puts them, and step it `frames` times by 1/fps s,
  writing a stamp before each step into `stamps`."
  [root frames ^objects stamps]
  (let [space (bare-space)
        step (float (/ 1 fps))]
    (cortex.engine/add-all! space root)
    (.setGravity space earth)
    (doseq [^PhysicsRigidBody b (.getRigidBodyList space)]
      (.setGravity b earth)
      (.activate b))
    (dotimes [i frames]
      (aset stamps i (stamp))
      (.update space step)
      (.distributeEvents space))
    (.destroy space)))

(defn bare-run!
  "Build a creature from `make`, put it and a floor into a bare Bullet
  space with no world and no scene graph, and step the space `frames`
  times by 1/fps s. Returns the :stamps of the steps and the bodies'
  final :states."
  [make frames]
  (let [creature (doto ^Node (make) (body/body!))
        stamps (object-array frames)]
    (step-bare! (util/nodify [creature (floor-under creature)]) frames stamps)
    {:stamps (vec stamps) :states (body-states creature)}))

(defn measure-sim!
  "Median throughput (simulated s per wall s) of the creatures `make`
  returns, in a cortex world (:cortex) and in bare Bullet (:bare), over
  `runs` runs of `frames` frames each after one warm-up of each; their
  :ratio; the same per CPU second of the stepping thread (:cortex-cpu,
  :bare-cpu, :cpu-ratio); and :same? when both simulated exactly the
  same motion. Runs alternate, world then bare, so that a change in
  the machine's load falls on both."
  [make {:keys [frames runs]}]
  (let [one! (fn [run!] (settle!) (run! make frames))]
    (one! cortex-run!)
    (one! bare-run!)
    (let [pairs (vec (repeatedly runs #(vector (one! cortex-run!) (one! bare-run!))))
          speed (fn [side clock] (median (map #(throughput (:stamps (side %)) clock) pairs)))
          [cortex bare cortex-cpu bare-cpu] (for [clock [0 1] side [first second]]
                                              (speed side clock))]
      {:cortex cortex :bare bare :ratio (/ cortex bare)
       :cortex-cpu cortex-cpu :bare-cpu bare-cpu :cpu-ratio (/ cortex-cpu bare-cpu)
       :frames frames :runs runs
       :same? (every? (fn [[a b]] (= (:states a) (:states b))) pairs)})))

(defn step-loop-run!
  "Build a creature from `make` and step it `frames` times by 1/fps s
  over a floor one unit below it: in bare Bullet when `observe` is nil,
  else in a cortex.sim simulation observing `observe`. Returns the
  :stamps of the steps and the bodies' final :states."
  [make frames observe]
  (let [creature (doto ^Node (make) (body/body!))
        ^Geometry under (floor-under creature)
        height (+ (.y (.getWorldTranslation under)) 0.5)
        stamps (object-array frames)]
    (if observe
      (let [s (sim/simulation creature {:floor height :observe observe})]
        (dotimes [i frames] (aset stamps i (stamp)) (sim/step! s))
        (sim/destroy! s))
      (step-bare! (util/nodify [creature (sim/floor height)]) frames stamps))
    {:stamps (vec stamps) :states (body-states creature)}))

(defn measure-step-loop!
  "Median simulated seconds per CPU second of bare Bullet (:bare-cpu),
  of cortex.sim observing nothing (:none-cpu) and everything
  (:all-cpu), their ratios to bare, and :same? when all three computed
  the same motion; `runs` rounds of `frames` frames after a warm-up."
  [make {:keys [frames runs]}]
  (let [kinds [nil #{} sim/all-observations]
        one! (fn [observe] (settle!) (step-loop-run! make frames observe))]
    (run! one! kinds)
    (let [rounds (vec (repeatedly runs #(mapv one! kinds)))
          speed (fn [i] (median (map #(throughput (:stamps (nth % i)) 1) rounds)))
          [bare none all] (map speed [0 1 2])]
      {:bare-cpu bare :none-cpu none :all-cpu all
       :none-ratio (/ none bare) :all-ratio (/ all bare)
       :frames frames :runs runs
       :same? (every? #(apply = (map :states %)) rounds)})))

(declare progress)

(defn- eyed-worm
  "The worm with eyes, built, with `n` eyes (2 of its own, more copied
  from its right eye)."
  [n]
  (let [^Node c (util/load-blender-model "Models/test-creature/worm-eyes.blend")
        ^Node eyes (.getChild c "eyes")
        ^Node right (.getChild eyes "right-eye")]
    (doseq [i (range 3 (inc n))]
      (.attachChild eyes (doto (.clone right) (.setName (str "eye-" i)))))
    (body/body! c)))

(defn- crawl
  "The worm's crawling gait at time `t` (see the simulation chapter):
  it keeps the worm awake, so that every step's physics is paid for."
  [t]
  (let [phase (mod (* 1.5 (max 0.0 (- (double t) 0.5))) 1.0)]
    {"worm-joint" {:target (* 0.6 (if (< phase 0.8) (/ phase 0.8) (/ (- 1 phase) 0.2)))}}))

(defn- steps-per-second
  "Wall-clock steps a second of a simulation of `creature` made with
  `opts`, crawling: the median of three runs of `frames` steps, after
  `frames`/2 steps of warm-up."
  [creature opts frames]
  (let [s (sim/simulation creature (merge {:floor 0} opts))
        step! #(sim/step! s (crawl (sim/sim-time s)))]
    (try
      (dotimes [_ (quot frames 2)] (step!))
      (median (repeatedly 3 #(let [t0 (now)]
                               (dotimes [_ frames] (step!))
                               (/ frames (/ (ms-since t0) 1000.0)))))
      (finally (sim/destroy! s)))))

(defn run-eyes!
  "Eye rows: for 1 and 4 eyes at 64x64 and 128x128 (RGB and depth),
  eye images and steps a second, against the same worm stepped without
  eyes; `frames` steps each."
  [frames]
  (let [_ (do (progress "eyes" "warming up")
              (steps-per-second (eyed-worm 1) {:eyes {"right-eye" {}}} frames))
        plain (do (progress "eyes" "without")
                  (steps-per-second (eyed-worm 2) {} (* 4 frames)))]
    (vec (for [size [64 128] n [1 4]]
           (let [_ (progress "eyes" (str n " x " size "x" size))
                 names (take n ["right-eye" "left-eye" "eye-3" "eye-4"])
                 steps (steps-per-second (eyed-worm n)
                                         {:eyes (into {} (for [e names] [e {:resolution [size size]}]))}
                                         frames)]
             {:eyes n :size size :images-per-s (* n steps) :steps-per-s steps
              :step-ms (/ 1000.0 steps) :plain-step-ms (/ 1000.0 plain)
              :eye-frame-ms (/ (- (/ 1000.0 steps) (/ 1000.0 plain)) n)})))))

(defn eyes-table
  "The eye rows as a text table."
  [rows]
  (str "eyes (worm-eyes, RGB + depth each step, wall clock)\n"
       (format "%-5s %-8s %12s %10s %10s %14s %14s\n" "eyes" "size" "images/s" "steps/s"
               "step ms" "no-eyes ms" "ms/eye frame")
       (apply str (for [{:keys [eyes size images-per-s steps-per-s step-ms plain-step-ms eye-frame-ms]} rows]
                    (format "%-5d %-8s %12.0f %10.0f %10.3f %14.3f %14.3f\n" eyes (str size "x" size)
                            (double images-per-s) (double steps-per-s) (double step-ms)
                            (double plain-step-ms) (double eye-frame-ms))))))

(defn- heap-used
  "Bytes of heap in use now, garbage included."
  ^long []
  (.getUsed (.getHeapMemoryUsage (ManagementFactory/getMemoryMXBean))))

(defn- collected-heap-used
  "Bytes of heap in use after collecting garbage."
  ^long []
  (dotimes [_ 3] (System/gc) (Thread/sleep 30))
  (heap-used))

(defn peak-heap!
  "Call (f) while sampling the heap's use every millisecond; return
  [peak-bytes value], peak-bytes being the highest reading."
  [f]
  (let [peak (atom (heap-used))
        running (atom true)
        sampler (doto (Thread. ^Runnable
                               (fn [] (while @running
                                        (swap! peak max (heap-used))
                                        (Thread/sleep 1))))
                  (.setDaemon true)
                  (.start))
        v (try (f) (finally (reset! running false) (.join sampler)))]
    [(max @peak (heap-used)) v]))

(defn- mb [bytes] (/ bytes 1048576.0))

(defn measure-heap!
  "The heap the creature `make` returns needs: :retained-mb after body!
  and collection, :build-peak-mb above the starting heap while it is made
  and built, and, when `frames` is given, :sim-peak-mb above the starting
  heap while it runs that many frames in a world."
  [make frames]
  (let [base (collected-heap-used)
        [peak creature] (peak-heap! #(doto ^Node (make) (body/body!)))
        retained (collected-heap-used)
        result {:retained-mb (mb (- retained base)) :build-peak-mb (mb (- peak base))
                :max-heap-mb (mb (.maxMemory (Runtime/getRuntime)))
                :segments (count (body/segments creature))}]
    (if frames
      (let [base (collected-heap-used)
            [peak _] (peak-heap! #(cortex-run! make frames))]
        (assoc result :sim-peak-mb (mb (- peak base)) :sim-frames frames))
      result)))

(def plans
  "What a full and a --quick benchmark measure."
  {:full {:build {:sizes [10 100 300 1000] :warmup 2 :runs 7}
          :sim {:sizes [10 100 300] :frames 300 :runs 3}
          :heap {:size 1000 :frames 120}
          :step-loop {:frames 600 :runs 5}
          :rollouts {:worm 8 :hand 4 :runs 3}
          :blender-load-runs 11}
   :quick {:build {:sizes [10 100 300] :warmup 1 :runs 3}
           :sim {:sizes [10 100] :frames 120 :runs 1}
           :heap {:size 1000 :frames nil}
           :step-loop {:frames 120 :runs 1}
           :rollouts {:worm 4 :hand 2 :runs 1}
           :blender-load-runs 3}})

(def sim-budget
  "Segment-frames a simulation run should at least have."
  30000)

(def max-frames
  "The most frames a simulation run takes, however small the creature."
  3000)

(defn frames-for
  "Frames to simulate a creature of `segments`: the plan's `frames`, or
  more for small creatures, so that every run lasts long enough to time."
  [frames segments]
  (max frames (min max-frames (quot sim-budget (max 1 segments)))))

(def generators
  "The generated kinds of creature, by name."
  {"chain" creatures/chain
   "tree" creatures/tree})

(defn- generated
  "A maker of fresh `kind` creatures of `n` segments, lifted to `height`."
  [kind n height]
  #(creatures/creature ((generators kind) n) height))

(defn- progress [& args]
  (binding [*out* *err*] (apply println "bench:" args) (flush)))

(defn- blender-rows
  "A row for each Blender creature, starting from `row`: its segment
  count merged with (measure make), or :skipped with the reason when
  the creature cannot be loaded. `verb` names the step in the progress
  line."
  [verb row measure]
  (for [name ["worm" "hand"]
        :let [{:keys [make skipped]} (blender-maker name)
              row (assoc row :creature name)]]
    (if make
      (do (progress verb name)
          (merge row {:segments (count (body/segments (make)))} (measure make)))
      (assoc row :skipped skipped))))

(defn run-build!
  "Build rows: the median split of body! for the Blender creatures and
  for generated chains and trees of every planned size."
  [{:keys [sizes] :as opts}]
  (vec
   (concat
    (blender-rows "building" {:kind "blender"} #(measure-build! % opts))
    (for [kind ["chain" "tree"] n sizes]
      (do (progress "building" (str kind "-" n))
          (merge {:creature (str kind "-" n) :kind kind :segments n}
                 (measure-build! (generated kind n 0) opts)))))))

(def build-metrics
  "The build times whose growth is fitted."
  [:physical :targets :connect :body])

(defn exponents
  "For each generated kind in `rows` and each of `build-metrics`, the
  fitted growth exponent over all sizes and over sizes of at least 100,
  beside the exponent n log n itself would show on the same sizes."
  [rows]
  (vec
   (for [[kind rs] (group-by :kind (remove :skipped rows))
         :when (not= kind "blender")
         :let [rs (sort-by :segments rs)
               large (filter #(>= (:segments %) 100) rs)]]
     (into {:kind kind
            :sizes (mapv :segments rs)
            :nlogn (nlogn-exponent (map :segments rs))
            :nlogn-large (nlogn-exponent (map :segments large))}
           (for [m build-metrics
                 [suffix sel] [["" rs] ["-large" large]]]
             [(keyword (str (name m) suffix)) (fit-exponent (map (juxt :segments m) sel))])))))

(defn run-sim!
  "Simulation rows: throughput in a world and in bare Bullet for the
  Blender creatures and generated chains of the planned sizes."
  [{:keys [sizes] :as opts}]
  (vec
   (concat
    (blender-rows "simulating" {}
                  #(measure-sim! % (update opts :frames frames-for
                                           (count (body/segments (%))))))
    (for [n sizes]
      (do (progress "simulating" (str "chain-" n))
          (merge {:creature (str "chain-" n) :segments n}
                 (measure-sim! (generated "chain" n 0) (update opts :frames frames-for n))))))))

(defn run-step-loop!
  "Step-loop rows: cortex.sim against bare Bullet for the Blender
  creatures and a chain of ten."
  [opts]
  (let [measure (fn [make n] (measure-step-loop! make (update opts :frames frames-for n)))]
    (vec (concat
          (blender-rows "step loop" {} #(measure % (count (body/segments (%)))))
          [(do (progress "step loop" "chain-10")
               (merge {:creature "chain-10" :segments 10}
                      (measure (generated "chain" 10 0) 10)))]))))

(defn run-heap!
  "Heap rows for the planned size of chain and tree."
  [{:keys [size frames]}]
  (vec (for [kind ["chain" "tree"]]
         (do (progress "heap" (str kind "-" size))
             (merge {:creature (str kind "-" size)}
                    (measure-heap! (generated kind size 0) frames))))))

(defn rollout-specs
  "`n` rollout specs of the Blender creature `name` (worm or hand), each
  from its own seed."
  [name n]
  (vec (for [seed (range n)]
         (case name
           "worm" {:creature "Models/test-creature/worm.blend" :controller 'cortex.rollout/crawl-gait
                   :seconds 5 :seed seed :start {:shift 0.3 :turn 0.2}}
           "hand" {:creature "Models/test-creature/hand.blend" :controller 'cortex.rollout/sine-gait
                   :seconds 2 :seed seed :start {:shift 0.3 :turn 0.2}}))))

(defn measure-rollouts!
  "Rollouts a second of `specs` on 1 and 2 threads (medians of `runs`
  after a warm-up), the speed-up, the scaling efficiency, :same? when
  every run gave the same results, and the heap each of eight
  simulations of the first spec keeps while they are held at once."
  [specs runs]
  (let [go (fn [threads] (settle!) (timed #((requiring-resolve 'cortex.rollout/rollouts)
                                            specs {:threads threads})))
        _ (go 2)
        rounds (vec (repeatedly runs #(mapv go [1 2])))
        rate (fn [i] (/ (count specs) (/ (median (map (comp first #(nth % i)) rounds)) 1000.0)))
        [r1 r2] (map rate [0 1])
        simulation (requiring-resolve 'cortex.rollout/simulation)
        checked ((requiring-resolve 'cortex.rollout/check-spec!) nil (first specs))
        base (collected-heap-used)
        held (vec (repeatedly 8 #(simulation checked)))
        per (/ (- (collected-heap-used) base) 8.0)]
    (run! sim/destroy! held)
    {:rollouts (count specs) :seconds-each (:seconds (first specs))
     :rate-1 r1 :rate-2 r2 :speedup (/ r2 r1) :efficiency (/ r2 (* 2 r1))
     :mb-per-world (mb per)
     :same? (apply = (map second (apply concat rounds))) :runs runs}))

(defn measure-spark!
  "Spark local[2] against rollouts on 2 threads for `specs`: the
  session's start (:session-ms), the median job (:spark-ms) and
  rollouts (:rollouts-ms) over `runs`, the overhead and :same?; or
  :skipped without the spark profile."
  [specs runs]
  (if-let [run (try (requiring-resolve 'cortex.spark/run) (catch Throwable _ nil))]
    (let [[start-ms s] (timed #((requiring-resolve 'cortex.spark/session) "local[2]"
                                {"spark.ui.enabled" "false"}))
          rollouts (requiring-resolve 'cortex.rollout/rollouts)]
      (try
        (run specs {:spark s})
        (let [spark (median (repeatedly runs #(do (settle!) (first (timed (fn [] (run specs {:spark s})))))))
              local (median (repeatedly runs #(do (settle!) (first (timed (fn [] (rollouts specs {:threads 2})))))))]
          {:session-ms start-ms :spark-ms spark :rollouts-ms local
           :overhead-ms (- spark local) :spark-ratio (/ spark local)
           :same? (= (run specs {:spark s}) (rollouts specs {:threads 2})) :runs runs})
        (finally (.close ^java.io.Closeable s))))
    {:skipped "needs the spark profile: lein with-profile +spark bench"}))

(defn run-rollouts!
  "Rollout rows: the worm and the hand on 1 and 2 threads, and the
  worm on Spark local[2]."
  [{:keys [worm hand runs]}]
  (vec (concat
        (for [[name n] [["worm" worm] ["hand" hand]]]
          (do (progress "rollouts" name)
              (merge {:creature name} (measure-rollouts! (rollout-specs name n) runs))))
        [(do (progress "rollouts" "worm on Spark local[2]")
             (merge {:creature "worm, Spark local[2]" :rollouts worm}
                    (measure-spark! (rollout-specs "worm" worm) runs)))])))

(defn- cell
  "`x` with `digits` decimals, or - when it is not a number."
  [digits x]
  (if (number? x) (format (str "%." digits "f") (double x)) "-"))

(def rollout-columns
  [["creature" :creature] ["rollouts" :rollouts] ["s each" :seconds-each]
   ["1 thread /s" #(cell 2 (:rate-1 %))] ["2 threads /s" #(cell 2 (:rate-2 %))]
   ["speed-up" #(cell 2 (:speedup %))] ["efficiency" #(cell 2 (:efficiency %))]
   ["MB a world" #(cell 2 (:mb-per-world %))] ["same" :same?] ["runs" :runs]])

(def spark-columns
  [["creature" :creature] ["rollouts" :rollouts] ["session start ms" #(cell 0 (:session-ms %))]
   ["Spark job ms" #(cell 0 (:spark-ms %))] ["rollouts ms" #(cell 0 (:rollouts-ms %))]
   ["overhead ms" #(cell 0 (:overhead-ms %))] ["Spark/rollouts" #(cell 2 (:spark-ratio %))]
   ["same" :same?] ["runs" :runs]])

(defn- jme3-blender-loader
  "A function loading a .blend file (by path) with jme3-blender, from
  disk every time, or nil when jme3-blender is not on the classpath."
  []
  (when-let [loader (try (Class/forName "com.jme3.scene.plugins.blender.BlenderLoader")
                         (catch ClassNotFoundException _ nil))]
    (let [am (doto (com.jme3.asset.DesktopAssetManager. true)
               (.registerLocator "/" com.jme3.asset.plugins.FileLocator)
               (.registerLoader ^Class loader ^"[Ljava.lang.String;" (into-array String ["blend"])))]
      (fn [^String path]
        (.clearCache am)
        (.loadModel am path)))))

(defn run-blender-load!
  "Median load times of the Blender creatures with cortex's reader and
  with jme3-blender, measured with cortex.blender-bench's `medians` over
  `runs` rounds."
  [runs]
  (let [quiet (java.util.logging.Logger/getLogger "com.jme3")
        level (.getLevel quiet)
        am (util/asset-manager {:new true})
        theirs (jme3-blender-loader)]
    (progress "blender load times")
    (.setLevel quiet java.util.logging.Level/OFF)
    (try
      (vec (for [[name asset] (sort blender-creatures)
                 :let [path (.getCanonicalPath (io/file "assets" asset))
                       [ours jme] (blender-bench/medians
                                   runs (cond-> [#(util/load-blender-model am path)]
                                          theirs (conj #(theirs path))))]]
             {:creature name :cortex-ms ours :jme3-blender-ms jme
              :speed-up (when (and ours jme) (/ jme ours))}))
      (finally (.setLevel quiet level)))))

(def growth-tolerance
  "How far above n log n's own fitted exponent a measured exponent may
  be and still count as n log n: timing noise moves exponents by about
  this much."
  0.1)

(defn verdicts
  "Each target, the measured value and whether it is :met (true, false,
  or nil when not measured)."
  [{:keys [build sim exponents]}]
  (let [row (fn [rows c] (first (filter #(= c (:creature %)) rows)))
        check (fn [target value ok?] {:target target :value value
                                      :met (when (some? value) (boolean (ok? value)))})]
    (vec
     (concat
      [(check "body! of chain-300 < 1000 ms" (:body (row build "chain-300")) #(< % 1000))]
      (for [{:keys [kind] :as e} exponents]
        (check (format "%s body! growth <= n log n (exponent n>=100 <= %.2f + %.1f)"
                       kind (or (:nlogn-large e) 0.0) growth-tolerance)
               (:body-large e)
               #(<= % (+ (:nlogn-large e) growth-tolerance))))
      (for [{:keys [creature ratio cpu-ratio]} sim
            [clock r] [["wall" ratio] ["cpu" cpu-ratio]]
            :when r]
        (check (str creature " world >= 0.85 of bare Bullet (" clock ")") r #(>= % 0.85)))
      [(check "chain-100 world >= 30x real time" (:cortex (row sim "chain-100")) #(>= % 30))
       (check "chain-100 world >= 30x per CPU second" (:cortex-cpu (row sim "chain-100")) #(>= % 30))]))))

(defn- fmt
  "A number to `digits` decimals, or - when there is none."
  [digits x]
  (if (number? x) (format (str "%." digits "f") (double x)) "-"))

(defn table
  "Text of a table of `rows` under `columns`, [title cell-fn] pairs. A
  row with :skipped shows its first column and then the reason."
  [columns rows]
  (let [cells (for [r rows]
                (if (:skipped r)
                  [(str ((second (first columns)) r)) (str "(" (:skipped r) ")")]
                  (mapv #(str ((second %) r)) columns)))
        full (filter #(= (count columns) (count %)) cells)
        widths (for [i (range (count columns))]
                 (apply max (count (first (nth columns i))) (map #(count (nth % i)) full)))
        ;; the first column (names) left-aligned, the numbers right-aligned
        pad (fn [i w c] (format (str "%" (if (zero? i) "-" "") w "s") c))
        line (fn [cs] (str/join "  " (map pad (range) widths cs)))]
    (str/join "\n" (concat [(line (map first columns))
                            (line (map #(apply str (repeat % "-")) widths))]
                           (for [cs cells]
                             (if (= (count cs) (count columns))
                               (line cs)
                               (str (pad 0 (first widths) (first cs))
                                    "  " (second cs))))))))

(def build-columns
  [["creature" :creature] ["segments" :segments] ["joints" :joints]
   ["physical! ms" #(fmt 2 (:physical %))] ["targets ms" #(fmt 2 (:targets %))]
   ["connect ms" #(fmt 2 (:connect %))] ["sum ms" #(fmt 2 (:sum %))]
   ["body! ms" #(fmt 2 (:body %))] ["runs" :runs]])

(def exponent-columns
  (into [["kind" :kind] ["sizes" #(str/join "," (:sizes %))]]
        (concat (for [m build-metrics]
                  [(str (name m) " k (all/n>=100)")
                   #(str (fmt 2 (get % m)) " / " (fmt 2 (get % (keyword (str (name m) "-large")))))])
                [["n log n k (all/n>=100)" #(str (fmt 2 (:nlogn %)) " / " (fmt 2 (:nlogn-large %)))]])))

(def sim-columns
  [["creature" :creature] ["segments" :segments]
   ["world sim-s/s" #(fmt 2 (:cortex %))] ["bare Bullet sim-s/s" #(fmt 2 (:bare %))]
   ["world/bare" #(fmt 3 (:ratio %))]
   ["world sim-s/cpu-s" #(fmt 2 (:cortex-cpu %))] ["bare sim-s/cpu-s" #(fmt 2 (:bare-cpu %))]
   ["world/bare cpu" #(fmt 3 (:cpu-ratio %))] ["same motion" :same?]
   ["frames" :frames] ["runs" :runs]])

(def heap-columns
  [["creature" :creature] ["segments" :segments]
   ["retained MB" #(fmt 1 (:retained-mb %))] ["build peak MB" #(fmt 1 (:build-peak-mb %))]
   ["sim peak MB" #(fmt 1 (:sim-peak-mb %))] ["sim frames" #(or (:sim-frames %) "-")]
   ["max heap MB" #(fmt 0 (:max-heap-mb %))]])

(def step-loop-columns
  [["creature" :creature] ["segments" :segments]
   ["bare sim-s/cpu-s" #(fmt 1 (:bare-cpu %))] ["sim, none" #(fmt 1 (:none-cpu %))]
   ["sim, all" #(fmt 1 (:all-cpu %))] ["none/bare" #(fmt 3 (:none-ratio %))]
   ["all/bare" #(fmt 3 (:all-ratio %))] ["same motion" :same?]
   ["frames" :frames] ["runs" :runs]])

(def verdict-columns
  [["target" :target] ["measured" #(fmt 3 (:value %))]
   ["met" #(case (:met %) true "yes" false "NO" "not measured")]])

(defn blender-load-columns
  "Columns for the reader's rows: whatever keys they have."
  [rows]
  (let [ks (distinct (mapcat keys (remove :skipped rows)))]
    (if (seq ks)
      (for [k ks] [(name k) #(let [v (get % k)]
                               (cond (float? v) (fmt 2 v) (nil? v) "-" :else (str v)))])
      [["benchmark" (constantly ".blend load")]])))

(defn report
  "The text of all the tables of a benchmark `result`."
  [{:keys [build exponents sim heap step-loop blender-load targets machine rollouts]}]
  (str/join
   "\n\n"
   [(str "cortex benchmark on " ({:jbullet "jBullet" :native "native Bullet"} (:engine machine)) ", "
         (:when machine) ", " (:cores machine) " cores, "
         (:java machine) ", load average " (fmt 2 (:load-before machine))
         " before, " (fmt 2 (:load-after machine)) " after; medians after warm-up")
    (str "1. Building: body! split into physical! (hulls), joint targets, connect\n"
         (table build-columns build))
    (str "Growth exponents k (time ~ n^k), least squares on log-log\n"
         (table exponent-columns exponents))
    (str "2. Simulation at 60 Hz fixed step: simulated seconds per wall second\n"
         (table sim-columns sim))
    (str "3. Heap\n" (table heap-columns heap))
    (str "4. The step loop (cortex.sim) against bare Bullet, per CPU second: observing none, all\n"
         (table step-loop-columns step-loop))
    (str "5. Many rollouts at once (wall clock), on 1 and 2 threads; heap per world held\n"
         (table rollout-columns (remove #(re-find #"Spark" (:creature %)) rollouts))
         "\nSpark local[2] against rollouts on 2 threads, the same specs\n"
         (table spark-columns (filter #(re-find #"Spark" (:creature %)) rollouts)))
    (str ".blend load times, ms (medians by cortex.blender-bench's method)\n"
         (table (blender-load-columns blender-load) blender-load))
    (str "Targets\n" (table verdict-columns targets))]))

(defn csv-rows
  "One [section creature segments metric value] row per number in
  `result`."
  [{:keys [build sim heap step-loop exponents targets rollouts]}]
  (concat
   [["section" "creature" "segments" "metric" "value"]]
   (for [[section rows ks] [["build" build [:physical :targets :connect :sum :body :joints :runs]]
                            ["sim" sim [:cortex :bare :ratio :cortex-cpu :bare-cpu :cpu-ratio
                                        :same? :frames :runs]]
                            ["heap" heap [:retained-mb :build-peak-mb :sim-peak-mb :max-heap-mb]]
                            ["step-loop" step-loop [:bare-cpu :none-cpu :all-cpu :none-ratio
                                                    :all-ratio :same? :frames :runs]]
                            ["rollouts" rollouts [:rollouts :seconds-each :rate-1 :rate-2 :speedup
                                                  :efficiency :mb-per-world :session-ms :spark-ms
                                                  :rollouts-ms :overhead-ms :spark-ratio :same?
                                                  :skipped :runs]]]
         r rows
         k ks
         :when (contains? r k)]
     [section (:creature r) (:segments r) (name k) (get r k)])
   (for [e exponents
         k (keys (dissoc e :kind :sizes))]
     ["exponent" (:kind e) (str/join " " (:sizes e)) (name k) (get e k)])
   (for [t targets]
     ["target" (:target t) "" "met" (:met t)])))

(defn- csv-cell [x]
  (let [s (str x)]
    (if (re-find #"[\",\n]" s) (str "\"" (str/replace s "\"" "\"\"") "\"") s)))

(defn csv
  "CSV text of `rows`."
  [rows]
  (str (str/join "\n" (for [r rows] (str/join "," (map csv-cell r)))) "\n"))

(defn write-results!
  "Write `result` and its report to `dir`: results.csv, results.edn and
  report.txt. Returns the files written."
  [dir result]
  (let [files {"results.csv" (csv (csv-rows result))
               "results.edn" (with-out-str (pprint/pprint result))
               "report.txt" (str (report result) "\n")}]
    (doall (for [[name text] files
                 :let [f (io/file dir name)]]
             (do (io/make-parents f) (spit f text) (str f))))))

(defn- load-average []
  (.getSystemLoadAverage (ManagementFactory/getOperatingSystemMXBean)))

(defn machine
  "What the numbers were measured on."
  []
  {:when (str (java.time.LocalDateTime/now))
   :engine cortex.engine/name
   :cores (.availableProcessors (Runtime/getRuntime))
   :java (System/getProperty "java.version")
   :jvm-args (vec (.getInputArguments (ManagementFactory/getRuntimeMXBean)))})

(defn warm-up!
  "Run everything the benchmark measures a few times before measuring
  any of it, so that the first sizes measured do not pay for the JIT
  compiling code the later ones find compiled."
  []
  (progress "warming up")
  (dotimes [_ 3]
    (doseq [kind ["chain" "tree"]] (body/body! ((generated kind 300 0))))
    (cortex-run! (generated "chain" 30 0) 300)
    (bare-run! (generated "chain" 30 0) 300)))

(defn run-benchmark!
  "Run the benchmark `plan` (see `plans`); return the result as data."
  [plan]
  (let [m (assoc (machine) :load-before (load-average))
        _ (warm-up!)
        build (run-build! (:build plan))
        sim (run-sim! (:sim plan))
        heap (run-heap! (:heap plan))
        step-loop (run-step-loop! (:step-loop plan))
        rollouts (run-rollouts! (:rollouts plan))
        blender-load (run-blender-load! (:blender-load-runs plan))
        eyes (run-eyes! (get-in plan [:step-loop :frames]))
        result {:plan plan :build build :exponents (exponents build)
                :rollouts rollouts
                :sim sim :heap heap :step-loop step-loop :blender-load blender-load
                :eyes eyes
                :machine (assoc m :load-after (load-average))}]
    (assoc result :targets (verdicts result))))

(defn -main
  "lein bench [--quick] [--out DIR]: run the benchmark, print its tables
  and write them to DIR (target/bench by default) as CSV and EDN."
  [& args]
  (let [opts (loop [[a & more] args opts {:plan :full :out "target/bench"}]
               (case a
                 nil opts
                 "--quick" (recur more (assoc opts :plan :quick))
                 "--out" (recur (rest more) (assoc opts :out (first more)))
                 (throw (ex-info (str "unknown option " a "; use --quick, --out DIR") {}))))
        t0 (now)
        result (run-benchmark! (plans (:plan opts)))]
    (println (report result))
    (println)
    (println (eyes-table (:eyes result)))
    (doseq [f (write-results! (:out opts) result)]
      (println "wrote" f))
    (println (format "benchmark took %.0f s" (/ (ms-since t0) 1000)))
    (shutdown-agents)))
