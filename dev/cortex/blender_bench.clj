;; Generated from org/blender.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender-bench
  "Median load times: cortex's .blend reader against jme3-blender.
  Run with `lein run -m cortex.blender-bench [runs]`."
  (:require [clojure.java.io :as io]
            [cortex.blender :as blender]
            [cortex.util :as util])
  (:import [com.jme3.asset DesktopAssetManager]
           [com.jme3.asset.plugins FileLocator]
           [com.jme3.scene.plugins.blender BlenderLoader]
           [java.io File]
           [java.util.logging Logger Level]))

(set! *warn-on-reflection* true)

(defn- time-ms
  "Wall time of one call of `f` in milliseconds, or nil when it throws."
  [f]
  (try (let [t0 (System/nanoTime)]
         (f)
         (/ (- (System/nanoTime) t0) 1e6))
       (catch Throwable _ nil)))

(defn medians
  "Median times of `fs` (thunks) over `runs` rounds, after ten rounds
  to let the JIT compile both readers. Each round calls every thunk
  once, so a machine that is busy for a while slows all of them alike;
  a thunk that ever throws gets nil."
  [runs fs]
  (dotimes [_ 10] (doseq [f fs] (time-ms f)))
  (let [rounds (for [_ (range runs)] (mapv time-ms fs))]
    (vec (for [i (range (count fs))
               :let [ts (map #(nth % i) rounds)]]
           (when (every? some? ts)
             (nth (sort ts) (quot runs 2)))))))

(defn bench-files
  "Corpus files, fixtures and creatures that exist."
  []
  (concat
   (sort (filter #(.endsWith (str %) ".blend")
                 (.listFiles (io/file "../shared/corpus/blend-legacy"))))
   (sort (filter #(.endsWith (str %) ".blend") (file-seq (io/file "test/fixtures/blend"))))
   (sort (filter #(.endsWith (str %) ".blend") (file-seq (io/file "assets/Models"))))))

(defn -main
  "Print a table of median load times and ratios."
  [& [runs]]
  (.setLevel (Logger/getLogger "com.jme3") Level/OFF)
  (let [runs (if runs (Long/parseLong runs) 21)
        am (util/asset-manager {:new true})
        theirs-am (doto (DesktopAssetManager. true)
                    (.registerLocator "/" FileLocator)
                    (.registerLoader BlenderLoader ^"[Ljava.lang.String;" (into-array String ["blend"])))
        rows (for [^File f (bench-files)]
               (let [theirs-reads? (some? (time-ms #(.loadModel theirs-am (.getCanonicalPath f))))
                     [ours theirs] (medians runs
                                            (cond-> [#(blender/load-blender-model am (str f))]
                                              theirs-reads?
                                              (conj #(do (.clearCache theirs-am)
                                                         (.loadModel theirs-am (.getCanonicalPath f))))))]
                 [(str f) ours theirs]))]
    (println (format "%-62s %10s %14s %7s" "file" "cortex ms" "jme3-blender" "ratio"))
    (doseq [[f ours theirs] rows]
      (println (format "%-62s %10s %14s %7s" f
                       (if ours (format "%.2f" ours) "FAIL")
                       (if theirs (format "%.2f" theirs) "-")
                       (if (and ours theirs) (format "%.1fx" (/ theirs ours)) ""))))
    (let [both (filter #(and (second %) (nth % 2)) rows)]
      (when (seq both)
        (println (format "geometric mean speed-up over %d files jme3-blender reads: %.1fx"
                         (count both)
                         (Math/exp (/ (reduce + (map #(Math/log (/ (nth % 2) (second %))) both))
                                      (count both)))))))
    (shutdown-agents)))
