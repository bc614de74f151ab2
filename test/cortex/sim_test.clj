;; Generated from org/sim.org by lein tangle: edit the chapter, not this file.
(ns cortex.sim-test
  (:require [clojure.java.io :as io]
            [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.engine :as engine]
            [cortex.joint-fixtures :as f]
            [cortex.proprioception :as p]
            [cortex.render :as render]
            [cortex.sim :as sim]
            [cortex.blender]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Node)
           (java.nio.file Files)
           (java.nio.file.attribute FileAttribute)))

(set! *warn-on-reflection* true)

(defn crawl-gait
  "The worm's open-loop gait at time `t`: from 0.5 s, when it has
  landed, its hinge's target rises from 0 to 0.6 rad over 80% of each
  1/1.5 s cycle, and drops back."
  [t]
  (let [phase (mod (* 1.5 (max 0.0 (- (double t) 0.5))) 1.0)
        up 0.8]
    {"worm-joint" {:target (* 0.6 (if (< phase up)
                                    (/ phase up)
                                    (- 1 (/ (- phase up) (- 1 up)))))}}))

(defn grippy-worm
  "The worm as its file makes it: worm-1 with friction 1.0, worm-2 with
  0.1 (custom properties)."
  []
  (body/body! (util/load-blender-model f/worm-path)))

(defn- even-worm
  "The worm with both segments' friction set to 0.5, as a designer would
  set it in Blender: a custom property on each object."
  []
  (let [^Node c (util/load-blender-model f/worm-path)]
    (doseq [n ["worm-1" "worm-2"]]
      (.setUserData (.getChild c ^String n) "friction" (float 0.5)))
    (body/body! c)))

