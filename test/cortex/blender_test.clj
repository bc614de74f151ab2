;; Generated from org/blender.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender-test
  (:require [clojure.test :refer [deftest is testing]]
            [clojure.java.io :as io]
            [clojure.test.check :as tc]
            [clojure.test.check.generators :as gen]
            [clojure.test.check.properties :as prop]
            [cortex.blender :as blender]
            [cortex.blender.file :as file]
            [cortex.blender.math :as m]
            [cortex.blender.mesh :as mesh]
            [cortex.blender.scene :as scene]
            [cortex.sense :as sense]
            [cortex.util :as util])
  (:import [com.jme3.scene Spatial Node Geometry]
           [com.jme3.asset DesktopAssetManager]
           [com.jme3.asset.plugins FileLocator]
           [com.jme3.math Vector3f Quaternion]
           [com.jme3.scene.plugins.blender BlenderLoader]
           [clojure.lang ExceptionInfo]
           [java.io ByteArrayOutputStream File]
           [java.nio.file Files]
           [java.util Random]
           [java.util.logging Logger Level]
           [java.util.zip GZIPOutputStream]))

(set! *warn-on-reflection* true)

(def corpus-dir
  "The shared corpus of old .blend files, beside the project."
  (io/file "../shared/corpus/blend-legacy"))

