;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.export-test
  (:require [clojure.java.io :as io]
            [clojure.java.shell :as shell]
            [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.drops :as drops]
            [cortex.export :as ex]
            [cortex.export.geometry :as geo]
            [cortex.export.model :as model]
            [cortex.muscle :as muscle]
            [cortex.plan :as plan]
            [cortex.sim :as sim]
            [cortex.blender]
            [cortex.util :as util])
  (:import (java.nio.file Files)
           (java.nio.file.attribute FileAttribute)))

(def fixtures
  "The creatures exported and checked, by name."
  {"worm" "Models/test-creature/worm.blend"
   "hand" "Models/test-creature/hand.blend"
   "quadruped" "test/fixtures/designer/quadruped.blend"
   "humanoid" "test/fixtures/strangers/humanoid.blend"})

(defn python
  "A Python that imports mujoco and pybullet: $CORTEX_PYTHON, or the one
  .ci/run makes (target/python); nil when there is none."
  []
  (first (for [p [(System/getenv "CORTEX_PYTHON") "target/python/bin/python"]
               :when (and p (.exists (io/file p))
                          (zero? (:exit (shell/sh p "-c" "import mujoco, pybullet"))))]
           p)))

(defn- skip [what]
  (println (str "SKIPPED " what ": no Python with mujoco and pybullet (set CORTEX_PYTHON,"
                " or run .ci/run, which makes target/python from scripts/export/requirements.txt)")))

(defn- placed
  "[creature plan] of `fixture`: loaded, placed with its lowest point
  1 m above y = 0 (as cortex.drops/place! places it), planned and
  built."
  [fixture]
  (let [c (util/load-blender-model (fixtures fixture))
        [lo] (drops/extent c)]
    (.move c 0 (float (- 1.0 (double lo))) 0)
    (let [p (plan/plan c)]
      (body/body! c)
      [c p])))

