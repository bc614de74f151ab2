;; Generated from org/physics-trust.org by lein tangle: edit the chapter, not this file.
(ns cortex.trust-matrix
  "The physics-trust drop (see cortex.drops/drop!) under
  solver and joint settings, alternating in one JVM, as a table: worst
  overshoot (times its allowance), worst joint, rest, and the humanoid's
  steps per CPU second (sleeping off) relative to the first setting.
  jBullet only (cortex.JointLimit is a jBullet constraint).

  bin/lein run -m cortex.trust-matrix SETTING...   each a name in
  `configs` or an EDN map ({:rows false} builds without cortex's limit
  rows); FRICTIONS=0.5,1.0 CREATURES=hand,humanoid NOSPEED=1 narrow the
  run."
  (:require [cortex.body :as body]
            [cortex.drops :refer [extent overshoot]]
            [cortex.sim :as sim]
            [cortex.blender]
            [cortex.util :as util]
            [clojure.string :as str])
  (:import (com.jme3.bounding BoundingBox)
           (com.jme3.scene Geometry Node)
           (com.jme3.bullet PhysicsSpace)
           (com.jme3.bullet.joints HingeJoint SixDofJoint)
           (com.bulletphysics.dynamics.constraintsolver ContactSolverInfo SolverMode)
           (java.lang.management ManagementFactory)))