(defn corpus-files
  "The corpus .blend files, or nil (with a message) when the folder is
  missing."
  []
  (if (.isDirectory ^File corpus-dir)
    (sort-by #(.getName ^File %)
             (filter #(.endsWith (.getName ^File %) ".blend") (.listFiles ^File corpus-dir)))
    (println "SKIP: no corpus at" (str corpus-dir))))

(defn node-seq
  "Every spatial under `s`, itself first."
  [^Spatial s]
  (tree-seq #(instance? Node %) #(.getChildren ^Node %) s))

(defn object-nodes
  "The object Nodes of a loaded model (everything under the scene Node
  that is not a Geometry), by name."
  [^Node root]
  (into {} (for [^Node scene (.getChildren root)
                 s (rest (node-seq scene))
                 :when (not (instance? Geometry s))]
             [(.getName ^Spatial s) s])))

(defn parent-name
  "The name of the object Node a Node hangs from, nil at the top."
  [^Spatial s]
  (let [p (.getParent s)]
    (when (and p (.getParent p) (.getParent (.getParent p)))
      (.getName p))))

(defn triangles
  "Triangles in the Geometries directly under object Node `n`."
  [^Node n]
  (reduce + (for [c (.getChildren n) :when (instance? Geometry c)]
              (.getTriangleCount (.getMesh ^Geometry c)))))

(defn close?
  "Are numbers (or nested collections of them) equal within `tol`,
  relative to their size when that is above 1?"
  [a b tol]
  (cond
    (and (number? a) (number? b))
    (<= (Math/abs (- (double a) (double b)))
        (* (double tol) (max 1.0 (Math/abs (double a)))))
    (and (sequential? a) (sequential? b))
    (and (= (count a) (count b)) (every? true? (map #(close? %1 %2 tol) a b)))
    :else (= a b)))

(defn rotation-rows
  "A jME Quaternion as a 3x3 matrix of rows."
  [^Quaternion q]
  (let [r (.toRotationMatrix q)]
    (mapv (fn [i] (mapv (fn [j] (.get r i j)) (range 3))) (range 3))))

(defn world-matrix
  "The world transform of spatial `s` as a 4x4 of rows (jME's TRS)."
  [^Spatial s]
  (let [t (.getWorldTranslation s)
        r (rotation-rows (.getWorldRotation s))
        sc (.getWorldScale s)
        sv [(.x sc) (.y sc) (.z sc)]]
    (m/mat3->mat4 (mapv (fn [row] (mapv * row sv)) r) [(.x t) (.y t) (.z t)])))

(defn quietly
  "Run `f` with jME's logging off (jme3-blender complains at length
  about textures it cannot find), then put the level back."
  [f]
  (let [l (Logger/getLogger "com.jme3")
        old (.getLevel l)]
    (.setLevel l Level/OFF)
    (try (f) (finally (.setLevel l old)))))

(deftest corpus-files-load
  (doseq [f (corpus-files)]
    (testing (str f)
      (let [root (blender/load-blender-model (str f))]
        (is (instance? Node root))
        (is (seq (filter #(instance? Geometry %) (node-seq root))))))))

(def jme3-blender-skips
  "Corpus files jme3-blender cannot read properly."
  #{"yxa_1.blend" "box.blend"})

(deftest same-as-jme3-blender
  (quietly
   (fn []
     (let [am (doto (DesktopAssetManager. true)
                (.registerLocator "/" FileLocator)
                (.registerLoader BlenderLoader ^"[Ljava.lang.String;" (into-array String ["blend"])))]
       (doseq [^File f (corpus-files)
               :when (not (jme3-blender-skips (.getName f)))]
         (testing (.getName f)
           (let [^Node theirs (.loadModel am (.getCanonicalPath f))
                 ^Node ours (blender/load-blender-model (str f))
                 data (:scene-data (blender/read-blend (str f)))
                 modifiers (into {} (map (juxt :name :modifiers)) (:objects data))
                 tn (object-nodes theirs)
                 on (object-nodes ours)]
             (.updateGeometricState theirs)
             (.updateGeometricState ours)
             (is (= (set (keys tn)) (set (keys on))))
             (doseq [[name ^Spatial t] tn
                     :let [^Spatial o (on name)]
                     :when o]
               (testing name
                 (is (= (parent-name t) (parent-name o)))
                 (is (close? (vec (.toArray (.getWorldTranslation t) nil))
                             (vec (.toArray (.getWorldTranslation o) nil)) 1e-4))
                 (is (close? (rotation-rows (.getWorldRotation t))
                             (rotation-rows (.getWorldRotation o)) 1e-4))
                 (when (empty? (modifiers name))
                   (is (= (triangles t) (triangles o)))))))))))))

(defn read-json
  "Parse JSON text: objects become maps with string keys, arrays
  vectors, numbers Longs or Doubles."
  [^String s]
  (let [n (count s)
        pos (int-array 1)
        at (fn [] (when (< (aget pos 0) n) (.charAt s (aget pos 0))))
        skip (fn [] (while (and (< (aget pos 0) n)
                                (Character/isWhitespace (.charAt s (aget pos 0))))
                      (aset pos 0 (inc (aget pos 0)))))
        eat (fn [^String lit]
              (if (.startsWith s lit (aget pos 0))
                (aset pos 0 (+ (aget pos 0) (count lit)))
                (throw (ex-info (str "bad JSON at " (aget pos 0)) {}))))]
    (letfn [(value []
              (skip)
              (case (at)
                \{ (do (eat "{") (skip)
                       (if (= (at) \}) (do (eat "}") {})
                           (loop [m {}]
                             (skip)
                             (let [k (string)]
                               (skip) (eat ":")
                               (let [m (assoc m k (value))]
                                 (skip)
                                 (if (= (at) \,) (do (eat ",") (recur m)) (do (eat "}") m)))))))
                \[ (do (eat "[") (skip)
                       (if (= (at) \]) (do (eat "]") [])
                           (loop [v []]
                             (let [v (conj v (value))]
                               (skip)
                               (if (= (at) \,) (do (eat ",") (recur v)) (do (eat "]") v))))))
                \" (string)
                \t (do (eat "true") true)
                \f (do (eat "false") false)
                \n (do (eat "null") nil)
                (number)))
            (string []
              (eat "\"")
              (let [sb (StringBuilder.)]
                (loop []
                  (let [c (.charAt s (aget pos 0))]
                    (aset pos 0 (inc (aget pos 0)))
                    (case c
                      \" (str sb)
                      \\ (let [e (.charAt s (aget pos 0))]
                           (aset pos 0 (inc (aget pos 0)))
                           (case e
                             \u (do (.append sb (char (Integer/parseInt
                                                       (subs s (aget pos 0) (+ 4 (aget pos 0))) 16)))
                                    (aset pos 0 (+ 4 (aget pos 0))))
                             \n (.append sb \newline)
                             \t (.append sb \tab)
                             \r (.append sb \return)
                             \b (.append sb \backspace)
                             \f (.append sb \formfeed)
                             (.append sb e))
                           (recur))
                      (do (.append sb c) (recur)))))))
            (number []
              (let [start (aget pos 0)]
                (while (and (< (aget pos 0) n) (#{\- \+ \. \e \E \0 \1 \2 \3 \4 \5 \6 \7 \8 \9} (at)))
                  (aset pos 0 (inc (aget pos 0))))
                (let [t (subs s start (aget pos 0))]
                  (if (re-find #"[.eE]" t) (Double/parseDouble t) (Long/parseLong t)))))]
      (value))))

(defn oracle-pairs
  "[blend json] for every .blend with a .json beside it under
  test/fixtures (the other engineers' fixtures and this chapter's own,
  in test/fixtures/blender-reader) and assets/Models, and every corpus
  file with a dump in test/fixtures/corpus."
  []
  (concat
   (for [dir ["test/fixtures" "assets/Models"]
         ^File f (sort (file-seq (io/file dir)))
         :let [j (io/file (.replaceAll (str f) "\\.blend$" ".json"))]
         :when (and (.endsWith (.getName f) ".blend") (.isFile j))]
     [f j])
   (for [^File j (sort (file-seq (io/file "test/fixtures/corpus")))
         :when (.endsWith (.getName j) ".json")
         :let [f (io/file corpus-dir (.replaceAll (.getName j) "\\.json$" ".blend"))]
         :when (.isFile f)]
     [f j])))

(defn java->clj
  "User data back to Clojure data, for comparing."
  [v]
  (cond (instance? java.util.Map v) (into {} (for [[k x] v] [k (java->clj x)]))
        (instance? java.util.List v) (mapv java->clj v)
        :else v))

(defn same-property?
  "Is the property value we read `ours` what Blender's dump says?
  Floats compare at float precision."
  [ours theirs]
  (cond
    (and (map? ours) (map? theirs))
    (and (= (set (keys ours)) (set (keys theirs)))
         (every? #(same-property? (ours %) (theirs %)) (keys ours)))
    (and (sequential? ours) (sequential? theirs))
    (and (= (count ours) (count theirs)) (every? true? (map same-property? ours theirs)))
    (and (number? ours) (number? theirs)) (close? ours theirs 1e-6)
    :else (= ours theirs)))

(defn check-vertices
  "Every vertex of the Geometries under object Node `n`, taken to the
  world by jME, must be Blender's world matrix `w` applied to one of
  the mesh's vertices: C W v for vertex v, C the change to Y-up."
  [^Node n w md]
  (let [wy (m/mat-mul (m/mat3->mat4 m/y-up [0 0 0]) w)
        ^floats pos (:positions md)
        expected (vec (for [i (range (quot (alength pos) 3))]
                        (subvec (m/mat-vec wy [(aget pos (* 3 i)) (aget pos (+ 1 (* 3 i)))
                                               (aget pos (+ 2 (* 3 i))) 1.0])
                                0 3)))
        scale (max 1.0 (reduce max 0.0 (map #(Math/abs (double %)) (flatten expected))))]
    (doseq [c (.getChildren n) :when (instance? Geometry c)
            :let [^Geometry g c
                  fb (.getFloatBuffer (.getMesh g) com.jme3.scene.VertexBuffer$Type/Position)]]
      (is (zero? (count (for [i (range (quot (.limit fb) 3))
                              :let [v (.localToWorld g (Vector3f. (.get fb (int (* 3 i)))
                                                                  (.get fb (int (+ 1 (* 3 i))))
                                                                  (.get fb (int (+ 2 (* 3 i)))))
                                                     nil)
                                    p [(.x v) (.y v) (.z v)]]
                              :when (not-any? #(close? p % (* 1e-4 scale)) expected)]
                          p)))
          (str (.getName g) ": vertices not where Blender puts them")))))

(deftest same-as-blender
  (doseq [[^File f ^File j] (oracle-pairs)]
    (testing (str f)
      (let [oracle (read-json (slurp j))
            theirs (into {} (map (juxt #(get % "name") identity)) (get oracle "objects"))
            in-scene (set (or (get oracle "scene_objects") (keys theirs)))
            data (:scene-data (blender/read-blend (str f)))
            ours (into {} (map (juxt :name identity)) (:objects data))
            ^Node root (blender/load-blender-model (str f))
            nodes (object-nodes root)]
        (.updateGeometricState root)
        (is (= in-scene (set (keys ours))))
        (is (= in-scene (set (keys nodes))))
        (doseq [[name o] ours
                :let [t (theirs name) ^Node n (nodes name)]
                :when t]
          (testing name
            (is (= (get t "type") (:type o)))
            (is (= (get t "parent") (:parent o)))
            (is (close? (get t "matrix_world") (:world o) 1e-4))
            (is (same-property? (:properties o) (get t "properties")))
            ;; the dump counts the base mesh; a Mirror applied is checked
            ;; against the mesh Blender shows in modifiers-are-listed-...
            (when-let [tm (when-not (some :applied? (:modifiers o)) (get t "mesh"))]
              (is (= (get tm "vertices") (quot (alength ^floats (:positions (:mesh o))) 3)))
              (is (= (get tm "polygons") (alength ^ints (:counts (:mesh o)))))
              (is (= (get tm "triangles") (mesh/triangle-count (:mesh o)))))
            (when n
              (is (= (when (in-scene (get t "parent")) (get t "parent")) (parent-name n)))
              (let [wy (m/to-y-up (get t "matrix_world"))
                    {:keys [residual]} (cortex.blender.jme/world-trs (get t "matrix_world"))]
                (is (close? (m/translation wy) (m/translation (world-matrix n)) 1e-4))
                (when-not residual
                  (is (close? wy (world-matrix n) 1e-4))))
              (when-let [tm (get t "mesh")]
                (is (= (mesh/triangle-count (:mesh o)) (triangles n)))
                (when-not (some :applied? (:modifiers o))
                  (is (= (get tm "triangles") (triangles n))))
                (when (< (get tm "vertices") 2000)
                  (check-vertices n (get t "matrix_world") (:mesh o))))
              (doseq [[k v] (get t "properties")]
                (is (same-property? (java->clj (sense/meta-data n k)) v) k)))))))))

(deftest computed-worlds-match-stored
  (doseq [^File f (concat (corpus-files)
                          (filter #(.endsWith (.getName ^File %) ".blend")
                                  (file-seq (io/file "test/fixtures"))))
          :let [data (:scene-data (blender/read-blend (str f)))]
          o (:objects data)
          :when (and (:stored-world o) (not (#{5 6 7} (:partype o))))]
    (is (close? (:stored-world o) (:world o) 1e-4) (str f " " (:name o)))))

(defn uv-set
  "The set of (position, uv) pairs of the Geometries under object Node
  `n`, rounded, to compare meshes whose corners come in any order."
  [^Node n]
  (set (for [c (.getChildren n) :when (instance? Geometry c)
             :let [m (.getMesh ^Geometry c)
                   p (.getFloatBuffer m com.jme3.scene.VertexBuffer$Type/Position)
                   t (some-> (.getBuffer m com.jme3.scene.VertexBuffer$Type/TexCoord)
                             .getData)]
             :when t
             i (range (quot (.limit p) 3))]
         (mapv #(Math/round (* 1000.0 (double %)))
               [(.get p (int (* 3 i))) (.get p (int (+ 1 (* 3 i)))) (.get p (int (+ 2 (* 3 i))))
                (.get ^java.nio.FloatBuffer t (int (* 2 i)))
                (.get ^java.nio.FloatBuffer t (int (+ 1 (* 2 i))))]))))

(defn uv-pairs
  "The set of UV pairs of object `name` in file `f`, as read-blend has
  them, or nil."
  [f name]
  (when (.isFile (io/file f))
    (some->> (:objects (:scene-data (blender/read-blend f)))
             (some #(when (= name (:name %)) %))
             :mesh :uvs seq (partition 2) (map vec) set)))

(deftest uvs-agree-across-versions
  (let [sets (for [v ["b34" "b45" "b50"]]
               (uv-set (.getChild ^Node (blender/load-blender-model
                                         (str "test/fixtures/blender-reader/" v "/reader.blend"))
                                        "shear-parent")))]
    ;; 24 corners, but corners that share a vertex and a UV are one pair
    (is (= 14 (count (first sets))))
    (is (apply = sets)))
  (when-let [box (uv-pairs (str corpus-dir "/box.blend") "Cube")]
    (is (= (uv-pairs "test/fixtures/blender-reader/b34/reader.blend" "shear-parent") box)))
  (when (.isFile (io/file corpus-dir "BlenderDefault_250_Compressed.blend"))
    (let [cube (some #(when (= "Cube" (:name %)) %)
                     (:objects (:scene-data (blender/read-blend
                                             (str corpus-dir "/BlenderDefault_250_Compressed.blend")))))
          ^floats uv (:uvs (:mesh cube))]
      (is (= 48 (alength uv)))
      (is (every? #(<= 0.0 % 1.0) uv)))))

(deftest worm-meta-data
  (let [worm (blender/load-blender-model "Models/test-creature/worm.blend")
        seg (.getChild ^Node worm "worm-1")
        geom (first (filter #(instance? Geometry %) (node-seq seg)))]
    (is (some? seg))
    (is (= 1.0 (sense/meta-data seg "mass")))
    (is (= 1.0 (sense/meta-data geom "mass")))
    (is (= "MESH" (sense/meta-data geom "blender-type")))
    (is (string? (sense/meta-data (.getChild ^Node worm "worm-joint") "joint")))
    (is (nil? (sense/meta-data geom "no-such-property")))))

(deftest asset-manager-loads-blend
  (let [am (util/asset-manager {:new true})
        ^Node worm (.loadModel am "Models/test-creature/worm.blend")]
    (is (some? (.getChild worm "worm-2")))
    (testing "a second load comes from jME's cache as a clone, user data intact"
      (let [^Node again (.loadModel am "Models/test-creature/worm.blend")]
        (is (not (identical? worm again)))
        (is (= 1.0 (sense/meta-data (.getChild again "worm-2") "mass")))))))

(deftest poses-are-computed
  (let [{:keys [warnings objects]} (:scene-data (blender/read-blend "test/fixtures/poses/stale-pose.blend"))]
    (is (= 2 (count warnings)))
    (is (some #(re-find #"bone \"held\" of armature \"rig-c\" has constraints" %) warnings))
    (is (some #(re-find #"bone \"driven\" of armature \"rig-c\" has drivers" %) warnings))
    (testing "the loader keeps the warnings on the root Node"
      (is (= warnings (vec (.getUserData ^Node (blender/load-blender-model "test/fixtures/poses/stale-pose.blend")
                                         ^String blender/warnings-key)))))
    (testing "every child of a bone is where Blender puts it, though the saved poses are stale"
      (let [theirs (into {} (map (juxt #(get % "name") #(get % "matrix_world")))
                         (get (read-json (slurp "test/fixtures/poses/stale-pose.json")) "objects"))
            bone-children (filter #(= 7 (:partype %)) objects)]
        (is (= 11 (count bone-children)))
        (doseq [o bone-children]
          (is (close? (theirs (:name o)) (:world o) 1e-5) (:name o)))))))

(deftest scenes-can-be-chosen
  (let [f "test/fixtures/poses/scenes.blend"
        names (fn [^Node root] (set (keys (object-nodes root))))
        game #{"floor" "player" "crate"}]
    (is (= [{:name "Empty" :objects 0 :meshes 0 :current? false}
            {:name "Game" :objects 3 :meshes 3 :current? false}
            {:name "Menu" :objects 2 :meshes 0 :current? true}]
           (blender/scenes f)))
    (testing "the saved scene by default, with a warning that says how to choose"
      (let [{:keys [scene warnings]} (:scene-data (blender/read-blend f))]
        (is (= "Menu" scene))
        (is (re-find #"scene \"Menu\" has no mesh objects; scene \"Game\" has 3.*\{:scene \"Game\"\}"
                     (first warnings)))))
    (testing "every form of load-blender-model takes the scene"
      (is (= game (names (blender/load-blender-model f {:scene "Game"}))))
      (is (= game (names (blender/load-blender-model (util/asset-manager) f {:scene "Game"}))))
      (is (= game (names (util/load-blender-model f {:scene "Game"}))))
      (is (= game (names (util/load-blender-model (util/asset-manager) f {:scene "Game"}))))
      (is (= #{"menu-camera" "menu-title"} (names (util/load-blender-model f))))
      (is (= #{"menu-camera" "menu-title"} (names (util/load-blender-model (util/asset-manager) f)))))
    (testing "an asset, by name, with options"
      (is (= "Scene" (.getName ^Spatial (first (.getChildren ^Node (blender/load-blender-model
                                                                    "Models/test-creature/worm.blend"
                                                                    {:scene "Scene"})))))))
    (testing "a scene chosen is that scene, even empty; an unknown one is an error naming the scenes"
      (is (empty? (names (blender/load-blender-model f {:scene "Empty"}))))
      (is (re-find #"no scene named \"Nope\"; the file has \[\"Empty\" \"Game\" \"Menu\"\]"
                   (try (blender/load-blender-model f {:scene "Nope"}) ""
                        (catch ExceptionInfo e (ex-message e))))))))

(defn- rounded-vertices
  "The vertices of mesh data `mesh`, each coordinate rounded to 6
  places, sorted: as make_modifiers.py dumps Blender's."
  [mesh]
  (sort (map (fn [p] (mapv #(+ 0.0 (/ (Math/round (* 1e6 (double %))) 1e6)) p))
             (partition 3 (vec (:positions mesh))))))

(deftest modifiers-are-listed-applied-or-warned-about
  (doseq [dir ["test/fixtures/modifiers/" "test/fixtures/modifiers/b52/"]
          :let [f (str dir "modifiers.blend")
                theirs (into {} (map (juxt #(get % "name") identity))
                             (get (read-json (slurp (str dir "modifiers.json"))) "objects"))
                {:keys [objects warnings]} (:scene-data (blender/read-blend f))
                name-of (into {} (map (juxt :key :name)) objects)
                root (blender/load-blender-model f)]]
    (testing dir
      (is (= (set (keys theirs)) (set (map :name objects))))
      (is (= 6 (count (mapcat :modifiers objects))))
      (doseq [{:keys [name modifiers mesh]} objects
              :let [t (theirs name)]]
        (testing name
          (is (= (mapv #(vector (get % "name") (get % "type") (get % "show_viewport")) (get t "modifiers"))
                 (mapv #(vector (:name %) (.toUpperCase ^String (:kind %)) (:viewport? %)) modifiers)))
          (doseq [[md {:keys [mirror]}] (map vector (get t "modifiers") modifiers)
                  :when (= "MIRROR" (get md "type"))]
            (is (= [(get md "use_axis") (boolean (some true? (get md "use_bisect_axis")))
                    (get md "use_mirror_merge") (get md "mirror_object")]
                   [(:axes mirror) (:bisect? mirror) (:merge? mirror) (name-of (:object-key mirror))]))
            (is (< (Math/abs (- (double (get md "merge_threshold")) (:tolerance mirror))) 1e-9)))
          (when mesh
            (if (#{"torso" "leg" "tail"} name)
              (is (= (get t "evaluated_vertices") (rounded-vertices mesh)) "the mesh Blender shows")
              (is (= (get-in t ["mesh" "vertices"]) (quot (count (:positions mesh)) 3)) "the base mesh")))))
      (is (= 12 (count (get-in theirs ["torso" "evaluated_vertices"]))))
      (is (= [["fin" "Mirror: Mirror, it bisects"] ["head" "Subdivision: Subsurf"]]
             (for [w warnings
                   :let [[_ o ms] (re-find #"object \"(\w+)\" has modifiers or shape keys the reader does not apply \((.*)\): it loads as Blender draws it with them off" w)]
                   :when o]
               [o ms])))
      (testing "on the object's node, for the body to say"
        (is (= [{:name "Mirror" :kind "Mirror" :why "it bisects"}]
               (sense/meta-data (.getChild ^Node root "fin") sense/modifiers-key)))
        (is (nil? (sense/meta-data (.getChild ^Node root "torso") sense/modifiers-key)))
        (is (nil? (sense/meta-data (.getChild ^Node root "tail") sense/modifiers-key)))))))

(deftest a-mirror-past-the-budget-is-said
  (binding [scene/*mirror-budget* 10]
    (let [{:keys [objects warnings]} (:scene-data (blender/read-blend "test/fixtures/modifiers/modifiers.blend"))
          torso (first (filter #(= "torso" (:name %)) objects))]
      (is (= 8 (quot (count (:positions (:mesh torso))) 3)) "the half torso, as stored")
      (is (= [{:name "Mirror" :kind "Mirror" :why "it would make more than 10 vertices"}]
             (scene/unapplied torso)))
      (is (some #(re-find #"object \"torso\" has modifiers or shape keys the reader does not apply \(Mirror: Mirror, it would make more than 10 vertices\)" %)
                warnings)))))

(defn- same-vertices?
  "Whether vertex lists `as` and `bs` ([x y z] each) are the same
  multiset, coordinates within 1.01e-5."
  [as bs]
  (and (= (count as) (count bs))
       (empty? (reduce (fn [left a]
                         (if-let [b (first (filter (fn [b] (every? #(<= (Math/abs (- (double (nth a %)) (double (nth b %)))) 1.01e-5)
                                                                   [0 1 2]))
                                                   left))]
                           (let [i (.indexOf ^java.util.List left b)] (into (subvec left 0 i) (subvec left (inc i))))
                           (reduced [a])))
                       (vec bs) as))))

(deftest strangers-mirrors-are-blenders
  (let [dir "test/fixtures/modifiers/strangers/"
        files (sort (filter #(.endsWith ^String % ".evaluated.json") (.list (io/file dir))))]
    (is (= 24 (count files)))
    (doseq [j files
            :let [oracle (read-json (slurp (str dir j)))
                  {:keys [objects warnings]} (:scene-data (blender/read-blend (str dir (get oracle "file"))))
                  ours (into {} (map (juxt :name identity)) objects)]
            t (get oracle "objects")
            :let [name (get t "name") o (ours name)
                  said? (some #(.contains ^String % (str "object " (pr-str name) " ")) warnings)]]
      (testing (str j " " name)
        (is (some? o))
        (if (empty? (scene/unapplied o))
          (do (is (same-vertices? (get t "vertices") (partition 3 (vec (:positions (:mesh o)))))
                  "the vertices Blender shows")
              (when-not (some #(= "TRIANGULATE" (get % "type")) (get t "modifiers"))
                (is (= (get t "polygon_count") (count (:counts (:mesh o)))))))
          (is said? "what is not applied is said"))
        (when (:constrained? o)
          (is said? "a constrained object is said"))))))

(def ^:dynamic *tmp*
  "Folder for the damaged files."
  (doto (.toFile (Files/createTempDirectory "cortex-blend" (make-array java.nio.file.attribute.FileAttribute 0)))
    (.deleteOnExit)))

(defn write-tmp
  "Write bytes `bs` to file `name` in the temporary folder."
  ^File [name ^bytes bs]
  (let [f (io/file *tmp* name)]
    (io/copy bs f)
    (.deleteOnExit f)
    f))

(defn slurp-bytes
  "The bytes of a file."
  ^bytes [f]
  (Files/readAllBytes (.toPath (io/file f))))

(defn gzip
  "Bytes `bs` gzipped."
  ^bytes [^bytes bs]
  (let [out (ByteArrayOutputStream.)]
    (with-open [z (GZIPOutputStream. out)] (.write z bs))
    (.toByteArray out)))

(defn fails-clearly
  "Loading `f` must throw ex-info whose message names the file and
  matches `re`, within five seconds."
  [^File f re]
  (let [t0 (System/nanoTime)
        e (try (blender/load-blender-model (str f)) nil
               (catch ExceptionInfo e e))
        secs (/ (- (System/nanoTime) t0) 1e9)]
    (is (instance? ExceptionInfo e) (str (.getName f) " loaded"))
    (when e
      (is (.contains (.getMessage ^Exception e) (.getName f)) (.getMessage ^Exception e))
      (is (re-find re (.getMessage ^Exception e)) (.getMessage ^Exception e))
      (is (= (str f) (:file (ex-data e)))))
    (is (< secs 5.0) (str (.getName f) " took " secs " s"))))

(def good-file "test/fixtures/blend/b34/transforms.blend")
(def zstd-file "test/fixtures/blend/b34/transforms_compressed.blend")

(deftest bad-input-fails-clearly
  (let [good (slurp-bytes good-file)
        n (alength good)
        rnd (Random. 42)
        random-bytes (fn [k] (let [b (byte-array k)] (.nextBytes rnd b) b))]
    (fails-clearly (write-tmp "empty.blend" (byte-array 0)) #"empty")
    (fails-clearly (write-tmp "random.blend" (random-bytes 4096)) #"not a .blend")
    (fails-clearly (write-tmp "garbage.blend"
                              (byte-array (concat (.getBytes "BLENDER-v279") (random-bytes 2000))))
                   #"block|truncated")
    (doseq [cut [12 13 30 1000 (quot n 3) (quot n 2) (- n 10) (- n 1)]]
      (fails-clearly (write-tmp (str "cut-" cut ".blend") (java.util.Arrays/copyOf good (int cut)))
                     #"truncated|claims|cut"))
    (testing "a block claiming 2^31-1 bytes"
      (let [b (aclone good)
            buf (.order (java.nio.ByteBuffer/wrap b) java.nio.ByteOrder/LITTLE_ENDIAN)]
        (.putInt buf 16 Integer/MAX_VALUE)
        (fails-clearly (write-tmp "huge-block.blend" b) #"claims 2147483647 bytes")))
    (let [z (slurp-bytes zstd-file)]
      (fails-clearly (write-tmp "cut-zstd.blend" (java.util.Arrays/copyOf z (quot (alength z) 2)))
                     #"zstd"))
    (let [g (gzip good)]
      (fails-clearly (write-tmp "cut-gzip.blend" (java.util.Arrays/copyOf g (quot (alength g) 2)))
                     #"malformed|EOF|end"))))

(deftest decompression-is-bounded
  ;; a small gzip that would expand far past the limit (lowered here)
  (with-redefs [cortex.blender.bytes/max-bytes 100000]
    (fails-clearly (write-tmp "bomb.blend" (gzip (byte-array 5000000))) #"decompresses to more than")))

(deftest missing-model-fails-clearly
  (let [e (try (blender/load-blender-model "Models/no-such-creature.blend") nil
               (catch ExceptionInfo e e))]
    (is (instance? ExceptionInfo e))
    (is (re-find #"no-such-creature\.blend" (str (some-> e .getMessage))))))

(deftest errors-survive-jme-asset-manager
  (write-tmp "broken.blend" (java.util.Arrays/copyOf (slurp-bytes good-file) 5000))
  (let [am (doto (util/asset-manager {:new true}) (.registerLocator (str *tmp*) FileLocator))
        e (try (.loadModel am "broken.blend") nil (catch ExceptionInfo e e))]
    (is (instance? ExceptionInfo e))
    (is (re-find #"broken\.blend" (str (some-> e .getMessage))))))

(defn put-ptr!
  "Write old pointer `p` at byte `off` of file bytes `b` (8-byte
  little-endian pointers)."
  [^bytes b off ^long p]
  (.putLong (.order (java.nio.ByteBuffer/wrap b) java.nio.ByteOrder/LITTLE_ENDIAN) (int off) p))

(deftest cycles-are-cut
  (let [good (slurp-bytes good-file)
        bf (file/parse good-file good)
        obs (into {} (for [b (file/blocks-with-code bf "OB")
                           :let [r (file/block-ref bf b)]]
                       [(file/id-name r) [b r]]))
        [b1 r1] (obs "chain-1")
        [b4 r4] (obs "chain-4")
        bad (aclone good)]
    ;; chain-1's parent becomes chain-4, which descends from chain-1
    (put-ptr! bad (file/field-offset r1 "parent") (:old b4))
    (let [root (blender/load-blender-model (str (write-tmp "cycle.blend" bad)))]
      (is (= 4 (count (filter #(re-find #"^chain-\d$" (.getName ^Spatial %))
                              (filter #(not (instance? Geometry %)) (node-seq root)))))))
    ;; the master collection's object list: last link points to the first
    (let [sc (file/block-ref bf (first (file/blocks-with-code bf "SC")))
          mc (file/deref-ptr bf (file/fget sc "master_collection") "Collection")
          links (file/list-seq bf (file/fget mc "gobject") "CollectionObject")
          bad (aclone good)]
      (when (seq links)
        (put-ptr! bad (file/field-offset (last links) "next")
                  (:addr (file/fget (file/fget mc "gobject") "first")))
        (is (instance? Node (blender/load-blender-model
                             (str (write-tmp "cyclic-list.blend" bad)))))))))

(defn hot-ranges
  "[start end] byte ranges worth damaging in a valid file: every block
  header and the blocks of objects, meshes, scenes, collections, the
  catalogue, and the data blocks that follow objects and meshes."
  [bf]
  (let [hs (long (:bhead-size bf))]
    (vec (concat
          (for [b (:blocks bf)] [(- (long (:offset b)) hs) (:offset b)])
          (for [[b nxt] (partition 2 1 (:blocks bf))
                :when (#{"OB" "ME" "SC" "GR" "DNA1" "GLOB"} (:code b))
                :let [end (+ (long (:offset b)) (long (:len b)))]]
            [(:offset b) (if (= "DATA" (:code nxt))
                           (min (+ end 20000) (+ (long (:offset nxt)) (long (:len nxt))))
                           end)])))))

(def fuzz-bases
  "Valid files to damage: old and new, plain and compressed."
  (filterv #(.isFile (io/file %))
           ["test/fixtures/blend/b34/transforms.blend"
            "test/fixtures/blend/b45/props.blend"
            "test/fixtures/blend/b50/transforms.blend"
            "test/fixtures/blend/b50/props.blend"
            "test/fixtures/blend/b50/transforms_compressed.blend"
            "assets/Models/test-creature/worm.blend"
            "../shared/corpus/blend-legacy/CubeHierarchy_248.blend"
            "../shared/corpus/blend-legacy/yxa_1.blend"
            "../shared/corpus/blend-legacy/BlenderDefault_250_Compressed.blend"]))

(def fuzz-data
  "Each base's bytes and hot ranges (plain files only; compressed ones
  are damaged anywhere)."
  (delay (mapv (fn [f] (let [bs (slurp-bytes f)
                             bf (try (file/parse f bs) (catch Exception _ nil))]
                         {:name f :bytes bs
                          :hot (if (and bf (= (:size bf) (alength bs))) (hot-ranges bf) [])}))
               fuzz-bases)))

(defn mutate
  "Apply mutation `mu` to a copy of base `d`'s bytes: flips at positions
  chosen by fractions (into the hot ranges or anywhere), then maybe a
  truncation."
  ^bytes [{:keys [^bytes bytes hot]} {:keys [flips cut]}]
  (let [b (aclone bytes)
        n (alength b)]
    (doseq [[hot? r1 r2 bit] flips
            :let [pos (if (and hot? (seq hot))
                        (let [[s e] (hot (int (* (double r1) (count hot))))]
                          (+ (long s) (long (* (double r2) (- (long e) (long s))))))
                        (long (* (double r1) n)))
                  pos (min (dec n) (max 0 (long pos)))]]
      (aset b pos (unchecked-byte (bit-xor (aget b pos) (bit-shift-left 1 (long bit))))))
    (if cut (java.util.Arrays/copyOf b (int (max 0 (* (double cut) n)))) b)))

(def fraction
  "A number in [0, 1), uniform whatever the size (test.check's doubles
  cluster near 0 at small sizes, which would flip the first byte over
  and over)."
  (gen/fmap #(/ (double %) 1e6) (gen/choose 0 999999)))

(def gen-mutation
  "A base index, up to 12 bit flips, and a truncation one time in five."
  (gen/hash-map
   :base gen/nat
   :flips (gen/vector (gen/tuple (gen/frequency [[4 (gen/return true)] [1 (gen/return false)]])
                                 fraction fraction (gen/choose 0 7))
                      1 12)
   :cut (gen/frequency [[4 (gen/return nil)] [1 fraction]])))

(defn survives?
  "Does loading the mutated bytes end, within ten seconds, in a Node or
  an ex-info naming the file?"
  [name ^bytes bs]
  (let [f (future
            (try (blender/load-bytes (util/asset-manager) name bs) :ok
                 (catch ExceptionInfo e (if (= name (:file (ex-data e))) :ex-info [:unnamed e]))
                 (catch Throwable e [:escaped e])))
        r (deref f 10000 :timeout)]
    (when (= r :timeout) (future-cancel f))
    (or (#{:ok :ex-info} r)
        (do (println "fuzz failure" name r) false))))

(deftest mutations-never-escape
  (let [data @fuzz-data
        p (prop/for-all [mu gen-mutation]
            (let [d (data (mod (:base mu) (count data)))]
              (survives? (str (:name d) "#mutated") (mutate d mu))))
        result (tc/quick-check 150 p :seed 20261122 :max-size 40)]
    (is (:pass? result) (pr-str (select-keys result [:seed :fail :shrunk])))))
