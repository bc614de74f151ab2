(ns cortex.blender
  "Load Blender creatures into jME: cortex's own .blend reader, for
  files saved by Blender 2.48 through 5.0.

  Entry points: `load-blender-model` (a file or asset as a jME Node;
  also reachable as cortex.util/load-blender-model), `read-blend` (a
  file as data, no jME), `load-bytes`, `register-loader!` (make any
  AssetManager read .blend files with cortex's reader)."
  (:require [clojure.java.io :as io]
            [cortex.blender.file :as file]
            [cortex.blender.scene :as scene]
            [cortex.blender.jme :as jme]
            [cortex.util :as util])
  (:import [com.jme3.asset AssetManager AssetInfo ModelKey]
           [java.io File InputStream]
           [java.nio.file Files]))

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

(defn read-blend
  "Read a .blend file into data: the parsed file under :file (header,
  blocks, SDNA) and the scene under :scene-data (see
  cortex.blender.scene/scene-data). `source` is a path, File,
  InputStream or byte array; `name` names it in errors."
  ([source] (read-blend source (if (bytes? source) "<bytes>" (str source))))
  ([source name]
   (guarded name
            (fn []
              (let [bf (file/parse name (read-all source))]
                {:file bf :scene-data (scene/scene-data bf)})))))

(defn load-bytes
  "A jME scene graph (see cortex.blender.jme/scene-graph) of the .blend
  file in byte array `bs`, named `name`; materials need `am`."
  [^AssetManager am name bs]
  (guarded name
           (fn []
             (let [bf (file/parse name bs)]
               (jme/scene-graph am name (scene/scene-data bf))))))

(defn load-asset-info
  "What cortex.BlendLoader calls: load the asset jME opened."
  [^AssetInfo info]
  (let [name (.getName (.getKey info))]
    (load-bytes (.getManager info) name
                (guarded name #(with-open [in (.openStream info)] (.readAllBytes in))))))

(defn register-loader!
  "Make `am` load .blend files with cortex's reader, over any loader
  (jme3-blender's) registered for them before."
  [^AssetManager am]
  (.registerLoader am cortex.BlendLoader (into-array String ["blend"]))
  am)

(defn load-blender-model
  "Load a Blender model as a jME Node. `model` is an asset name (such as
  \"Models/test-creature/worm.blend\", found on the classpath or under
  assets/) or the path of a .blend file. Errors are ex-info naming the
  file."
  ([model] (load-blender-model (util/asset-manager) model))
  ([^AssetManager am model]
   (let [f (io/file (str model))]
     (if (.isFile f)
       (load-bytes am (str model) (guarded (str model) #(read-all f)))
       (try (.loadModel am (ModelKey. (str model)))
            (catch com.jme3.asset.AssetNotFoundException e
              (throw (ex-info (str model ": no such file, nor asset under assets/ or on the classpath")
                              {:file (str model)} e))))))))

