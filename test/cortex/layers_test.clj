;; Generated from org/index.org by lein tangle: edit the chapter, not this file.
(ns cortex.layers-test
  (:require [clojure.java.shell :as sh]
            [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.tangle :as tangle]))

(set! *warn-on-reflection* true)

(defn- loaded-after
  "The cortex namespaces a fresh JVM on this classpath has loaded after
  requiring `namespaces`."
  [namespaces]
  (let [form (pr-str `(do (apply require '~namespaces)
                          (prn (sort (filter #(str/starts-with? % "cortex")
                                             (map (comp str ns-name) (all-ns)))))))
        {:keys [exit out err]} (sh/sh "java" "-cp" (System/getProperty "java.class.path")
                                      "clojure.main" "-e"
                                      (str "(require 'clojure.string) " form))]
    (is (zero? exit) err)
    (read-string (last (str/split-lines out)))))

(deftest body-and-world-do-not-load-the-reader
  (let [loaded (set (loaded-after '[cortex.body cortex.world]))]
    (is (contains? loaded "cortex.body"))
    (is (contains? loaded "cortex.world"))
    (is (not-any? #(str/starts-with? % "cortex.blender") loaded)
        (str "the reader was loaded: " (sort loaded)))))

(deftest the-step-loop-loads-neither-the-reader-nor-the-renderer
  (let [loaded (set (loaded-after '[cortex.sim]))]
    (is (contains? loaded "cortex.sim"))
    (is (not-any? #(or (str/starts-with? % "cortex.blender") (= % "cortex.render")
                       (= % "cortex.sight") (= % "cortex.physics-tab"))
                  loaded)
        (str "requiring cortex.sim loaded " (sort loaded)))))

(deftest hooks-say-what-to-require
  (let [form (pr-str
              '(do (require 'cortex.util 'cortex.body 'cortex.sim)
                   (defn message [f] (try (f) "no error" (catch Exception e (ex-message e))))
                   (println "reader:" (message #(cortex.util/load-blender-model
                                                 "Models/test-creature/worm-eyes.blend")))
                   (require 'cortex.blender)
                   (let [c (cortex.body/body! (cortex.util/load-blender-model
                                               "Models/test-creature/worm-eyes.blend"))]
                     (println "segments:" (count (cortex.body/segments c)))
                     (println "eyes:" (message #(cortex.sim/simulation c {:eyes true}))))
                   (shutdown-agents)))
        {:keys [exit out err]} (sh/sh "java" "-cp" (System/getProperty "java.class.path")
                                      "clojure.main" "-e" form)
        ;; a line each, found by its label (an engine may print its own)
        said (fn [k] (some #(when (str/starts-with? % (str k ": ")) (subs % (+ 2 (count k))))
                           (str/split-lines out)))]
    (is (zero? exit) err)
    (is (re-find #"needs the \.blend reader.*\(require 'cortex\.blender\)" (str (said "reader"))) out)
    (is (= "2" (said "segments")) "with the reader loaded, the seed's loader loads")
    (is (re-find #"needs cortex\.sight.*\(require 'cortex\.sight\)" (str (said "eyes"))) out)))

(def ^:private layers
  "The library's namespaces, lowest first."
  ["cortex.export.geometry" "cortex.geometry" "cortex.strength" "cortex.engine" "cortex.engine-contract" "cortex.mass" "cortex.sense"
   "cortex.projection" "cortex.util" "cortex.world"
   "cortex.blender.bytes" "cortex.blender.file" "cortex.blender.math" "cortex.blender.mesh"
   "cortex.blender.rigid-body" "cortex.blender.scene" "cortex.blender.jme" "cortex.blender"
   "cortex.shapes" "cortex.segment" "cortex.nearest" "cortex.joint" "cortex.vision"
   "cortex.rigid-body" "cortex.constraint" "cortex.plan" "cortex.body" "cortex.physics-tab"
   "cortex.proprioception" "cortex.muscle" "cortex.touch" "cortex.sim"
   "cortex.export.xml" "cortex.export.model" "cortex.export.urdf"
   "cortex.export"
   "cortex.render" "cortex.sight" "cortex.demo" "cortex.test.body" "cortex.rollout"
   "cortex.main"])

(def ^:private late-reaches
  "The requiring-resolves that reach up, on purpose: [namespace target]."
  #{["cortex.rollout" nil]})

(defn- ns-form
  [^java.io.File file]
  (binding [*read-eval* false]
    (with-open [r (java.io.PushbackReader. (clojure.java.io/reader file))]
      (read r))))

(defn- library-files []
  (for [dir ["src" "engine/jbullet/src" "engine/native/src"]
        ^java.io.File f (file-seq (java.io.File. ^String dir))
        :when (str/ends-with? (.getName f) ".clj")]
    f))

(defn- cortex-requires
  [form]
  (for [[k & specs] (drop 2 form) :when (and (seq? (list* k specs)) (= :require k))
        spec specs
        :let [n (str (if (sequential? spec) (first spec) spec))]
        :when (str/starts-with? n "cortex")]
    n))

(deftest every-namespace-requires-only-lower-layers
  (let [place (zipmap layers (range))]
    (doseq [f (library-files)
            :let [form (ns-form f)
                  me (str (second form))]]
      (is (contains? place me) (str me " (" f ") has no place in the layers"))
      (doseq [r (cortex-requires form)]
        (is (< (long (place r Long/MAX_VALUE)) (long (place me -1)))
            (str me " requires " r ", which is not below it"))))))

(deftest reaches-up-are-only-the-deliberate-ones
  (doseq [f (library-files)
          :let [text (slurp f)
                me (str (second (ns-form f)))]
          [_ target] (re-seq #"requiring-resolve\s+'?([\w.-]*)" text)
          :let [target-ns (when (str/starts-with? target "cortex") target)]]
    (is (contains? late-reaches [me target-ns])
        (str me " reaches up to " (or target-ns target) " with requiring-resolve"))))


(defn- required
  "The namespaces the ns form at the head of `file` requires."
  [^java.io.File file]
  (let [[_ _ & clauses] (binding [*read-eval* false]
                          (with-open [r (java.io.PushbackReader. (clojure.java.io/reader file))]
                            (read r)))]
    (for [[k & specs] clauses :when (= :require k)
          spec specs]
      (if (sequential? spec) (first spec) spec))))

(deftest no-tool-requires-a-test
  (let [tools (for [dir ["dev" "engine/jbullet/dev" "engine/native/dev"]
                    ^java.io.File f (file-seq (java.io.File. ^String dir))
                    :when (str/ends-with? (.getName f) ".clj")]
                f)]
    (is (< 10 (count tools)) "the tools are found")
    (doseq [f tools]
      (is (not-any? #(str/ends-with? (name %) "-test") (required f)) (str f)))))

(def ^:private tests-reaching-ahead
  "[test namespace, namespace of a later chapter] a test may require,
  and why."
  {["cortex.shapes-test" "cortex.body"] "shapes are checked on whole bodies, built by body!"
   ["cortex.shapes-test" "cortex.sim"] "small bodies rest, and take more substeps, in a simulation"
   ["cortex.body-test" "cortex.body"] "the seed's functions, tested where the seed's chapter explains them"
   ["cortex.designer-test" "cortex.body"] "designers' creatures, built by body!"
   ["cortex.designer-test" "cortex.drops"] "designers' creatures, dropped to rest"
   ["cortex.plan-test" "cortex.drops"] "a plan built from text falls as body!'s creature does"
   ["cortex.plan-test" "cortex.sim"] "... stepped, observation by observation"
   ["cortex.plan-test" "cortex.muscle"] "a plan's muscles are those cortex.muscle sizes on the built body"
   ["cortex.plan-test" "cortex.physics-tab"] "the plan of a Physics-tab creature is physics-body!'s"
   ["cortex.muscle-test" "cortex.sim"] "muscles are checked by stepping creatures"})

(defn- reading-order
  "The chapters of the reading list, in order, as file names."
  []
  (map second (re-seq #"(?m)^\s*\d+\.\s+\[\[file:([\w.-]+\.org)\]" (slurp "org/index.org"))))

(defn- tangled-clj
  "The Clojure files (as paths from the project's root) `chapter` tangles."
  [chapter]
  (let [root (.getCanonicalPath (java.io.File. "."))]
    (distinct
     (for [b (tangle/blocks chapter (slurp (str "org/" chapter)))
           :let [t (get-in b [:args :tangle])]
           :when (and t (str/ends-with? t ".clj"))
           :let [f (.getCanonicalPath (java.io.File. (java.io.File. "org") ^String t))]
           :when (str/starts-with? f root)]
       (subs f (inc (count root)))))))

(deftest chapters-require-only-earlier-chapters
  (let [order (reading-order)
        files (for [[i c] (map-indexed vector order), f (tangled-clj c)
                    :let [form (ns-form (java.io.File. ^String f))]]
                {:chapter c :place i :file f :ns (str (second form))
                 :requires (cortex-requires form)})
        owner (reduce (fn [m {:keys [ns place chapter]}]
                        (if (contains? m ns) m (assoc m ns [place chapter])))
                      {"cortex.engine" [(.indexOf ^java.util.List order "engine-contract.org")
                                        "engine-contract.org"]}
                      (sort-by :place files))]
    (is (< 30 (count order)) "the reading list is found")
    (is (< 80 (count files)) "the chapters' files are found")
    (doseq [{:keys [chapter place file ns requires]} files
            r requires
            :let [[p c] (owner r)]
            :when (and p (> (long p) (long place))
                       (not (contains? tests-reaching-ahead [ns r])))]
      (is false (str chapter " (" file ", " ns ") requires " r
                     ", which " c " writes later in the book")))
    (testing "every reach ahead listed is still made"
      (doseq [[[t r] _] tests-reaching-ahead]
        (is (some #(and (= t (:ns %)) (some #{r} (:requires %))) files)
            (str t " no longer requires " r ": take it off the list"))))))