(def creatures
  [["humanoid" #(util/load-blender-model "test/fixtures/humanoid/humanoid.blend")]
   ["heavy-hands" #(util/load-blender-model "test/fixtures/humanoid/humanoid-heavy-hands.blend")]
   ["quadruped" #(util/load-blender-model "test/fixtures/designer/quadruped.blend")]
   ["hand" #(util/load-blender-model "Models/test-creature/hand.blend")]
   ["chain-100" #((requiring-resolve 'cortex.bench.creatures/creature)
                  ((requiring-resolve 'cortex.bench.creatures/chain) 100))]])

(defn configure!
  "Apply config `cfg` to simulation `s` of `creature`."
  [cfg s creature]
  (let [^PhysicsSpace space (:space s)
        ^ContactSolverInfo info (.getSolverInfo (.getDynamicsWorld space))]
    ;; {:tail {:passes n :points p}}: cortex.LimitSolver's passes (0:
    ;; none, jBullet's solver as it is), holding the pivots too when p
    (when-let [{:keys [passes points]} (:tail cfg)]
      (.setConstraintSolver ^com.bulletphysics.dynamics.DiscreteDynamicsWorld (.getDynamicsWorld space)
                            (cortex.LimitSolver. (int passes) (boolean points))))
    (when-let [n (:iterations cfg)] (set! (.numIterations info) (int n)))
    (when-let [v (:erp cfg)] (set! (.erp info) (float v)))
    (when-let [v (:erp2 cfg)] (set! (.erp2 info) (float v)))
    (when (contains? cfg :split) (set! (.splitImpulse info) (boolean (:split cfg))))
    (when-let [v (:slop cfg)] (set! (.linearSlop info) (float v)))
    (when-let [v (:warm cfg)] (set! (.warmstartingFactor info) (float v)))
    (when (:no-random cfg)
      (set! (.solverMode info) (int (bit-and (.solverMode info) (bit-not SolverMode/SOLVER_RANDMIZE_ORDER)))))
    (when-let [k (:substeps cfg)]
      (.setAccuracy space (float (/ (float sim/tpf) (float k)))))
    (when (:no-self cfg)
      (doseq [[^Geometry g rb] (:controls s)]
        (if (= "floor" (.getName g))
          (.setCollideWithGroups ^com.jme3.bullet.collision.PhysicsCollisionObject rb (int 3))
          (do (.setCollisionGroup ^com.jme3.bullet.collision.PhysicsCollisionObject rb (int 2))
              (.setCollideWithGroups ^com.jme3.bullet.collision.PhysicsCollisionObject rb (int 1))))))
    (when-let [lim (:limits cfg)]
      (doseq [{:keys [physics-joint type description] :as rec} (body/joint-records creature)
              :when (#{:hinge :cone} type)]
        (let [{:keys [frame-a frame-b axis]} ((requiring-resolve 'cortex.proprioception/rest-frames) rec)
              ^com.bulletphysics.dynamics.RigidBody
              ra (.getObjectId (.getBodyA ^com.jme3.bullet.joints.PhysicsJoint physics-joint))
              ^com.bulletphysics.dynamics.RigidBody
              rb (.getObjectId (.getBodyB ^com.jme3.bullet.joints.PhysicsJoint physics-joint))
              da #(double-array (map double %))
              c (if (= type :hinge)
                  (let [[lo hi] (:limit description)]
                    (cortex.JointLimit. ra rb ^doubles (da frame-a) ^doubles (da frame-b) ^doubles (da axis)
                                        (double lo) (double hi)))
                  (cortex.JointLimit. ra rb ^doubles (da frame-a) ^doubles (da frame-b) (double (:twist description))
                                      (double (:limit-xz description)) (double (:limit-xy description))))]
          (when-let [v (:erp lim)] (set! (.erp ^cortex.JointLimit c) (float v)))
          (when (contains? lim :spec) (set! (.speculative ^cortex.JointLimit c) (boolean (:spec lim))))
          (when-let [v (:act lim)] (set! (.activation ^cortex.JointLimit c) (double v)))
          (when-not (:keep-engine lim)
            (if (= type :hinge)
              (.setLimit ^HingeJoint physics-joint (float 1) (float -1))
              (dotimes [i 3]
                (doto (.getRotationalLimitMotor ^SixDofJoint physics-joint i)
                  (.setLoLimit (float 1)) (.setHiLimit (float -1))))))
          (.addConstraint (.getDynamicsWorld space) c true))))
    (doseq [{:keys [physics-joint]} (body/joint-records creature)]
      (cond
        (and (instance? HingeJoint physics-joint) (:hinge cfg))
        (let [^HingeJoint h physics-joint
              [soft bias relax] (:hinge cfg)]
          (.setLimit h (.getLowerLimit h) (.getUpperLimit h) (float soft) (float bias) (float relax)))
        (and (instance? SixDofJoint physics-joint) (:sixdof cfg))
        (let [^SixDofJoint j physics-joint
              {:keys [erp softness damping bounce max-force]} (:sixdof cfg)]
          (dotimes [i 3]
            (let [m (.getRotationalLimitMotor j i)]
              (when erp (.setERP m (float erp)))
              (when softness (.setLimitSoftness m (float softness)))
              (when damping (.setDamping m (float damping)))
              (when bounce (.setBounce m (float bounce)))
              (when max-force (.setMaxLimitForce m (float max-force))))))))))

(defn step! [cfg s]
  (let [k (int (or (:substeps cfg) 1))]
    (if (= 1 k)
      (sim/step! s)
      (do (.update ^PhysicsSpace (:space s) (float sim/tpf) k)
          (.distributeEvents ^PhysicsSpace (:space s))
          (sim/observe s)))))

(defn body-opts [cfg]
  (cond-> {}
    (:ang-damp cfg) (assoc :angular-damping (:ang-damp cfg))
    (:sleep cfg) (assoc :sleeping-thresholds (:sleep cfg))))

(defn build!
  "body! `creature` with `cfg`'s body options; without cortex's limit
  rows (cortex.engine/limit-rows!) when `cfg` has :rows false."
  [cfg ^Node creature opts]
  (if (false? (:rows cfg))
    (with-redefs [cortex.engine/limit-rows! (fn [joint _] joint)]
      (body/body! creature opts))
    (body/body! creature opts)))

(defn drop! [cfg ^Node creature friction]
  (let [[lo hi] (extent creature)
        _ (.move creature 0 (float (- 1.0 lo)) 0)
        _ (build! cfg creature (body-opts cfg))
        limit (+ 1.0 (Math/sqrt (* 2 9.81 (+ 1.0 (- hi lo)))))
        described (into {} (map (juxt :name :description)) (body/joint-records creature))
        s (sim/simulation creature {:floor {:height 0 :friction friction} :observe #{:joints :segments}})
        _ (configure! cfg s creature)
        start (sim/observe s)
        past (fn [obs] (into {} (for [[n j] (:joints obs)] [n (overshoot j (described n))])))
        start-past (past start)
        speed (fn [obs] (apply max (for [[_ {:keys [velocity]}] (:segments obs)]
                                     (Math/sqrt (reduce + (map #(* % %) velocity))))))
        obs (vec (repeatedly 600 #(step! cfg s)))
        still-from (loop [i 599] (if (and (>= i 0) (< (speed (obs i)) 0.05)) (recur (dec i)) (inc i)))
        moved (apply max (for [[n {p1 :position}] (:segments (obs 599))
                               :let [p0 (get-in obs [479 :segments n :position])]]
                           (Math/sqrt (reduce + (map #(let [d (- %1 %2)] (* d d)) p1 p0)))))
        pasts (for [o obs [n p] (past o)] [n (- p (start-past n))])
        [wj wp] (reduce (fn [[_ bp :as b] [_ p :as x]] (if (> p bp) x b)) [nil 0.0] pasts)]
    {:fastest (apply max (map speed obs)) :limit limit
     :worst-past wp :worst-joint wj
     :still-at (when (< still-from 600) (/ still-from 60.0)) :moved moved
     :rest? (and (< still-from 600) (< moved 0.02))}))

(defn cpu-ns ^long [] (.getCurrentThreadCpuTime (ManagementFactory/getThreadMXBean)))

(defn speed-run
  "Steps per CPU second of the humanoid, sleeping off, 300 warm-up and
  `n` timed steps."
  [cfg n]
  (let [c (build! cfg ((second (first creatures))) (assoc (body-opts cfg) :sleeping-thresholds [0 0]))
        s (sim/simulation c {:floor {:height -0.2 :friction 1.0} :observe #{}})]
    (configure! cfg s c)
    (dotimes [_ 300] (step! cfg s))
    (let [t0 (cpu-ns)]
      (dotimes [_ n] (step! cfg s))
      (/ n (/ (- (cpu-ns) t0) 1e9)))))

(def configs
  {"base" {}
   "sub2" {:substeps 2}
   "sub4" {:substeps 4}
   "it20" {:iterations 20}
   "hinge1" {:hinge [1.0 0.3 1.0]}
   "hinge1b" {:hinge [1.0 0.6 1.0]}
   "6dof-stiff" {:sixdof {:softness 1.0 :max-force 1e5}}
   "6dof-erp" {:sixdof {:erp 0.8 :softness 1.0 :max-force 1e5 :damping 1.0}}
   "sub2-stiff" {:substeps 2 :hinge [1.0 0.3 1.0] :sixdof {:softness 1.0 :max-force 1e5}}
   "sub4-stiff" {:substeps 4 :hinge [1.0 0.3 1.0] :sixdof {:softness 1.0 :max-force 1e5}}
   "split" {:split true}
   "erp0.8" {:erp 0.8}
   "norand" {:no-random true}
   "lim" {:limits {}}
   "lim-keep" {:limits {:keep-engine true}}
   "lim-nospec" {:limits {:spec false}}
   "lim-erp5" {:limits {:erp 0.5}}
   "lim-sub2" {:substeps 2 :limits {}}})

(defn fmt-row [cname cr f r]
  (format "%-12s %-11s %4.2f %6.2f %6.2f %-13s %6s %7.4f %s"
          cname cr f (:fastest r) (:worst-past r) (str (:worst-joint r))
          (if (:still-at r) (format "%.1f" (:still-at r)) "never") (:moved r)
          (if (:rest? r) "rest" "NO-REST")))

(defn -main
  "bin/lein run -m cortex.trust-matrix SETTING..."
  [& names]
  (let [names (or (seq names) ["base" "sub2"])
        fr (if-let [f (System/getenv "FRICTIONS")] (mapv #(Double/parseDouble %) (str/split f #",")) [0.25 0.5 1.0])
        only (when-let [c (System/getenv "CREATURES")] (set (str/split c #",")))
        cfgs (mapv (fn [n] [n (or (configs n) (read-string n))]) names)
        results (atom {})]
    (println "config       creature    fric  fast   past   worst-joint   still   moved")
    (doseq [f fr [cr make] creatures :when (or (nil? only) (only cr))
            [cn cfg] cfgs]
      (let [r (drop! cfg (make) f)]
        (swap! results update cn (fnil conj []) r)
        (println (fmt-row cn cr f r))
        (flush)))
    (when-not (System/getenv "NOSPEED")
      (let [speeds (atom {})]
        (dotimes [_ 3]
          (doseq [[cn cfg] cfgs]
            (swap! speeds update cn (fnil conj []) (speed-run cfg 2000))))
        (println "\nsummary: config, max past (x allowance), drops not at rest, humanoid steps/s (median of 3), relative")
        (let [base (let [v (sort (@speeds (first (first cfgs))))] (nth v 1))]
          (doseq [[cn _] cfgs]
            (let [rs (@results cn)
                  sp (nth (sort (@speeds cn)) 1)]
              (println (format "%-14s past %6.2f  not-rest %2d  fastest %5.2f  steps/s %6.0f  x%.2f"
                               cn (apply max (map :worst-past rs)) (count (remove :rest? rs))
                               (apply max (map :fastest rs)) sp (/ sp base))))))))
    (shutdown-agents)
    (System/exit 0)))