(defn- centre [obs]
  (let [ps (map :position (vals (:segments obs)))]
    (mapv #(/ (double %) (count ps)) (apply map + ps))))

(defn- crawl
  "Every observation of the grippy worm crawling for 10 s."
  []
  (let [s (sim/simulation (grippy-worm) {:floor 0})]
    (vec (for [_ (range 600)] (sim/step! s (crawl-gait (sim/sim-time s)))))))

(defn crawl-at-least
  "How far (along -x) the worm's gait must take it in ten seconds: a
  segment length, 2, on jBullet; 1.5 on native Bullet, whose contacts
  hold its gripping head less (see below)."
  []
  (if (= :native engine/name) -1.5 -2.0))

(deftest the-worm-crawls
  (let [run-1 (crawl)
        run-2 (crawl)
        start (centre (run-1 0))
        [dx _ dz] (mapv - (centre (peek run-1)) start)]
    (is (= run-1 run-2) "two runs give bit-identical observations")
    (testing "along its length (x), towards its grippy end, at least a segment length"
      (is (<= dx (crawl-at-least)) (str "moved " dx " along x")))
    (testing "and much more along than sideways"
      (is (< (Math/abs (double dz)) (/ (Math/abs (double dx)) 2))))
    (testing "with the same friction on both segments it does not crawl"
      (let [s (sim/simulation (even-worm) {:floor 0})
            obs (vec (for [_ (range 600)] (sim/step! s (crawl-gait (sim/sim-time s)))))]
        (is (< (Math/abs (double (- (first (centre (peek obs))) (first (centre (obs 0)))))) 0.5))))))

(defn- body-states
  [^Node node]
  (vec (for [^Geometry g (body/segments node)
             :let [^RigidBodyControl c (.getControl g RigidBodyControl)]
             :when c
             :let [l (.getPhysicsLocation c) q (.getPhysicsRotation c)
                   v (.getLinearVelocity c) w (.getAngularVelocity c)]]
         [(.getName g) [(.x l) (.y l) (.z l)] [(.getX q) (.getY q) (.getZ q) (.getW q)]
          [(.x v) (.y v) (.z v)] [(.x w) (.y w) (.z w)]])))

(defn- world-run [make floor frames]
  (let [c (body/body! (make))
        w (world/world (util/nodify [c (sim/floor floor)]) {}
                       #(world/set-gravity % (Vector3f. 0 -9.81 0)) world/no-op)]
    (world/run-world! w frames)
    (body-states c)))

(defn- sim-run [make floor frames]
  (let [c (body/body! (make))
        s (sim/simulation c {:floor floor})]
    (dotimes [_ frames] (sim/step! s))
    (body-states c)))

(deftest same-motion-as-a-world
  (doseq [[label make floor frames] [["worm" #(util/load-blender-model f/worm-path) -1 180]
                                     ["hand" #(util/load-blender-model f/hand-path) 0 120]
                                     ["chain-10" #(f/chain 10 2) 0 180]]]
    (testing label
      (is (= (world-run make floor frames) (sim-run make floor frames))))))

(deftest a-step-is-a-sixtieth-of-a-second
  (let [s (sim/simulation (body/body! (f/chain 10 2)) {:observe #{:segments}})
        g 9.81 h (/ 1.0 60)
        mean (fn [o k] (/ (reduce + (for [[_ seg] (:segments o)] (nth (k seg) 1))) 10))
        y0 (mean (sim/observe s) :position)]
    (doseq [n (range 1 31)
            :let [o (sim/step! s)]]
      (is (== (/ n 60.0) (:time o)))
      (is (< (Math/abs (- (- y0 (mean o :position)) (* g h h n (inc n) 0.5))) 1e-4)
          (str "after " n " steps the chain has fallen " (- y0 (mean o :position))))
      (is (< (Math/abs (+ (mean o :velocity) (* g h n))) 1e-4)
          (str "after " n " steps the chain falls at " (mean o :velocity))))))

(deftest touch-reports-contacts
  (let [s (sim/simulation (util/load-blender-model f/worm-path) {:floor 0})
        in-air (:touch (sim/step! s))
        resting (vec (for [i (range 120)] (:touch (sim/step! s))))
        total (fn [touch] (+ (get-in touch ["worm-1" :impulse]) (get-in touch ["worm-2" :impulse])))
        mean (/ (reduce + (map total (subvec resting 30 120))) 90)
        weight-impulse (* 2 9.81 (/ 1 60.0))]
    (is (= {"worm-1" {:touching #{} :impulse 0.0} "worm-2" {:touching #{} :impulse 0.0}} in-air))
    (is (= #{"floor"} (get-in (peek resting) ["worm-1" :touching])
           (get-in (peek resting) ["worm-2" :touching])))
    (testing "on average the floor's impulses carry the worm's weight, m g dt a step"
      (is (< (Math/abs (- mean weight-impulse)) (* 0.1 weight-impulse)) (str "mean " mean)))))

(deftest observe-only-what-is-asked
  (let [s (sim/simulation (util/load-blender-model f/worm-path) {:floor 0 :observe #{}})]
    (is (= {:time (/ 1 60.0)} (sim/step! s)))
    (is (= #{:time :joints} (set (keys (sim/observe s #{:joints})))))))

(deftest bad-options-are-named
  (doseq [[opts pattern] [[{:gravity [0 -9.81]} #":gravity"]
                          [{:floor "low"} #":floor"]
                          [{:observe #{:smell}} #":observe"]
                          [{:flor 0} #"no key :flor; did you mean :floor\? It takes :eyes, :floor"]
                          [{:solver 20} #":solver must be a map"]
                          [{:solver {:iterations 0}} #":solver :iterations must be a whole number from 1 to 1000, not 0"]
                          [{:solver {:substeps 2.5}} #":solver :substeps must be a whole number from 1 to 64"]
                          [{:solver {:substep 2}} #":solver has no key :substep; did you mean :substeps\?"]
                          [{:solver {:projection "no"}} #":solver :projection must be true or false"]
                          [{:solver {:projecton false}} #"did you mean :projection\?"]]]
    (is (thrown-with-msg? clojure.lang.ExceptionInfo pattern
                          (sim/simulation (util/load-blender-model f/worm-path) opts)))))

(defn- speed-gained-in-a-second
  "The vertical speed the worm's first segment gains over the 60 steps
  after the first, with no floor, how many Bullet steps they took, and
  the simulation's solver, under `opts`."
  [opts]
  (let [s (sim/simulation (util/load-blender-model f/worm-path) opts)
        ticks (atom 0)
        vy #(get-in (sim/observe s #{:segments}) [:segments "worm-1" :velocity 1])]
    (sim/step! s)
    (.addTickListener ^com.jme3.bullet.PhysicsSpace (:space s)
                      (reify com.jme3.bullet.PhysicsTickListener
                        (prePhysicsTick [_ _ _] (swap! ticks inc))
                        (physicsTick [_ _ _])))
    (let [v0 (double (vy))]
      (dotimes [_ 60] (sim/step! s))
      [(- v0 (double (vy))) @ticks (sim/solver s)])))

(deftest the-solver-can-be-chosen
  (doseq [[opts solver] [[{} {:iterations engine/solver-iterations :substeps 1
                              :projection true}]
                         [{:solver {:iterations 25}} {:iterations 25 :substeps 1
                                                      :projection true}]
                         [{:solver {:substeps 8 :projection false}}
                          {:iterations engine/solver-iterations :substeps 8 :projection false}]]
          :let [[gained ticks seen] (speed-gained-in-a-second opts)
                k (:substeps solver)]]
    (testing (pr-str opts)
      (is (= solver seen))
      (is (= (* 60 k) ticks) "every substep is a Bullet step")
      (is (< (Math/abs (- gained 9.81)) 0.01)
          (format "gained %.4f m/s in a second" gained))))
  (testing "a Physics-tab creature steps as its file says, unless :solver says otherwise"
    (let [make #((requiring-resolve 'cortex.physics-tab/physics-body!)
                 ((requiring-resolve 'cortex.physics-tab/load-creature) "test/fixtures/physics-sim/substeps.blend"))
          file (sim/simulation (make) {})
          ours (sim/simulation (make) {:solver {:iterations 12 :substeps 4}})]
      ;; its joints are Blender's, not the body chapter's: none is projected
      (is (= {:iterations 4 :substeps 2 :projection true} (sim/solver file)))
      (is (= {:iterations 12 :substeps 4 :projection true} (sim/solver ours)))
      (testing "at the file's time scale of 0.5: four substeps of 0.5/240 s"
        (is (< (Math/abs (- (* 4 (.getAccuracy ^com.jme3.bullet.PhysicsSpace (:space ours))) (/ 0.5 60)))
               1e-6))))))

(deftest sync-moves-the-geometries
  (let [s (sim/simulation (util/load-blender-model f/worm-path) {:floor 0})]
    (dotimes [_ 60] (sim/step! s))
    (sim/sync! s)
    (doseq [^Geometry g (body/segments (:creature s))
            :let [^RigidBodyControl c (.getControl g RigidBodyControl)]]
      (is (< (.distance (.getWorldTranslation g) (.getPhysicsLocation c)) 1e-5))
      (is (< (Math/abs (- (.y (.getWorldTranslation g)) 0.3)) 0.05) "resting on the floor"))))

(defn- drawn [node]
  (into {} (for [^Geometry g (body/segments node)]
             [(.getName g) [(.clone (.getWorldTranslation g)) (.clone (.getWorldRotation g))]])))

(defn- apart [[^Vector3f p ^com.jme3.math.Quaternion q] [^Vector3f p' ^com.jme3.math.Quaternion q']]
  (max (.distance p p') (- 1.0 (Math/abs (double (.dot q q'))))))

(deftest sync-draws-segments-whose-bodies-are-offset
  (let [c (body/body! (util/load-blender-model "test/fixtures/strangers/humanoid.blend"))
        _ (.updateGeometricState c)
        built (drawn c)
        offset? (set (map #(.getName ^Geometry %) (filter cortex.segment/mass-offset (body/segments c))))
        s (sim/simulation c {:floor -10 :observe #{}})]
    (is (<= 5 (count offset?)) "most of its segments' bodies are off their own frames")
    (sim/sync! s)
    (testing "before a step: where the designer left them"
      (doseq [[n pose] (drawn c)]
        (is (< (apart pose (built n)) 1e-5) n)))
    (dotimes [_ 30] (sim/step! s))
    (sim/sync! s)
    (let [synced (drawn c)]
      (testing "after 30 steps, falling: where their bodies are"
        (doseq [^Geometry g (body/segments c)
                :let [[p q] (cortex.segment/segment-pose g)]]
          (is (< (apart [p q] (synced (.getName g))) 1e-5) (.getName g))))
      ;; a world's frame: each control places its own Geometry
      (doseq [^Geometry g (body/segments c)]
        (.update ^RigidBodyControl (.getControl g RigidBodyControl) (float (/ 1.0 60))))
      (.updateGeometricState c)
      (testing "and where a world's frame draws the offset ones"
        (doseq [[n pose] (drawn c) :when (offset? n)]
          (is (< (apart pose (synced n)) 1e-5) n))))
    (sim/destroy! s)))

(deftest a-simulation-can-be-recorded
  (let [dir (str (Files/createTempDirectory "cortex-sim" (into-array FileAttribute [])))
        recorded (sim/simulation (grippy-worm) {:floor 0})
        w (sim/world recorded #(crawl-gait (:time %)))
        plain (sim/simulation (grippy-worm) {:floor 0})]
    (render/record! w dir {:progress nil})
    (render/run-offscreen! w 30 {:size [320 240]})
    (dotimes [_ 30] (sim/step! plain (crawl-gait (sim/sim-time plain))))
    (is (= 30 (count (render/frames-in dir))))
    (is (pos? (.length (io/file dir "frame-000030.png"))))
    (testing "the worm is lit: its green shows (unlit, it was black)"
      (let [^java.awt.image.BufferedImage img (javax.imageio.ImageIO/read (io/file dir "frame-000030.png"))
            green (count (for [x (range (.getWidth img)) y (range (.getHeight img))
                               :let [rgb (.getRGB img x y)
                                     r (bit-and (bit-shift-right rgb 16) 255)
                                     g (bit-and (bit-shift-right rgb 8) 255)]
                               :when (and (> g 80) (> g (+ r 40)))]
                           1))]
        (is (> green 500) (str green " green pixels"))))
    (is (= 30 (sim/steps recorded)))
    (is (= (sim/observe plain) (sim/observe recorded)))))

(deftest the-readme-examples
  (let [hand (body/body! (util/load-blender-model "Models/test-creature/hand.blend"))
        joints (p/proprioception hand)]
    (is (= 15 (count joints)))
    (is (every? #(= 0.0 (double (or (:angle %) (:twist %)))) (vals joints))))
  (let [quad #(body/body! (util/load-blender-model "test/fixtures/designer/quadruped.blend"))
        stand {"knee-front-r" {:target 0.0} "knee-front-l" {:target 0.0}
               "knee-back-r" {:target 0.0} "knee-back-l" {:target 0.0}
               "hip-front-r" {:target [0 0 0]} "hip-front-l" {:target [0 0 0]}
               "hip-back-r" {:target [0 0 0]} "hip-back-l" {:target [0 0 0]}}
        height (fn [actions steps]
                 (let [s (sim/simulation (quad) {:floor 0})
                       obs (last (repeatedly steps #(sim/step! s actions)))]
                   [(second (get-in obs [:segments "torso" :position]))
                    (get-in obs [:joints "knee-front-r" :angle])
                    (get-in obs [:touch "lower-leg-front-r" :touching])]))
        [held knee touching] (height stand 180)
        [still-held] (height stand 900)
        [fallen] (height nil 180)]
    (is (> held 1.25) "held by its muscles, it stands")
    (is (> still-held 1.25) "and still stands at 15 s")
    (is (< (Math/abs (double knee)) 0.1))
    (is (= #{"floor"} touching))
    (is (< fallen 1.0) "without them it folds"))
  (let [gait (fn [t] (let [phase (mod (* 1.5 (max 0.0 (- t 0.5))) 1.0)]
                       {"worm-joint" {:target (* 0.6 (if (< phase 0.8) (/ phase 0.8) (/ (- 1 phase) 0.2)))}}))
        w (sim/simulation (body/body! (util/load-blender-model "Models/test-creature/worm.blend")) {:floor 0})
        x0 (first (get-in (sim/observe w) [:segments "worm-1" :position]))]
    (dotimes [_ 600] (sim/step! w (gait (sim/sim-time w))))
    (is (< (- (first (get-in (sim/observe w) [:segments "worm-1" :position])) x0)
           ;; 3.8 on jBullet, 1.9 on native Bullet (see "The worm crawls")
           (if (= :native engine/name) -1.5 -3.0)))))

(deftest off-centre-segments-are-observed-at-their-origin
  (let [mesh (com.jme3.scene.shape.Box. (Vector3f. 0 -0.5 -0.25) (Vector3f. 2 0.5 0.25))
        g (Geometry. "lopsided" mesh)
        c (util/nodify "c" [(doto (Node. "lopsided") (.attachChild g) (.setLocalTranslation 1 2 3)
                              (.setLocalRotation (doto (com.jme3.math.Quaternion.)
                                                   (.fromAngleAxis 0.3 Vector3f/UNIT_Z))))])
        s (sim/simulation (body/body! c) {:gravity [0 0 0]})
        ^RigidBodyControl control (.getControl g RigidBodyControl)]
    (.setAngularVelocity control (Vector3f. 0 2 0))
    (let [obs (vec (repeatedly 31 #(sim/step! s)))
          at (fn [i] (get-in obs [i :segments "lopsided"]))
          {:keys [position velocity]} (at 29)
          [p _] (body/segment-pose g)
          ;; the origin's velocity, from its positions a step either side
          moved (mapv #(/ (- %1 %2) (/ 2 60.0)) (:position (at 30)) (:position (at 28)))]
      (is (< (.distance (util/vec3 (:position (at 30))) p) 1e-5))
      (is (> (.distance (util/vec3 position) (.getPhysicsLocation control)) 0.9)
          "the body itself is at the mesh's centre, a unit away")
      (testing "the origin swings round the centre, at the speed its positions say"
        (is (> (.length (util/vec3 velocity)) 1.0))
        (is (< (.distance (util/vec3 velocity) (util/vec3 moved))
               (* 0.02 (.length (util/vec3 moved)))))))))

(defn- bytes-per-step
  "What one `step!` of the creature at `path`, observing nothing,
  allocates on this thread, in bytes, after a warm-up."
  [path]
  (let [^com.sun.management.ThreadMXBean mx (java.lang.management.ManagementFactory/getThreadMXBean)
        s (sim/simulation (util/load-blender-model path) {:floor {:height 0 :friction 1.0}
                                                          :observe #{}})
        thread (.getId (Thread/currentThread))]
    (try
      (dotimes [_ 2000] (sim/step! s))
      (let [before (.getThreadAllocatedBytes mx thread)]
        (dotimes [_ 1000] (sim/step! s))
        (/ (- (.getThreadAllocatedBytes mx thread) before) 1000.0))
      (finally (sim/destroy! s)))))

(deftest a-step-allocates-little
  ;; native Bullet only: jBullet's own step allocates (see above)
  (when (= :native engine/name)
    (doseq [path ["test/fixtures/humanoid/humanoid.blend" "test/fixtures/designer/quadruped.blend"]]
      (let [b (bytes-per-step path)]
        (is (< b 1024.0) (str path ": " b " bytes a step"))))))

(defn- lift!
  "Move creature `c` so that its lowest point is 5% of its height above
  y = 0; its height."
  ^double [^Node c]
  (let [^com.jme3.bounding.BoundingBox b (do (.updateGeometricState c) (.getWorldBound c))
        lo (- (.y (.getCenter b)) (.getYExtent b))
        hi (+ (.y (.getCenter b)) (.getYExtent b))]
    (.move c 0 (float (+ (- (double lo)) (* 0.05 (- (double hi) (double lo))))) 0)
    (- (double hi) (double lo))))

(defn- stranger-rest
  "The strangers' creature `f` dropped limp from 5% of its height onto a
  floor of friction 1, 10 s, simulated with `opts`: {:height (of the
  creature) :centre (the mean height of its segments' origins at the
  end) :fastest (the fastest segment in the last second, m/s) :weight
  (the touch impulses of the last step, summed) :mass :scale
  :substeps}; with `k`, its file's scene first made k times its size."
  ([f opts] (stranger-rest f 1.0 opts))
  ([f k opts]
   (let [^Node c (doto ^Node (util/load-blender-model (str "test/fixtures/strangers/" f ".blend"))
                   (.setLocalScale (float k)))
         height (lift! c)
         s (sim/simulation c (merge {:floor {:height 0 :friction 1.0} :observe #{:segments :touch}}
                                    opts))]
     (try
       (let [obs (vec (repeatedly 600 #(sim/step! s)))
             speed (fn [v] (Math/sqrt (reduce + (map #(* (double %) (double %)) v))))
             segs (vals (:segments (peek obs)))]
         {:height height
          :centre (/ (reduce + (map #(double (second (:position %))) segs)) (count segs))
          :fastest (apply max (for [o (subvec obs 540), {v :velocity} (vals (:segments o))] (speed v)))
          :weight (reduce + (map :impulse (vals (:touch (peek obs)))))
          :mass (reduce + (map :mass (:segments (body/report c))))
          :scale (sim/scale s) :substeps (:substeps (sim/solver s))})
       (finally (sim/destroy! s))))))

(deftest a-small-creature-is-simulated-larger
  (is (= [10000.0 100.0 100.0 10.0 10.0 10.0 10.0 1.0 1.0 1.0]
         (mapv sim/auto-scale [0.0004 0.0157 0.099 0.1 0.3 0.83 0.999 1.0 2.0 0.0])))
  (is (= 0.0 (sim/creature-size (Node. "nothing"))) "a creature that shows nothing")
  (doseq [f ["worm-eye" "hand" "humanoid"]
          :let [twin (stranger-rest f {})
                small (stranger-rest (str f "-0.01") {})]]
    (testing f
      (is (= [1.0 100.0] [(:scale twin) (:scale small)]))
      (is (= 10 (:substeps small)) "its twin's one substep, times sqrt 100")
      (is (< (:fastest twin) 0.01) (str "the full-size twin still moving at " (:fastest twin)))
      (is (< (:fastest small) 0.001) (str "at a hundredth, still moving at " (:fastest small) " m/s"))
      (is (< (Math/abs (- (* 100 (double (:centre small))) (double (:centre twin))))
             (* 0.05 (double (:height twin))))
          (str "at a hundredth its centre ends at " (:centre small) ", its twin's at " (:centre twin)))
      ;; lying without touching itself, the small creature's touch
      ;; impulses are its weight over the last Bullet step, 1/(60 n) s;
      ;; on jBullet only: native Bullet's sleeping bodies keep stale
      ;; impulses (its full-size worm's read 1.7 times its weight, the
      ;; hand's 0.73, the small hand's 0.93 or 1.0 as it landed)
      (when (and (#{"worm-eye" "hand"} f) (= :jbullet engine/name))
        (let [{:keys [weight mass substeps]} small
              w (/ (* (double mass) 9.81) (* 60.0 (long substeps)))]
          (is (< (Math/abs (- (double weight) w)) (* 0.05 w))
              (str "the floor bears " weight " N s in a Bullet step, where the weight gives "
                   w))))))
  (let [at-size (stranger-rest "hand-0.01" {:scale 1})]
    (is (= 1.0 (:scale at-size)))
    (is (= 6 (:substeps at-size)) "its own, sqrt(0.05 / its thinnest) rounded up")))

(deftest a-creature-under-1-across-is-simulated-larger
  (doseq [f ["worm-eye" "humanoid"]
          :let [twin (stranger-rest f {})]
          k (if (= f "humanoid") [0.3 0.5] [0.3])
          :let [small (stranger-rest f k {})]]
    (testing (str f " at " k)
      (is (= 10.0 (:scale small)))
      (is (= 4 (:substeps small)) "its twin's one substep, times ceil(sqrt 10)")
      (is (< (:fastest small) 0.001) (str "still moving at " (:fastest small) " m/s"))
      (is (< (Math/abs (- (/ (double (:centre small)) k) (double (:centre twin))))
             (* 0.05 (double (:height twin))))
          (str "over " k ", its centre ends at " (/ (:centre small) k) ", its twin's at "
               (:centre twin))))))

(deftest a-creature-that-rests-at-its-size-rests-where-it-did
  (doseq [f ["flat-strangers/glider" "flat-strangers/leaf-walker"
             "flat-strangers/flat-hexagon-paddle" "strangers/inverted_pendulum"]
          :let [drop (fn [scale]
                       (let [^Node c (util/load-blender-model (str "test/fixtures/" f ".blend"))
                             height (lift! c)
                             s (sim/simulation c {:floor {:height 0 :friction 1.0} :observe #{:segments}
                                                  :scale scale})]
                         (try
                           (let [obs (vec (repeatedly 600 #(sim/step! s)))
                                 ys (map #(double (second (:position %))) (vals (:segments (peek obs))))]
                             {:scale (sim/scale s) :height height
                              :centre (/ (reduce + ys) (count ys))
                              :fastest (apply max (for [o (subvec obs 540), {v :velocity} (vals (:segments o))]
                                                    (Math/sqrt (reduce + (map #(* (double %) (double %)) v)))))})
                           (finally (sim/destroy! s)))))
                at-size (drop 1)
                larger (drop :auto)]]
    (testing f
      (println (format "%s: centre %.4f at its size (fastest %.3f m/s), %.4f simulated 10 times larger (%.3f)"
                       f (:centre at-size) (:fastest at-size) (:centre larger) (:fastest larger)))
      (is (= [1.0 10.0] [(:scale at-size) (:scale larger)]))
      (is (< (:fastest larger) 0.001) (str "simulated larger, still moving at " (:fastest larger)))
      (is (< (Math/abs (- (double (:centre at-size)) (double (:centre larger)))) (* 0.02 (:height at-size)))
          (str "its centre ends at " (:centre larger) ", at its size " (:centre at-size))))))

(deftest a-small-rod-lies-still
  (doseq [sides [16 32]
          :let [rod (doto (Node. "rod")
                      (.attachChild (Geometry. "rod" (com.jme3.scene.shape.Cylinder.
                                                      2 (int sides) (float 0.03) (float 0.6) true)))
                      (.setLocalRotation (doto (com.jme3.math.Quaternion.)
                                           (.fromAngles 0 (float (/ Math/PI 2)) 0)))
                      (.setLocalTranslation 0 (float 0.0305) 0))
                s (sim/simulation (doto (Node. "rod-creature") (.attachChild rod))
                                  {:floor {:height 0 :friction 1.0} :observe #{:segments}})]]
    (try
      (let [obs (vec (repeatedly 600 #(sim/step! s)))
            turn (apply max (for [o (subvec obs 540), {w :angular-velocity} (vals (:segments o))]
                              (Math/sqrt (reduce + (map #(* (double %) (double %)) w)))))
            y (double (second (:position (first (vals (:segments (peek obs)))))))]
        (testing (str "a cylinder of " sides " sides")
          (is (= 10.0 (sim/scale s)))
          (is (< turn 0.05) (str "turning at " turn " rad/s in its tenth second"))
          (is (< (Math/abs (- (/ y 0.03) 1.0)) 0.05) (str "its centre at " (/ y 0.03) " of its radius"))))
      (finally (sim/destroy! s)))))

(defn- scaled-run
  "The worm simulated at `scale` with one substep, no floor, its joint
  told to bend to 0.5 rad for 30 steps, then pushed with a third of
  its strength for 30: [every observation, the last efforts, the
  muscle]."
  [scale]
  (let [s (sim/simulation (util/load-blender-model f/worm-path)
                          {:scale scale :solver {:substeps 1} :observe #{:joints :segments}})
        strength (:strength (get (:muscles s) "worm-joint"))]
    (try
      [(vec (for [i (range 60)]
              (sim/step! s {"worm-joint" (if (< i 30) {:target 0.5} (/ strength 3.0))})))
       (sim/last-efforts s)
       (select-keys (get (:muscles s) "worm-joint") [:strength :kp :kd :inertia])]
      (finally (sim/destroy! s)))))

(defn- numbers [x] (filter number? (tree-seq coll? seq x)))

(deftest a-creature-simulated-larger-is-the-same-creature
  (let [[obs efforts muscle] (scaled-run 1)
        [obs-10 efforts-10 muscle-10] (scaled-run 10)
        apart (fn [a b] (apply max (map #(Math/abs (- (double %1) (double %2))) (numbers a) (numbers b))))]
    (is (= (count (numbers obs)) (count (numbers obs-10))))
    (is (< 0.1 (Math/abs (double (get-in obs [29 :joints "worm-joint" :angle])))) "the worm bends")
    (is (< (apply max (map #(Math/abs (double %)) (numbers (:segments (peek obs))))) 100))
    (is (< (apply max (map apart obs obs-10)) 1e-4) "every observation, as at its size")
    (is (< (apart efforts efforts-10) (* 1e-6 (:strength muscle))) (str efforts " " efforts-10))
    ;; to a float's precision: the joint's pivots are floats, ten times larger
    (is (< (apart muscle muscle-10) (* 1e-6 (apply max (numbers muscle)))) (str muscle " " muscle-10))))

(deftest a-creature-simulated-larger-is-reported-at-its-size
  (doseq [[f k] [["flat-strangers/flat-hexagon-paddle" 10.0] ["strangers/worm-eye-0.01" 100.0]]
          :let [load #(util/load-blender-model (str "test/fixtures/" f ".blend"))
                twin (body/report (body/body! (load)))
                c (load)
                s (sim/simulation c {:observe #{}})
                larger (body/report c)
                hulls (fn [r] (filter #(= :hull (:shape %)) (:segments r)))
                hull-free (fn [r] (update r :segments (partial mapv #(cond-> % (= :hull (:shape %))
                                                                      (dissoc :volume :hull-volume)))))]]
    (sim/destroy! s)
    (testing f
      (is (= k (sim/scale s)))
      (is (seq (:joints twin)))
      (is (= (hull-free twin) (hull-free larger)) "all but the hulls' volumes exactly as the twin's")
      (is (= (count (hulls twin)) (count (hulls larger))))
      (doseq [[a b] (map vector (hulls twin) (hulls larger))
              :let [va (double (:hull-volume a)) vb (double (:hull-volume b))]]
        (is (<= (Math/abs (- va vb)) (* 1e-3 (max va 1e-9))) (str (:name a) ": " va " " vb))
        (is (= [va vb] [(double (:volume a)) (double (:volume b))]) (:name a))))))

(deftest a-scale-is-refused-where-it-cannot-be-kept
  (let [bodied (body/body! (util/load-blender-model f/worm-path))
        fails (fn [opts c] (try (sim/destroy! (sim/simulation c opts)) nil
                                (catch clojure.lang.ExceptionInfo e (ex-message e))))]
    (is (re-find #"worm.*:scale 10: the creature has its body already.*before body!"
                 (str (fails {:scale 10} bodied))))
    (doseq [bad [0 -1 :big ##NaN "10"]]
      (is (re-find #":scale must be :auto or a positive number" (str (fails {:scale bad} bodied)))
          (pr-str bad)))
    (testing "a creature built larger is simulated larger again, and only so"
      (let [c (util/load-blender-model "test/fixtures/strangers/hand-0.01.blend")
            first-sim (sim/simulation c {:floor 0})
            _ (sim/destroy! first-sim)
            again (sim/simulation c {:floor 0})]
        (is (= [100.0 100.0] [(sim/scale first-sim) (sim/scale again)]))
        (is (= 10 (:substeps (sim/solver again))))
        (sim/destroy! again)
        (is (re-find #":scale 10: an earlier simulation built its body 100.0 times larger"
                     (str (fails {:scale 10} c))))))
    (testing "a small creature that has its body is simulated at its size"
      (let [s (sim/simulation (body/body! (util/load-blender-model
                                           "test/fixtures/strangers/hand-0.01.blend")))]
        (is (= 1.0 (sim/scale s)))
        (sim/destroy! s)))))
