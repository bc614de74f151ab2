;; Generated from org/blender.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender
  "Load Blender creatures into jME: cortex's own .blend reader, for
  files saved by Blender 2.48 through 5.2.

  Entry points: `load-blender-model` (a file or asset as a jME Node, the
  saved scene or one chosen by name; also reachable as
  cortex.util/load-blender-model), `scenes` (a file's scenes),
  `read-blend` (a file as data, no jME), `load-bytes`, `register-loader!` (make any
  AssetManager read .blend files with cortex's reader)."
  (:require [clojure.java.io :as io]
            [cortex.blender.file :as file]
            [cortex.blender.scene :as scene]
            [cortex.blender.jme :as jme]
            [cortex.util :as util])
  (:import [com.jme3.asset AssetManager AssetInfo ModelKey]
           [com.jme3.scene Node]
           [java.io File InputStream]
           [java.nio.file Files]
           [java.util.logging Logger]))

(set! *warn-on-reflection* true)

(defn- read-all
  "All bytes of `source`: a File, a path, an InputStream or bytes."
  ^bytes [source]
  (cond
    (bytes? source) source
    (instance? File source) (Files/readAllBytes (.toPath ^File source))
    (instance? InputStream source) (with-open [in ^InputStream source] (.readAllBytes in))
    :else (Files/readAllBytes (.toPath (io/file (str source))))))

(defn- guarded
  "Run `f`, turning any failure that is not already a named ex-info
  into one naming `source`: malformed data must surface as ex-info,
  whatever part of the reader trips over it."
  [source f]
  (try
    (f)
    (catch clojure.lang.ExceptionInfo e
      (if (:file (ex-data e))
        (throw e)
        (throw (ex-info (str source ": " (.getMessage e)) (assoc (ex-data e) :file (str source)) e))))
    (catch Exception e
      (throw (ex-info (str source ": malformed .blend file (" (.getName (class e)) ": "
                           (.getMessage e) ")")
                      {:file (str source)} e)))
    (catch StackOverflowError e
      (throw (ex-info (str source ": malformed .blend file (structure nested too deep)")
                      {:file (str source)} e)))
    (catch OutOfMemoryError e
      (throw (ex-info (str source ": malformed .blend file (too large to hold in memory)")
                      {:file (str source)} e)))))

(def ^:private ^Logger logger (Logger/getLogger "cortex.blender"))

(def ^:api warnings-key
  "The user data under which a loaded model's root Node keeps what the
  reader could not do as Blender would (a list of strings; see
  cortex.blender.scene/scene-data's :warnings)."
  "blender-warnings")

(defn ^:api read-blend
  "Read a .blend file into data: the parsed file under :file (header,
  blocks, SDNA) and the scene under :scene-data (see
  cortex.blender.scene/scene-data). `source` is a path, File,
  InputStream or byte array; `name` names it in errors. `opts`:
  {:scene \"Game\"} reads that scene instead of the saved one."
  ([source] (read-blend source {}))
  ([source opts-or-name]
   (if (map? opts-or-name)
     (read-blend source (if (bytes? source) "<bytes>" (str source)) opts-or-name)
     (read-blend source opts-or-name {})))
  ([source name opts]
   (guarded name
            (fn []
              (let [bf (file/parse name (read-all source))]
                {:file bf :scene-data (scene/scene-data bf opts)})))))

(defn ^:api scenes
  "The scenes of the .blend file at `source` (a path, File, InputStream
  or bytes): for each, {:name :objects :meshes :current?}, :objects
  and :meshes being how many objects and mesh objects it holds and
  :current? whether the file was saved showing it (the scene loaded
  when none is chosen)."
  [source]
  (let [name (if (bytes? source) "<bytes>" (str source))]
    (guarded name #(scene/scene-list (file/parse name (read-all source))))))

(defn load-bytes
  "A jME scene graph (see cortex.blender.jme/scene-graph) of the .blend
  file in byte array `bs`, named `name`; materials need `am`. `opts` as
  for `read-blend`. What the reader could not do as Blender would is
  logged and kept on the root Node (see `warnings-key`)."
  ([am name bs] (load-bytes am name bs {}))
  ([^AssetManager am name bs opts]
   (guarded name
            (fn []
              (let [bf (file/parse name bs)
                    sd (scene/scene-data bf opts)
                    ^Node root (jme/scene-graph am name sd)]
                (doseq [w (:warnings sd)] (.warning logger (str name ": " w)))
                (when (seq (:warnings sd))
                  (.setUserData root ^String warnings-key
                                (java.util.ArrayList. ^java.util.Collection (:warnings sd))))
                root)))))

(defn load-asset-info
  "What cortex.BlendLoader calls: load the asset jME opened."
  [^AssetInfo info]
  (let [name (.getName (.getKey info))]
    (load-bytes (.getManager info) name
                (guarded name #(with-open [in (.openStream info)] (.readAllBytes in))))))

(defn ^:api register-loader!
  "Make `am` load .blend files with cortex's reader, over any loader
  (jme3-blender's) registered for them before."
  [^AssetManager am]
  (.registerLoader am cortex.BlendLoader (into-array String ["blend"]))
  am)

(defn ^:api load-blender-model
  "Load a Blender model as a jME Node. `model` is an asset name (such as
  \"Models/test-creature/worm.blend\", found on the classpath or under
  assets/) or the path of a .blend file; `am` the asset manager
  (cortex.util's own when not given); `opts` a map: {:scene \"Game\"}
  loads that scene instead of the one the file was saved showing (see
  `scenes`). Errors are ex-info naming the file. Forms: (model),
  (model opts), (am model), (am model opts)."
  ([model] (load-blender-model (util/asset-manager) model {}))
  ([am-or-model model-or-opts]
   (if (instance? AssetManager am-or-model)
     (load-blender-model am-or-model model-or-opts {})
     (load-blender-model (util/asset-manager) am-or-model model-or-opts)))
  ([^AssetManager am model opts]
   (let [f (io/file (str model))
         opts (or opts {})]
     (cond
       (.isFile f)
       (load-bytes am (str model) (guarded (str model) #(read-all f)) opts)
       (empty? opts)
       (try (.loadModel am (ModelKey. (str model)))
            (catch com.jme3.asset.AssetNotFoundException e
              (throw (ex-info (str model ": no such file, nor asset under assets/ or on the classpath")
                              {:file (str model)} e))))
       :else
       (let [info (.locateAsset am (ModelKey. (str model)))]
         (when-not info
           (throw (ex-info (str model ": no such file, nor asset under assets/ or on the classpath")
                           {:file (str model)})))
         (load-bytes am (str model)
                     (guarded (str model) #(with-open [in (.openStream info)] (.readAllBytes in)))
                     opts))))))


;; cortex.util/load-blender-model, the seed's name, is this function
;; once the reader is loaded (see the utilities chapter)
(util/install-blend-reader! #'load-blender-model)
