;; The limp four-legged creature on friction FR (0.25): energy, the tail's tip and the torso every
;; half second. bin/lein run -m clojure.main notebook/limp/stand-trace.clj
(require '[cortex.blender] '[cortex.util :as util] '[cortex.drops :as drops] '[cortex.body :as body] '[cortex.sim :as sim] '[cortex.engine :as engine])
(let [fr (Double/parseDouble (or (System/getenv "FR") "0.25"))
      c (util/load-blender-model "test/fixtures/designer/quadruped.blend")]
  (drops/lift! c) (body/body! c)
  (let [s (sim/simulation c {:floor {:height 0 :friction fr} :observe #{:segments}})
        e0 (drops/energy s)]
    (doseq [i (range 600)]
      (let [o (sim/step! s {})]
        (when (zero? (mod (inc i) 30))
          (let [t3 (get-in o [:segments "tail-3"]) torso (get-in o [:segments "torso"])]
            (println (format "E %.1f s energy %.2f J (start %.2f) tail-3 y %.3f rot %s |v| %.2f torso y %.3f rot %s" (/ (inc i) 60.0) (drops/energy s) e0
                             (get-in t3 [:position 1]) (mapv #(format "%.2f" %) (:rotation t3))
                             (Math/sqrt (reduce + (map * (:velocity t3) (:velocity t3))))
                             (get-in torso [:position 1]) (mapv #(format "%.2f" %) (:rotation torso))))))))))
(shutdown-agents) (System/exit 0)
