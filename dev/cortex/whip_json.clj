;; Generated from org/physics-trust.org by lein tangle: edit the chapter, not this file.
(ns cortex.whip-json
  "A creature placed and built as the drop test does it, written as JSON
  (the model scripts/compare/quadruped_whip.py built before it loaded
  the MJCF export), and a drop's speeds as CSV for its picture (the
  physics-trust chapter).

  Entry point: `-main` (lein run -m cortex.whip-json FILE.blend OUT.json;
  lein run -m cortex.whip-json speeds FILE.blend OUT.csv [friction]: every
  segment's speed at every step of the drop's first 3 s)."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [cortex.compare :as compare]
            [cortex.engine :as engine]
            [cortex.drops :as drops]
            [cortex.util :as util]))

(set! *warn-on-reflection* true)

(defn- speeds-csv
  "`series` (see cortex.drops/speeds) as CSV text: a
  comment naming the engine and floor, a header, a row a step."
  [series friction]
  (let [names (keys (second (first series)))]
    (str "# engine: cortex (" engine/label
         "), friction " friction ", step 1/60 s\n"
         (str/join "," (cons "time" names)) "\n"
         (str/join (for [[t ss] series]
                     (str (str/join "," (cons (format "%.4f" (double t))
                                              (map #(format "%.4f" (double (ss %))) names)))
                          "\n"))))))

(defn -main
  "lein run -m cortex.whip-json FILE.blend OUT.json
  lein run -m cortex.whip-json speeds FILE.blend OUT.csv [friction]"
  [& [a b c d]]
  (let [[out text] (if (= "speeds" a)
                     (let [friction (Double/parseDouble (or d "0.5"))]
                       [c (speeds-csv (drops/speeds (util/load-blender-model b) friction 180) friction)])
                     [b (compare/json (drops/export (util/load-blender-model a)))])]
    (io/make-parents (io/file out))
    (spit out text)
    (println "wrote" out)
    (shutdown-agents)))
