(require 'cortex.blender '[cortex.body :as body] '[cortex.plan :as plan] '[cortex.sim :as sim] '[cortex.drops :as drops] '[cortex.util :as util] '[cortex.proprioception :as p] '[cortex.engine :as engine])
(def opts (read-string (or (System/getenv "OPTS") "{}")))
(def sopts (read-string (or (System/getenv "SOPTS") "{}")))
(def every (Long/parseLong (or (System/getenv "EVERY") "6")))
(def from (Double/parseDouble (or (System/getenv "FROM") "2.0")))
(def upto (Double/parseDouble (or (System/getenv "UPTO") "5.0")))
(def c (util/load-blender-model (or (System/getenv "FILE") "test/fixtures/designer/quadruped.blend")))
(let [[lo] (drops/extent c)] (.move c 0 (float (- 1.0 (double lo))) 0))
(def pl (plan/plan c opts))
(when (System/getenv "NOROWS") (alter-var-root #'cortex.engine/limit-rows! (fn [_] (fn [j _] j))))
(when-let [e (System/getenv "ROWERP")]
  (alter-var-root #'cortex.engine/limit-rows!
    (fn [f] (fn [j spec] (f j spec) (let [[_ l] (.get ^java.util.Map @(resolve 'cortex.engine/limit-rows) j)] (clojure.lang.Reflector/setInstanceField l "erp" (float (Double/parseDouble e)))) j))))
(body/body! c opts)
(def mass (into {} (map (juxt :id :mass)) (:segments pl)))
(def total (reduce + (vals mass)))
(def described (into {} (map (juxt :name :description)) (body/joint-records c)))
(def sensors (p/sensors c))
(def s (sim/simulation c (merge {:floor {:height 0 :friction (Double/parseDouble (or (System/getenv "FRICTION") "1.0"))} :observe #{:segments}} sopts)))
(println engine/label (sim/solver s) opts sopts)
(defn fmt [x] (format "%.2f" (double x)))
(dotimes [i (int (* 60 upto))]
  (let [o (sim/step! s) t (/ (inc i) 60.0)]
    (when (and (>= t (- from 1e-9)) (zero? (mod (inc i) every)))
      (let [segs (:segments o)
            com (/ (reduce + (for [[n {[_ y] :position}] segs] (* (mass n) y))) total)
            sp (fn [v] (Math/sqrt (reduce + (map * v v))))
            fast (sort-by (comp - second) (for [[n {v :velocity}] segs] [n (sp v)]))
            ov (sort-by (comp - second) (for [{n :name :as se} sensors] [n (drops/limit-overshoot se (described n))]))
            js (into {} (for [se sensors] [(:name se) (p/joint-state se)]))]
        (if (System/getenv "SHORT")
          (let [r (:rotation (segs "torso"))]
            (print (format " %.1f:%.3f/%.2f/%.1f" t com (second (p/rotate r [0 1 0])) (second (first fast))))
            (flush))
        (println (format "%5.2f com %.3f E %.2f fast %s %.2f / %s %.2f | over %s %.2f %s %.2f | torso y %.3f"
                         t com (drops/energy s) (ffirst fast) (second (first fast)) (first (second fast)) (second (second fast))
                         (ffirst ov) (second (first ov)) (first (second ov)) (second (second ov))
                         (double (second (:position (segs "torso")))))))
        (when (System/getenv "POS")
          (let [r (:rotation (segs "torso"))]
            (println "     torso up" (mapv fmt (p/rotate r [0 1 0])) "fwd" (mapv fmt (p/rotate r [1 0 0])) "pos" (mapv fmt (:position (segs "torso")))))
          (doseq [n ["lower-leg-front-r" "lower-leg-front-l" "lower-leg-back-r" "lower-leg-back-l" "head" "tail-3"]]
            (println "    " n (mapv fmt (:position (segs n))) "v" (mapv fmt (:velocity (segs n))) "axis" (mapv fmt (p/rotate (:rotation (segs n)) [0 1 0])))))
        (when (System/getenv "JOINTS")
          (doseq [[n j] (sort js)]
            (println "    " n (if (= :hinge (:type j)) (str (fmt (:angle j)) " v " (fmt (:velocity j)) " lim " (:limit (described n)))
                                (str "swing " (mapv fmt (:swing j)) " twist " (fmt (:twist j)) " w " (mapv fmt (:angular-velocity j))
                                     (when (= :cone (:type j)) (str " eng " (mapv #(mapv fmt %) (drops/cone-angles (first (filter #(= n (:name %)) sensors)) (described n))))))))))))))
(shutdown-agents)