(defn- close? [a b tol]
  (if (sequential? a)
    (every? true? (map #(close? %1 %2 tol) a b))
    (<= (Math/abs (- (double a) (double b))) (* tol (max 1.0 (Math/abs (double b)))))))

(deftest the-muscles-are-cortex-s
  (doseq [f ["hand" "quadruped" "humanoid"]
          :let [[c p] (placed f)
                mine (ex/muscles p)]
          [n {:keys [strength kp kd type]}] (muscle/muscles c)]
    (testing (str f " " n)
      (is (close? (:strength (mine n)) strength 1e-4))
      ;; cortex.muscle gives a cone's gains in Blender's axis order
      (let [order (if (= type :hinge) identity (fn [[x y z]] [x z y]))]
        (is (close? (order (:kp (mine n))) kp 1e-4))
        (is (close? (order (:kd (mine n))) kd 1e-4))))))

(deftest a-built-creature-exports-as-planned
  (let [[c p] (placed "quadruped")
        message (fn [f] (try (f) nil (catch clojure.lang.ExceptionInfo e (ex-message e))))]
    (is (= (ex/mjcf p) (ex/mjcf c)) "the creature, built, writes the plan body! built")
    (is (= (ex/urdf p) (ex/urdf c)))
    (is (= (ex/meshes p) (ex/meshes c)))
    (let [late (plan/plan c)
          said (message #(ex/mjcf late))]
      (is (re-find #"segment \".+\" of .* has no shape or mass.*export the creature itself" (str said))
          (str said))
      (is (= said (message #(ex/urdf late)))))
    (let [fresh (util/load-blender-model (fixtures "worm"))]
      (is (= (ex/mjcf (plan/plan fresh)) (ex/mjcf fresh)) "before body!, its plan now"))))

(deftest hulls-are-closed-and-minimal
  (let [corners (vec (for [x [-1 1] y [-1 1] z [-1 1]] [x y z]))
        on-faces [[0 0 1] [0.5 0 -1] [1 0.2 0.3] [0 0 0]]
        faces (geo/hull-faces (into corners on-faces))]
    (is (= 12 (count faces)))
    (is (= (set (range 8)) (set (flatten faces))))
    ;; every edge is shared by exactly two faces, once each way
    (let [edges (for [[a b c] faces e [[a b] [b c] [c a]]] e)]
      (is (= (count edges) (count (set edges))))
      (is (every? #(some #{[(second %) (first %)]} edges) edges))))
  (is (thrown? clojure.lang.ExceptionInfo
               (geo/hull-faces [[0 0 0] [1 0 0] [0 1 0] [1 1 0] [2 3 0]]))))

(def primitive-plan
  (let [seg (fn [id x shape]
              {:id id :mass 1.0 :friction 0.5 :position [x 1.0 0.0] :rotation [0 0 0 1]
               :inertia {:source :mesh :centre [0.0 0.0 0.0] :rotation [0 0 0 1]
                         :moments [0.01 0.01 0.01]}
               :shape shape})
        box {:type :box :half-extents [0.1 0.2 0.3]}
        ball {:type :sphere :radius 0.15}]
    {:creature "primitives"
     :segments [(seg "box" 0.0 box)
                (seg "sphere" 1.0 ball)
                (seg "capsule" 2.0 {:type :capsule :radius 0.1 :height 0.4 :axis 1})
                (seg "cylinder" 3.0 {:type :cylinder :half-extents [0.25 0.1 0.1] :axis 0})
                (seg "compound" 4.0 {:type :compound
                                     :children [{:shape box :position [0.0 0.3 0.0] :rotation nil}
                                                {:shape ball :position [0.0 -0.3 0.0]
                                                 :rotation [0 0 0 1]}]})]
     :joints (for [[k [a b]] (map-indexed vector (partition 2 1 ["box" "sphere" "capsule"
                                                                "cylinder" "compound"]))]
               {:name (str "j" k) :type :hinge :segments [a b] :pivot [(+ k 0.5) 1.0 0.0]
                :rotation [0 0 0 1] :description {:limit [-0.5 0.5] :axis [0 0 1]}})}))

(defn- geoms
  "The <geom .../> elements of `doc`: [{attribute value}]."
  [doc]
  (for [[_ attrs] (re-seq #"<geom ([^>]*)/>" doc)]
    (into {} (for [[_ k v] (re-seq #"(\w+)=\"([^\"]*)\"" attrs)] [k v]))))

(deftest primitives-are-exported-as-primitives
  (let [doc (ex/mjcf primitive-plan)
        gs (into {} (map (juxt #(get % "name") identity)) (geoms doc))
        nums (fn [s] (mapv #(Double/parseDouble %) (str/split s #" ")))]
    (is (= ["box" "0.1 0.2 0.3"] (mapv (gs "box") ["type" "size"])))
    (is (= ["sphere" "0.15"] (mapv (gs "sphere") ["type" "size"])))
    (is (= ["capsule" "0.1 0.2"] (mapv (gs "capsule") ["type" "size"])))
    (is (= ["cylinder" "0.1 0.25"] (mapv (gs "cylinder") ["type" "size"])))
    (is (= ["box" "sphere"] (mapv #(get (gs %) "type") ["compound" "compound/1"])))
    ;; the compound's box 0.3 up jME's Y: 0.3 up Z in the document
    (is (close? (nums (get (gs "compound") "pos")) [0.0 0.0 0.3] 1e-9))
    (is (close? (nums (get (gs "compound/1") "pos")) [0.0 0.0 -0.3] 1e-9))
    (is (empty? (ex/meshes primitive-plan)) "no primitive is written as a mesh")
    (let [u (ex/urdf primitive-plan)]
      (doseq [tag ["<box size=\"0.2 0.4 0.6\"/>" "<sphere radius=\"0.15\"/>"
                   "<capsule radius=\"0.1\" length=\"0.4\"/>"
                   "<cylinder radius=\"0.1\" length=\"0.5\"/>"]]
        (is (str/includes? u tag) tag)))
    (if-let [py (python)]
      (let [dir (str (Files/createTempDirectory "cortex-primitives" (make-array FileAttribute 0)))
            path (str (io/file dir "primitives.xml"))
            _ (ex/write! primitive-plan path nil)
            {:keys [exit out err]}
            (shell/sh py "-c" (str "import sys, mujoco\n"
                                   "w = []\n"
                                   "mujoco.set_mju_user_warning(lambda s: w.append(s))\n"
                                   "m = mujoco.MjModel.from_xml_path(sys.argv[1])\n"
                                   "d = mujoco.MjData(m); mujoco.mj_forward(m, d)\n"
                                   "z = d.geom_xmat[m.geom('capsule').id].reshape(3, 3)[:, 2]\n"
                                   "x = d.geom_xmat[m.geom('cylinder').id].reshape(3, 3)[:, 2]\n"
                                   "print(len(w), m.ngeom, *[round(abs(float(v)), 9) for v in [*z, *x]])\n")
                      path)]
        (is (zero? exit) err)
        (is (= "0 6 0.0 0.0 1.0 1.0 0.0 0.0" (str/trim out))
            "no warning, six geoms, the capsule along Z, the cylinder along X"))
      (skip "cortex.export-test/primitives-are-exported-as-primitives, in MuJoCo"))))

(def ^:private seconds 5.0)

(defn mv [m v] (mapv #(reduce + (map * % v)) m))
(defn mm [a b] (mapv (fn [row] (apply mapv (fn [& col] (reduce + (map * row col))) b)) a))
(defn v+ [a b] (mapv + a b))
(def C [[1 0 0] [0 0 -1] [0 1 0]])
(defn z-up-rotation [m] (mm (mm C m) (apply mapv vector C)))

(defn- size
  "The longest side of the box round `plan`'s segments."
  [plan]
  (let [pts (for [{:keys [position rotation shape]} (:segments plan)
                  p (model/shape-points shape)]
              (v+ position (mv (geo/quat->matrix rotation) p)))
        lo (apply mapv min pts) hi (apply mapv max pts)]
    (apply max (map - hi lo))))

(defn- cortex-drop
  "Heights of `creature`'s centre of mass after each 1/60 s step, and
  its fastest segment over the last half second."
  [creature plan]
  (let [mass (into {} (map (juxt :id :mass)) (:segments plan))
        total (reduce + (vals mass))
        s (sim/simulation creature {:floor {:height 0 :friction 1.0} :observe #{:segments}})
        obs (vec (repeatedly (long (* 60 seconds)) #(sim/step! s)))]
    {:heights (mapv (fn [o] (/ (reduce + (for [[n {[_ y] :position}] (:segments o)] (* (mass n) y)))
                               total))
                    obs)
     :rest-speed (apply max (for [o (subvec obs (- (count obs) 30))
                                  [_ {v :velocity}] (:segments o)]
                              (Math/sqrt (reduce + (map * v v)))))}))

(defn- manifest-entry
  "What check_export.py needs of fixture `f`, written into `dir`."
  [f plan dir]
  (let [mj (str (io/file dir (str f ".xml")))
        urdf (str (io/file dir (str f ".urdf")))
        dofs (ex/joint-dofs plan)
        {:keys [roots]} (ex/tree plan)
        root (first (filter #(= (first roots) (:id %)) (:segments plan)))]
    (ex/write! plan mj urdf)
    {:name f :mjcf mj :urdf urdf :seconds seconds
     :pairs (map :segments (:joints plan))
     :base {:link (:id root) :pos (geo/z-up (:position root))
            :quat (geo/matrix->quat (z-up-rotation (geo/quat->matrix (:rotation root))))}
     :joints (for [{:keys [name type segments rotation description]} (:joints plan)
                   :when (not= type :point)
                   :let [{ds :dofs} (dofs name)]]
               (cond-> {:name name :type type :segments segments
                        :dofs (for [d ds] {:joint (:name d) :actuator (str "muscle/" (:name d))
                                           :range (:range d)})}
                 (= type :hinge) (assoc :axis (:axis (first ds)))
                 (= type :cone) (assoc :frame (let [[turn] (model/cone-frame description)]
                                                ;; columns: the engine's axes, Z up
                                                (mm C (mm (geo/quat->matrix rotation) turn))))))}))

(defn- expected-angle
  "What cortex reads of a joint whose dof `d` (of joint-dofs' `joint`)
  is pushed to MuJoCo's `end` of its range: [index angle]."
  [{:keys [flipped? dofs]} dof-name end]
  (let [{[lo hi] :range k :engine-axis} (first (filter #(= dof-name (:name %)) dofs))
        q (if (= end "low") lo hi)]
    (if k
      ;; a cone: qpos is -angle (second segment the child) or +angle
      [k (if flipped? q (- q))]
      [0 (if flipped? (- q) q)])))

(def ^:private settles-alike
  "The fixtures whose drops the three simulators agree on (see the
  text: cortex's four-legged creature and humanoid do not come to rest)."
  #{"worm" "hand"})

(defn- drop-figures [who heights rest-speed]
  (format "%s: centre of mass %.3f m up after 1 s, %.3f m at the end, fastest segment then %.3f m/s"
          who (double (nth heights 59)) (double (peek (vec heights))) (double rest-speed)))

(defn- check-fixture
  [f plan cortex {:strs [mujoco bodies drives drop urdf]}]
  (testing f
    (is (nil? (get mujoco "error")))
    (is (empty? (get mujoco "warnings")))
    (let [sz (size plan)
          dofs (ex/joint-dofs plan)]
      (is (= (set (map :id (:segments plan))) (set (keys bodies))))
      (doseq [{:keys [id mass position rotation inertia]} (:segments plan)
              :let [{m "mass" com "com" I "inertia"} (bodies id)
                    R (geo/quat->matrix rotation)
                    axes (mm C (mm R (geo/quat->matrix (:rotation inertia))))
                    want (mm (mm axes (mapv #(assoc [0.0 0.0 0.0] % (nth (:moments inertia) %)) (range 3)))
                             (apply mapv vector axes))
                    want-com (geo/z-up (v+ position (mv R (:centre inertia))))
                    norm (fn [m] (Math/sqrt (reduce + (map #(* % %) (flatten m)))))]]
        (testing id
          (is (close? m mass 1e-6))
          (is (< (norm (map - com want-com)) (* 1e-6 sz)))
          (is (< (norm (map #(map - %1 %2) I want)) (* 1e-6 (norm want))) (pr-str I want))))
      (doseq [{:strs [joint dof end angles]} drives
              :let [[k want] (expected-angle (dofs joint) dof end)]]
        (is (< (Math/abs (- (double (nth angles k)) want)) 0.05)
            (str joint " " dof " to its " end ": " (nth angles k) ", cortex's limit " want)))
      (doseq [[who {:strs [heights rest_speed]}] [["MuJoCo" drop] ["PyBullet" (get urdf "drop")]]
              :when (or (settles-alike f)
                        (println (str f ", not yet alike: " (drop-figures who heights rest_speed)
                                      "; " (drop-figures "cortex" (:heights cortex) (:rest-speed cortex)))))]
        (testing who
          (doseq [[label i] [["after 1 s" 59] ["at the end" (dec (count heights))]]]
            (is (< (Math/abs (- (double (nth heights i)) (nth (:heights cortex) i))) (* 0.05 sz))
                (str label ": centre of mass " (nth heights i) " m up, cortex's "
                     (nth (:heights cortex) i) ", size " sz)))
          (is (< rest_speed 0.1) (str "still moving at " rest_speed " m/s"))))
      (when (settles-alike f)
        (is (< (:rest-speed cortex) 0.1) (str "cortex still moving at " (:rest-speed cortex))))
      (is (zero? (get-in urdf ["check_urdf" "code"] 0)) (get-in urdf ["check_urdf" "output"]))
      (doseq [{:keys [id mass]} (:segments plan)]
        (is (close? (get-in urdf ["masses" id]) mass 1e-6) id)))))

(deftest mujoco-and-pybullet-agree-with-cortex
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-export" (make-array FileAttribute 0)))
          runs (vec (for [f (sort (keys fixtures))]
                      (let [[c plan] (placed f)]
                        {:f f :plan plan :entry (manifest-entry f plan dir)
                         :cortex (cortex-drop c plan)})))
          manifest (str (io/file dir "manifest.json"))
          out (str (io/file dir "out.json"))
          _ (spit manifest ((requiring-resolve 'cortex.compare/json) {:fixtures (map :entry runs)}))
          {:keys [exit err]} (shell/sh py "scripts/export/check_export.py" manifest out)]
      (is (zero? exit) err)
      (when (zero? exit)
        (let [result ((requiring-resolve 'cortex.blender-test/read-json) (slurp out))]
          (doseq [{:keys [f plan cortex]} runs]
            (check-fixture f plan cortex (result f))))))
    (skip "cortex.export-test/mujoco-and-pybullet-agree-with-cortex")))

(def ^:private eye-turn
  "How the worm with eyes is turned for the camera check: 30 degrees
  about the vertical, after 12 about its own length (jME's X)."
  (.mult (.fromAngleAxis (com.jme3.math.Quaternion.) (float (Math/toRadians 30))
                         com.jme3.math.Vector3f/UNIT_Y)
         (.fromAngleAxis (com.jme3.math.Quaternion.) (float (Math/toRadians 12))
                         com.jme3.math.Vector3f/UNIT_X)))

(def ^:private scenery
  "What the worm with eyes looks at: each thing's place as [forward
  right height] (forward and right along the ground from between its
  eyes, height above the floor), half-extents (jME's axes) or radius."
  [{:name "red-box" :type :box :at [2.0 -0.8 0.5] :size [0.4 0.5 0.4] :colour [220 40 40]}
   {:name "blue-ball" :type :sphere :at [2.6 1.0 0.6] :size [0.6] :colour [40 70 220]}
   {:name "yellow-box" :type :box :at [6.0 0.2 1.0] :size [1.5 1.0 0.5] :colour [235 200 30]}
   {:name "green-ball" :type :sphere :at [2.2 0.1 1.6] :size [0.35] :colour [40 170 60]}
   {:name "right-post" :type :box :at [2.4 1.9 1.2] :size [0.1 1.2 0.1] :colour [200 60 200]}
   {:name "left-post" :type :box :at [3.0 -2.4 0.8] :size [0.15 0.8 0.15] :colour [245 140 30]}])

(defn- eye-world
  "The worm with eyes turned by `eye-turn`, its lowest point 0.3 above
  y = 0, planned and built, and `scenery` placed in front of its eyes
  in jME's world: {:creature :plan :objects [{... :position [x y z]}]}."
  []
  (let [c (util/load-blender-model "Models/test-creature/worm-eyes.blend")
        _ (.setLocalRotation c ^com.jme3.math.Quaternion eye-turn)
        [lo] (drops/extent c)
        _ (.move c 0 (float (- 0.3 (double lo))) 0)
        p (plan/plan c)
        _ (body/body! c)
        [a b] (:eyes p)
        mid (mapv #(/ (+ (double %1) (double %2)) 2) (:position a) (:position b))
        ;; where the eyes look (their local -Y), along the ground
        [dx _ dz] (mv (geo/quat->matrix (:rotation a)) [0 -1 0])
        n (Math/hypot dx dz)
        f [(/ dx n) 0.0 (/ dz n)]
        r [(- (f 2)) 0.0 (f 0)]]
    {:creature c :plan p
     :objects (for [{[ahead right height] :at :as o} scenery]
                (assoc o :position (assoc (v+ mid (v+ (mapv #(* ahead %) f) (mapv #(* right %) r)))
                                          1 (double height))))}))

(defn- scenery-geometry
  "A jME Geometry of thing `o`, not physical, in its colour."
  [{:keys [name type size colour position]}]
  (let [[r g b] (map #(/ (double %) 255) colour)
        opts [:name name :physical? false :position (util/vec3 position)
              :color (com.jme3.math.ColorRGBA. (float r) (float g) (float b) (float 1))]]
    (if (= type :box)
      (let [[x y z] size] (apply util/box x y z opts))
      (apply util/sphere (first size) opts))))

(defn eye-scene
  "What camera_check.py needs to see the exported worm with eyes
  beside cortex's: its MJCF written into `dir`, the floor and the
  scenery in Z-up axes, and each eye's classes as cortex saw them
  (a class name per pixel, \"\" for nothing)."
  [dir]
  (require 'cortex.sight)
  (let [{:keys [creature plan objects]} (eye-world)
        mj (str (io/file dir "worm-eyes.xml"))
        _ (ex/write! plan mj nil)
        s (sim/simulation creature {:gravity [0 0 0] :floor 0 :observe #{:eyes}
                                    :eyes {:all {:segmentation true}}})]
    (try
      (doseq [o objects] (.attachChild ^com.jme3.scene.Node (:root s) (scenery-geometry o)))
      (let [seen (:eyes (sim/step! s))]
        {:mjcf mj :floor {:height 0.0}
         :objects (for [{:keys [name type size colour position]} objects]
                    {:name name :type type :pos (geo/z-up position) :colour colour
                     :size (if (= type :box) (let [[x y z] size] [x z y]) size)})
         :eyes (for [{:keys [name spec]} (:eyes plan)
                     :let [{:keys [width height ^ints segmentation labels]} (seen name)]]
                 {:name name :width width :height height :near (:near spec) :far (:far spec)
                  :classes (map #(get labels % "") segmentation)})})
      (finally (sim/destroy! s)))))

(deftest the-exported-eyes-see-what-cortex-s-eyes-see
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-eyes" (make-array FileAttribute 0)))
          scene (eye-scene dir)
          in (str (io/file dir "scene.json"))
          out (str (io/file dir "out.json"))
          _ (spit in ((requiring-resolve 'cortex.compare/json) scene))
          {:keys [exit err]} (shell/sh py "scripts/export/camera_check.py" in out)]
      (is (zero? exit) err)
      (when (zero? exit)
        (let [{:strs [skipped eyes]} ((requiring-resolve 'cortex.blender-test/read-json) (slurp out))]
          (if skipped
            (println (str "SKIPPED cortex.export-test/the-exported-eyes-see-what-cortex-s-eyes-see: "
                          skipped))
            (doseq [{:keys [name width height]} (:eyes scene)
                    :let [{:strs [resolution agreement controls]} (eyes name)]]
              (testing name
                (is (= [width height] resolution) "the camera's resolution is the eye's image size")
                (when agreement
                  (println (format "%s: MuJoCo's camera and cortex's eye agree on %.2f%% of %d pixels"
                                   name (* 100 (double agreement)) (* width height)))
                  (is (<= 0.9 agreement))
                  (doseq [[label a] (sort controls)]
                    (println (format "  a wrong camera, %s: %.2f%%" label (* 100 (double a))))
                    (is (< a 0.9) (str "the check cannot tell a camera " label))))))))))
    (skip "cortex.export-test/the-exported-eyes-see-what-cortex-s-eyes-see")))
