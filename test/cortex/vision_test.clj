;; Generated from org/vision.org by lein tangle: edit the chapter, not this file.
(ns cortex.vision-test
  (:require [clojure.java.io :as io]
            [clojure.java.shell :as sh]
            [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.blender-test :as bt]
            [cortex.body :as body]
            [cortex.render :as render]
            [cortex.sense :as sense]
            ;; the eyes' renderer, which cortex.sim does not load itself:
            ;; the tests that step a simulation with eyes need it loaded
            ;; when this namespace runs alone
            [cortex.sight]
            [cortex.sim :as sim]
            [cortex.util :as util]
            [cortex.vision :as vision])
  (:import (com.jme3.bounding BoundingBox)
           (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.material RenderState$FaceCullMode)
           (java.awt.image BufferedImage)
           (javax.imageio ImageIO)
           (com.jme3.math ColorRGBA Quaternion Vector3f)
           (com.jme3.scene Geometry Node Spatial)
           (java.util Arrays)))

(set! *warn-on-reflection* true)

(def ^:private cameras-path "test/fixtures/eyes/cameras.blend")

(defn- close? [a b tol] (< (Math/abs (- (double a) (double b))) (double tol)))

(deftest blender-cameras-see-what-blender-says
  (let [expected (get (bt/read-json (slurp "test/fixtures/eyes/expected.json")) "cameras")
        creature (util/load-blender-model cameras-path)
        markers (vision/eyes creature)]
    (is (= (set (keys expected)) (set (map #(.getName ^Spatial %) markers))))
    (doseq [^Spatial m markers
            :let [n (.getName m)
                  e (expected n)
                  spec (vision/eye-spec m)
                  {:keys [left right bottom top near parallel?]} (vision/frustum spec)
                  [w h] (:resolution spec)
                  p (e "projection")
                  fov (vision/field-of-view spec)]]
      (testing n
        (is (= (e "resolution") [w h]))
        (is (= (= "ORTHO" (e "type")) parallel?))
        (if parallel?
          (do (is (close? (/ 2 (- right left)) (get-in p [0 0]) 1e-6))
              (is (close? (/ 2 (- top bottom)) (get-in p [1 1]) 1e-6))
              (is (close? (:width fov) (e "width") 1e-6))
              (is (close? (:height fov) (e "height") 1e-6)))
          (do (is (close? (/ (* 2 near) (- right left)) (get-in p [0 0]) 1e-5))
              (is (close? (/ (* 2 near) (- top bottom)) (get-in p [1 1]) 1e-5))
              (is (close? (/ (+ right left) (- right left)) (get-in p [0 2]) 1e-6))
              (is (close? (/ (+ top bottom) (- top bottom)) (get-in p [1 2]) 1e-6))
              (when (zero? (double (e "shift_x")))
                ;; Blender's angles are the unshifted window's
                (is (close? (Math/toRadians (:x fov)) (e "fov_x") 1e-6))
                (is (close? (Math/toRadians (:y fov)) (e "fov_y") 1e-6))
                (let [fit (e "sensor_fit")
                      across? (or (= fit "HORIZONTAL") (and (= fit "AUTO") (>= w h)))]
                  (is (close? (Math/toRadians (if across? (:x fov) (:y fov))) (e "angle") 1e-6))
                  (is (close? (e "angle") (if (= fit "VERTICAL") (e "angle_y") (e "angle_x")) 1e-9))))))))))

(defn- eye-marker
  ^Node [name position direction description]
  (doto (Node. ^String name)
    (.setLocalTranslation ^Vector3f position)
    (.setLocalRotation (vision/eye-rotation direction Vector3f/UNIT_Y))
    (.setUserData "eye" ^String description)))

(defn- creature
  "The head, the tail and `eyes` (markers), not yet built."
  ^Node [eyes]
  (util/nodify "seer"
               [(util/box 0.5 0.5 0.5 :name "head" :color ColorRGBA/Green :physical? false)
                (util/box 0.5 0.5 0.5 :name "tail" :color ColorRGBA/Blue :physical? false
                          :position (Vector3f. 0 0 -1.6))
                (util/nodify "eyes" eyes)]))

(def ^:private front-eye
  #(eye-marker "front-eye" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z
               "{:fov 60 :resolution [64 48] :near 0.05 :far 50}"))

(def ^:private back-eye
  #(eye-marker "back-eye" (Vector3f. 0 0 -0.55) (Vector3f. 0 0 -1) "{:resolution [32 24]}"))

(defn- seer-sim
  "A weightless simulation of the seer with its eyes, and the red cube
  attached to its scene: [sim cube]."
  [eyes-options]
  (let [c (body/body! (creature [(front-eye) (back-eye)]))
        s (sim/simulation c {:gravity [0 0 0] :eyes eyes-options})
        cube (util/box 0.25 0.25 0.25 :name "cube" :color ColorRGBA/Red :physical? false
                       :position (Vector3f. 0 0 3.55))]
    (.attachChild ^Node (:root s) cube)
    [s cube]))

(defn- pixel
  "The RGB of pixel (x, y) (y from the top) of eye observation `e`."
  [{:keys [width ^bytes rgb]} x y]
  (let [i (* 3 (+ x (* y width)))]
    (mapv #(bit-and 0xff (aget rgb (+ i %))) [0 1 2])))

(defn- red-columns
  "The columns of row `y` that are red."
  [e y]
  (filter #(= [255 0 0] (pixel e % y)) (range (:width e))))

(defn- predicted-columns
  "Where the cube's front face edges (x = +-0.25, z = 3.3) fall in the
  front eye (60 degrees, 64 wide) when the head has turned by `a`
  radians about Y: [left right] as fractional columns."
  [a]
  (let [eye [(* 0.55 (Math/sin a)) (* 0.55 (Math/cos a))]
        column (fn [[px pz]]
                 (let [dx (- px (first eye)) dz (- pz (second eye))
                       ;; into the eye's frame: undo the turn about Y
                       x (- (* dx (Math/cos a)) (* dz (Math/sin a)))
                       z (+ (* dx (Math/sin a)) (* dz (Math/cos a)))]
                   (* 32 (- 1 (/ (/ x z) (Math/tan (Math/toRadians 30)))))))]
    (sort [(column [0.25 3.3]) (column [-0.25 3.3])])))

(deftest an-eye-sees-a-red-cube
  (let [[s] (seer-sim true)]
    (try
      (let [front (get-in (sim/step! s) [:eyes "front-eye"])]
        (testing "red at the centre"
          (is (= [255 0 0] (pixel front 32 24))))
        (testing "depth at the cube's face is its distance from the eye, within 1%"
          (let [d (aget ^floats (:depth front) (+ 32 (* 24 64)))]
            (is (< (Math/abs (- d 2.75)) 0.0275) (str "depth " d))))
        (testing "the sky is the sky, far away"
          (is (= [140 178 230] (pixel front 0 0)))
          (is (== 50.0 (aget ^floats (:depth front) 0))))
        (testing "turning the head moves the cube as the field of view predicts"
          (doseq [degrees [0 10 -12]
                  :let [a (Math/toRadians degrees)
                        ^RigidBodyControl c (.getControl (body/segment (:creature s) "head")
                                                         RigidBodyControl)]]
            (.setPhysicsRotation c (doto (Quaternion.) (.fromAngleAxis (float a) Vector3f/UNIT_Y)))
            (let [e (get-in (sim/step! s) [:eyes "front-eye"])
                  cols (red-columns e 24)
                  [lo hi] (predicted-columns a)]
              (is (seq cols) (str degrees " degrees"))
              (is (<= (Math/abs (- (double (first cols)) (double lo))) 1.0) (str degrees " degrees: " (first cols) " vs " lo))
              (is (<= (Math/abs (- (double (inc (last cols))) (double hi))) 1.0) (str degrees " degrees: " (inc (last cols)) " vs " hi))))))
      (finally (sim/destroy! s)))))

(deftest an-eye-sees-both-sides-of-a-plane
  (let [^Geometry blade (body/segment (util/load-blender-model
                                       "test/fixtures/flat-strangers/flat-hexagon-paddle.blend")
                                      "paddle")
        ^BoundingBox bound (.getBound (.getMesh blade))
        ext (.getExtent bound nil)
        ;; the blade's normal, in its own frame: its thinnest axis
        normal (apply min-key #(Math/abs (.dot ext ^Vector3f %))
                      [Vector3f/UNIT_X Vector3f/UNIT_Y Vector3f/UNIT_Z])
        seen (fn [^Vector3f facing]
               (let [[s cube] (seer-sim true)
                     axis (.cross ^Vector3f normal facing)
                     ^Quaternion turn (if (< (.length axis) 1e-6)
                            (if (pos? (.dot ^Vector3f normal facing))
                              (Quaternion.)
                              (doto (Quaternion.) (.fromAngleAxis (float Math/PI) Vector3f/UNIT_X)))
                            (doto (Quaternion.) (.fromAngleAxis (float (.angleBetween ^Vector3f normal facing))
                                                                (.normalize axis))))
                     plane (doto (Geometry. "blade" (.getMesh blade))
                             (.setMaterial (.getMaterial blade))
                             (.setLocalRotation turn)
                             (.setLocalTranslation (.subtract (Vector3f. 0 0 3.55)
                                                              (.mult turn (.getCenter bound)))))]
                 (try
                   (.removeFromParent ^Spatial cube)
                   (.attachChild ^Node (:root s) plane)
                   (pixel (get-in (sim/step! s) [:eyes "front-eye"]) 32 24)
                   (finally (sim/destroy! s)))))
        ;; the blade's thinnest axis turned to point at the eye, and away
        one (seen (Vector3f. 0 0 -1))
        other (seen (Vector3f. 0 0 1))
        ^Geometry handle (body/segment (util/load-blender-model
                                        "test/fixtures/flat-strangers/flat-hexagon-paddle.blend")
                                       "handle")]
    (is (not= [140 178 230] one) "one side of the blade, turned to the eye, is seen")
    (is (not= [140 178 230] other) "so is the other")
    (is (= one other) "both sides are lit alike")
    (is (= RenderState$FaceCullMode/Back
           (.getFaceCullMode (.getAdditionalRenderState (.getMaterial handle))))
        "a closed mesh (the handle) is drawn on its outside only")))

(deftest segmentation-names-what-is-seen
  (let [[s] (seer-sim {:all {:segmentation true}})]
    (try
      (let [{:strs [front-eye back-eye]} (:eyes (sim/step! s))
            id (fn [{:keys [width ^ints segmentation labels]} x y]
                 (get labels (aget segmentation (+ x (* y width)))))]
        (is (= "cube" (id front-eye 32 24)))
        (is (nil? (id front-eye 0 0)) "the sky is 0, nothing")
        (is (= "tail" (id back-eye 16 12)))
        (is (= #{"head" "tail" "cube"} (set (vals (:labels front-eye)))))
        (is (= [32 24] [(:width back-eye) (:height back-eye)])))
      (finally (sim/destroy! s)))))

(defn- gait [t]
  (let [phase (mod (* 1.5 (max 0.0 (- (double t) 0.5))) 1.0)]
    {"worm-joint" {:target (* 0.6 (if (< phase 0.8) (/ phase 0.8) (/ (- 1 phase) 0.2)))}}))

(defn- crawl-seeing [steps]
  (let [s (sim/simulation (body/body! (util/load-blender-model "Models/test-creature/worm-eyes.blend"))
                          {:floor 0 :eyes true :observe #{:eyes}})]
    (try
      (vec (for [_ (range steps)] (:eyes (sim/step! s (gait (sim/sim-time s))))))
      (finally (sim/destroy! s)))))

(deftest seeing-repeats-and-moves
  (let [a (crawl-seeing 90)
        b (crawl-seeing 90)
        same? (fn [x y] (every? (fn [eye]
                                  (and (Arrays/equals ^bytes (get-in x [eye :rgb]) ^bytes (get-in y [eye :rgb]))
                                       (Arrays/equals ^floats (get-in x [eye :depth]) ^floats (get-in y [eye :depth]))))
                                ["left-eye" "right-eye"]))]
    (is (every? true? (map same? a b)) "two runs, the same pictures")
    (is (not (same? (first a) (peek a))) "the eyes moved with the worm")
    (is (< 60 (count (filter false? (map same? a (rest a))))) "and saw it, nearly every step")))

(deftest eyes-on-many-threads
  (let [alone (crawl-seeing 20)
        together (mapv deref (doall (repeatedly 3 #(future (crawl-seeing 20)))))]
    (doseq [run together]
      (is (every? true? (map (fn [x y]
                               (every? #(Arrays/equals ^bytes (get-in x [% :rgb]) ^bytes (get-in y [% :rgb]))
                                       ["left-eye" "right-eye"]))
                             alone run))))))

(defn- build-error
  [eyes]
  (try (body/body! (creature eyes)) nil
       (catch clojure.lang.ExceptionInfo e (ex-message e))))

(defn- camera-marker
  ^Node [name camera description]
  (doto (eye-marker name (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{}")
    (.setUserData "eye" description)
    (.setUserData "blender-type" "CAMERA")
    (.setUserData sense/camera-key
                  (merge {:type :perspective :lens 50.0 :sensor-width 36.0 :sensor-height 24.0
                          :sensor-fit :auto :clip-start 0.1 :clip-end 100.0 :ortho-scale 7.0
                          :shift-x 0.0 :shift-y 0.0}
                         camera))))

(deftest bad-eyes-are-named
  (doseq [[label eyes pattern]
          [["unknown key" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{:fvo 60}")]
            #"eye \"e\": unknown key :fvo; an eye's keys are :far, :fov, :near, :resolution"]
           ["zero width" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{:resolution [0 48]}")]
            #"eye \"e\": :resolution must be \[width height\], whole numbers of pixels from 8"]
           ["tiny" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{:resolution [4 4]}")]
            #"eye \"e\": :resolution"]
           ["fov 180" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{:fov 180}")]
            #"eye \"e\": :fov is the angle across the image in degrees, more than 0 and less than 180"]
           ["fov 0" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{:fov 0}")] #":fov"]
           ["near" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{:near -1}")]
            #"eye \"e\": :near must be a positive distance"]
           ["far" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{:near 2 :far 1}")]
            #"eye \"e\": :far must be a distance beyond :near"]
           ["not a map" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "[60]")]
            #"eye \"e\": the eye property is a map"]
           ["unreadable" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{:fov")]
            #"eye \"e\": cannot read"]
           ["code" [(eye-marker "e" (Vector3f. 0 0 0.55) Vector3f/UNIT_Z "{:fov (System/exit 1)}")]
            #"eye \"e\": not an allowed operation"]
           ["no property" [(doto (Node. "e") (.setLocalTranslation 0 0 0.55))]
            #"eye \"e\": an empty under \"eyes\" needs an eye property"]
           ["a mesh" [(doto (Node. "e") (.setLocalTranslation 0 0 0.55) (.setUserData "blender-type" "MESH"))]
            #"eye \"e\": a MESH object cannot be an eye"]
           ["far from everything" [(eye-marker "e" (Vector3f. 0 0 3) Vector3f/UNIT_Z "{}")]
            #"eye \"e\": its nearest segment, head, is 2.500 away, more than that segment's longest side \(1.000\)"]
           ["between two" [(eye-marker "e" (Vector3f. 0 0 -0.8) Vector3f/UNIT_Z "{}")]
            #"eye \"e\": it is about equally near head \(0.300\) and tail \(0.300"]
           ["twice" [(front-eye) (front-eye)] #"eyes share the names \[\"front-eye\"\]"]
           ["camera with fov" [(camera-marker "c" {} "{:fov 30}")]
            #"eye \"c\": a camera's eye property only sets :resolution; :fov comes from"]
           ["panoramic" [(camera-marker "c" {:type :panoramic} "{}")]
            #"eye \"c\": a panoramic camera cannot be an eye"]
           ["no lens" [(camera-marker "c" {:lens 0.0} "{}")] #"eye \"c\": the camera's lens must be positive"]]]
    (testing label
      (let [m (build-error eyes)]
        (is (some? m) "is an error")
        (when m
          (is (re-find #"^creature \"seer\", " m) m)
          (is (re-find pattern m) m))))))

(deftest bad-eye-options-are-named
  (let [c (body/body! (creature [(front-eye)]))]
    (doseq [[opts pattern] [[{"nose" {}} #"no eye called \"nose\"; the eyes are \[\"front-eye\"\]"]
                            [{"front-eye" {:colour true}} #"unknown eye option \[:colour\]"]
                            [{"front-eye" {:resolution [64]}} #":resolution"]
                            [:yes #":eyes must be true or a map"]]]
      (is (thrown-with-msg? clojure.lang.ExceptionInfo pattern (sim/simulation c {:eyes opts}))))
    (is (thrown-with-msg? clojure.lang.ExceptionInfo #"has no eyes"
                          (sim/simulation (body/body! (util/load-blender-model "Models/test-creature/worm.blend"))
                                          {:eyes true})))))

(deftest the-report-lists-the-eyes
  (let [{:keys [eyes]} (body/report (body/body! (util/load-blender-model
                                                 "Models/test-creature/worm-eyes.blend")))
        [left right] eyes]
    (is (= ["left-eye" "right-eye"] (map :name eyes)))
    (is (= ["worm-1" "worm-1"] (map :segment eyes)))
    (is (= [:camera :empty] (map :kind eyes)))
    (is (every? #(close? (:distance %) 0.035 1e-3) eyes))
    (is (= [64 48] (:resolution left) (:resolution right)))
    (is (close? (first (:fov left)) 83.974 1e-3) "lens 20 on a 36 mm sensor")
    (is (close? (first (:fov right)) 84.0 1e-9))))

(deftest no-opengl-without-eyes
  (let [form (pr-str '(do (require '[cortex.blender :as blender] '[cortex.body :as body]
                                   '[cortex.sim :as sim])
                          (let [s (sim/simulation (body/body! (blender/load-blender-model
                                                               "Models/test-creature/worm.blend"))
                                                  {:floor 0})]
                            (dotimes [_ 10] (sim/step! s))
                            (println "stepped" (sim/steps s)))
                          (shutdown-agents)))
        ;; without dev/, whose user.clj a REPL would load
        classpath (str/join java.io.File/pathSeparator
                            (remove #(str/ends-with? % "/dev")
                                    (str/split (System/getProperty "java.class.path")
                                               (re-pattern java.io.File/pathSeparator))))
        {:keys [exit out err]} (sh/sh "java" "-verbose:class" "-cp" classpath
                                      "clojure.main" "-e" form)
        loaded (filter #(re-find #"^\[.*class,load\]" %) (str/split-lines out))]
    (is (zero? exit) err)
    (is (re-find #"stepped 10" out))
    (is (< 1000 (count loaded)) "the JVM said what it loaded")
    (is (empty? (filter #(re-find #"org\.lwjgl|opengl|com\.jme3\.system\.lwjgl|cortex\.sight" %) loaded))
        (str/join "\n" (take 5 (filter #(re-find #"lwjgl|opengl" %) loaded))))))

(deftest an-orthographic-eye
  (let [ortho (fn [] (camera-marker "ortho" {:type :orthographic :ortho-scale 2.0 :clip-start 0.05
                                             :clip-end 50.0}
                                    "{:resolution [64 64]}"))
        c (body/body! (creature [(doto ^Node (ortho) (.setLocalTranslation 0 0 0.55))]))
        s (sim/simulation c {:gravity [0 0 0] :eyes true})
        cube (util/box 0.25 0.25 0.25 :name "cube" :color ColorRGBA/Red :physical? false
                       :position (Vector3f. 0 0 3.55))]
    (.attachChild ^Node (:root s) cube)
    (try
      (let [near (get-in (sim/step! s) [:eyes "ortho"])
            _ (.setLocalTranslation ^Spatial cube 0 0 6.55)
            far (get-in (sim/step! s) [:eyes "ortho"])]
        (is (= 16 (count (red-columns near 32)) (count (red-columns far 32)))
            "0.5 of 2 units across is 16 of 64 pixels, near or far")
        (is (close? (aget ^floats (:depth near) (+ 32 (* 32 64))) 2.75 0.0275))
        (is (close? (aget ^floats (:depth far) (+ 32 (* 32 64))) 5.75 0.0575)))
      (finally (sim/destroy! s)))))

(deftest the-readme-example-runs
  (let [readme (slurp "README.md")
        section (second (re-find #"(?s)\n## Eyes\n(.*?)\n## " readme))
        code (second (re-find #"(?s)```clojure\n(.*?)```" (or section "")))
        the-ns (create-ns (gensym "readme-eyes"))]
    (is (some? code) "the README has an Eyes section with a Clojure example")
    (binding [*ns* the-ns]
      (refer-clojure)
      (loop [[line & more] (str/split-lines (or code "")) pending []]
        (cond
          (nil? line) (when (seq pending) (load-string (str/join "\n" pending)))
          (str/starts-with? line ";; => ")
          (let [value (load-string (str/join "\n" pending))]
            (is (= (read-string (subs line 6)) value) (str/join "\n" pending))
            (recur more []))
          :else (recur more (conj pending line)))))
    (remove-ns (ns-name the-ns))))

(defn- first-sight
  "[scale, what the eye \"eye\" of the strangers' worm `f` sees before a
  step (segment names per pixel, depth)] on a floor at 0."
  [f]
  (let [s (sim/simulation (util/load-blender-model (str "test/fixtures/strangers/" f ".blend"))
                          {:floor 0 :observe #{:eyes} :eyes {"eye" {:segmentation true}}})]
    (try
      (let [{:keys [segmentation labels depth]} (get-in (sim/observe s) [:eyes "eye"])]
        [(sim/scale s) (mapv #(get labels % :none) segmentation) (vec depth)])
      (finally (sim/destroy! s)))))

(deftest a-small-creature-s-eye-sees-as-its-twin-s
  (let [[k1 seen depth] (first-sight "worm-eye")
        [k100 seen-small depth-small] (first-sight "worm-eye-0.01")
        n (count seen)
        same (count (filter true? (map = seen seen-small)))
        near (count (filter true? (map (fn [a b] (< (Math/abs (- (* 100.0 (double b)) (double a)))
                                                    (* 0.01 (double a))))
                                       depth depth-small)))]
    (is (= [1.0 100.0] [k1 k100]))
    (is (< 1 (count (distinct seen))) (str "the eye sees more than one thing: " (frequencies seen)))
    (is (< 0.99 (/ same (double n))) (str same " of " n " pixels see the same segment"))
    (is (< 0.99 (/ near (double n))) (str near " of " n " pixels' depths within 1%"))))
