;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.export-test
  (:require [clojure.java.io :as io]
            [clojure.java.shell :as shell]
            [clojure.set :as set]
            [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.drops :as drops]
            [cortex.engine :as engine]
            [cortex.export :as ex]
            [cortex.export.geometry :as geo]
            [cortex.export.model :as model]
            [cortex.joint-fixtures :as jf]
            [cortex.muscle :as muscle]
            [cortex.physics-tab :as physics-tab]
            [cortex.plan :as plan]
            [cortex.rigid-body :as rigid-body]
            [cortex.segment :as segment]
            [cortex.sim :as sim]
            [cortex.blender]
            [cortex.util :as util])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry Spatial)
           (java.nio.file Files)
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

(defn- check-export
  "Run scripts/export/check_export.py with Python `py` on a manifest of
  `entries` written into `dir`: its figures by fixture name, or nil, the
  failed run asserted with what the script said."
  [py dir entries]
  (let [manifest (str (io/file dir "manifest.json"))
        out (str (io/file dir "out.json"))
        _ (spit manifest ((requiring-resolve 'cortex.compare/json) {:fixtures entries}))
        {:keys [exit err]} (shell/sh py "scripts/export/check_export.py" manifest out)]
    (is (zero? exit) err)
    (when (zero? exit)
      ((requiring-resolve 'cortex.blender-test/read-json) (slurp out)))))

(defn- placed
  "[creature plan] of `fixture`: loaded, turned by `turn` (a heading
  about the vertical in radians, none by default, or jME's angles
  [x y z] as Quaternion.fromAngles takes them), placed with its lowest
  point 1 m above y = 0 (as cortex.drops/place! places it), planned and
  built."
  ([fixture] (placed fixture 0.0))
  ([fixture turn]
   (let [[x y z :as angles] (if (number? turn) [0 turn 0] turn)
         c (util/load-blender-model (fixtures fixture))]
     (when-not (every? zero? (map double angles))
       (.rotate c (doto (com.jme3.math.Quaternion.) (.fromAngles (float x) (float y) (float z)))))
     (drops/lift! c)
     (let [p (plan/plan c)]
       (body/body! c)
       [c p]))))

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
      (is (= (ex/mjcf (plan/plan fresh)) (ex/mjcf fresh)) "before body!, its plan now")))
  (let [paddle #(util/load-blender-model "test/fixtures/flat-strangers/flat-hexagon-paddle.blend")
        twin (body/body! (paddle))
        larger (paddle)]
    (sim/destroy! (sim/simulation larger {:observe #{}}))
    (is (= 10.0 (:scale (segment/record larger))) "simulated ten times larger")
    (is (= (ex/mjcf twin) (ex/mjcf larger)) "exported at its size")
    (is (= (ex/urdf twin) (ex/urdf larger)))
    (is (= (ex/meshes twin) (ex/meshes larger)))))

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

(defn- elements
  "The <`tag` .../> elements of `doc`: [{attribute value}]."
  [tag doc]
  (for [[_ attrs] (re-seq (re-pattern (str "<" tag " ([^>]*)/>")) doc)]
    (into {} (for [[_ k v] (re-seq #"(\w+)=\"([^\"]*)\"" attrs)] [k v]))))

(def ^:private geoms (partial elements "geom"))

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
    (let [u (ex/urdf primitive-plan)
          link (second (re-find #"(?s)<link name=\"capsule\">(.*?)</link>" u))
          at (fn [tag] (for [[_ xyz] (re-seq (re-pattern (str "<origin xyz=\"([^\"]*)\"[^>]*/>\\s*<geometry>\\s*<" tag)) link)]
                         (nums xyz)))
          [c] (at "cylinder")
          [s1 _ s2 :as ss] (at "sphere radius=\"0.1\"")]
      (doseq [tag ["<box size=\"0.2 0.4 0.6\"/>" "<sphere radius=\"0.15\"/>"
                   "<cylinder radius=\"0.1\" length=\"0.4\"/>"
                   "<cylinder radius=\"0.1\" length=\"0.5\"/>"]]
        (is (str/includes? u tag) tag))
      (is (not (str/includes? u "<capsule")) "URDF 1.0 has no capsule")
      (is (= 2 (count (re-seq #"<cylinder radius=\"0.1\" length=\"0.4\"/>" link))) "visual and collision")
      (is (= 4 (count ss)) "two spheres, each a visual and a collision")
      (is (close? (Math/sqrt (reduce + (map #(* % %) (map - s1 s2)))) 0.4 1e-9) "the spheres 0.4 apart")
      (is (close? (mapv #(/ (+ %1 %2) 2) s1 s2) c 1e-9) "the cylinder between them"))
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

(deftest cylinders-become-meshes-for-mjx
  (let [p (ex/cylinders-as-meshes primitive-plan)
        by-id (fn [plan] (into {} (map (juxt :id identity)) (:segments plan)))
        {{:keys [type points]} :shape} ((by-id p) "cylinder")]
    (is (= :hull type))
    (is (= (* 2 ex/mesh-cylinder-sides) (count points)))
    (is (every? (fn [[x y z]] (and (close? (Math/abs (double x)) 0.25 1e-12)
                                   (close? (Math/hypot y z) 0.1 1e-12)))
                points)
        "every corner on the cylinder's ends and round its axis")
    (is (= (dissoc ((by-id primitive-plan) "cylinder") :shape) (dissoc ((by-id p) "cylinder") :shape))
        "mass, inertia and place as they were")
    (is (= (dissoc (by-id primitive-plan) "cylinder") (dissoc (by-id p) "cylinder"))
        "every other segment as it was")
    (let [doc (ex/mjcf p)]
      (is (not (re-find #"type=\"cylinder\"" doc)))
      (is (= 1 (count (ex/meshes p))) "the prism, written as a mesh"))))

(deftest a-cone-s-strength-per-axis-or-inscribed
  (doseq [f ["humanoid" "quadruped"]
          :let [[_ p] (placed f)
                ms (ex/muscles p)
                kind (into {} (map (juxt :name :type)) (:joints p))
                joint-of (into {} (for [[j {ds :dofs}] (ex/joint-dofs p)
                                        {d :name} (when (sequential? ds) ds)]
                                    [(str "muscle/" d) j]))
                bounds (fn [opts]
                         (let [doc (ex/mjcf p opts)]
                           (for [a (elements "position" doc)]
                             ;; a point joint's three: muscle/joint/x, y, z
                             [(or (joint-of (a "name")) (joint-of (str/replace (a "name") #"/[xyz]$" "")))
                              (a "forcerange")])))]]
    (testing f
      (is (some #{:cone} (vals kind)) "the fixture has cones")
      (doseq [[opts scale] [[{} 1.0] [{:cone-strength :per-axis} 1.0]
                            [{:cone-strength :inscribed} (/ 1.0 (Math/sqrt 3.0))]]
              :let [bs (bounds opts)]]
        (is (= (set (keys ms)) (set (map first bs))) "every muscle has its actuators, each its joint's")
        (doseq [[j range] bs
                :let [s (:strength (ms j))
                      want (if (= :hinge (kind j)) s (* scale s))
                      [lo hi] (map #(Double/parseDouble %) (str/split range #" "))]]
          (is (and (close? hi want 1e-9) (close? lo (- want) 1e-9))
              (str f " " j " " opts ": " range ", want +-" want)))))
    (is (re-find #":cone-strength :equal"
                 (try (ex/mjcf p {:cone-strength :equal}) ""
                      (catch clojure.lang.ExceptionInfo e (ex-message e)))))))

(def tab-fixtures
  "The Physics-tab creatures exported and checked, by name."
  {"ragdoll" "test/fixtures/physics-sim/ragdoll.blend"
   "rig-chain" "test/fixtures/physics-sim/rig-chain.blend"
   "kick" "test/fixtures/physics-sim/kick.blend"
   "four-bar" "test/fixtures/loops/four-bar.blend"
   "welded-ring" "test/fixtures/loops/welded-ring.blend"
   "addon-ragdoll" "test/fixtures/physics-sim/addon-ragdoll.blend"})

(defn- tab-plan [f] (plan/plan (physics-tab/load-creature (tab-fixtures f))))

(defn- refusal [f] (try (f) nil (catch clojure.lang.ExceptionInfo e (ex-message e))))

(defn- joint-attrs
  "The <joint .../> elements of `doc`, by name: {attribute value}."
  [doc]
  (into {} (for [[_ attrs] (re-seq #"<joint ([^>]*)/>" doc)
                 :let [m (into {} (for [[_ k v] (re-seq #"(\w+)=\"([^\"]*)\"" attrs)] [k v]))]
                 :when (m "name")]
             [(m "name") m])))

(deftest a-friction-cone-pyramidal-or-elliptic
  (let [[_ p] (placed "hand")
        cone (fn [doc] (second (re-find #"<option [^>]*cone=\"(\w+)\"" doc)))]
    (doseq [plan [p (tab-plan "ragdoll")]]
      (is (= "pyramidal" (cone (ex/mjcf plan)) (cone (ex/mjcf plan {:friction-cone :pyramidal}))))
      (is (= "elliptic" (cone (ex/mjcf plan {:friction-cone :elliptic}))))
      (is (re-find #":friction-cone :round is neither :pyramidal nor :elliptic"
                   (str (refusal #(ex/mjcf plan {:friction-cone :round})))))
      (is (re-find #":cone-strength :equal is neither :per-axis nor :inscribed"
                   (str (refusal #(ex/mjcf plan {:cone-strength :equal}))))
          "a Physics-tab creature has no muscles, yet a misspelt option is named"))))

(deftest a-physics-tab-creature-is-a-tree
  (let [p (tab-plan "ragdoll")
        {:keys [joints loops skipped]} (model/tab-joints p)
        {:keys [roots flipped]} (model/tab-tree p)
        doc (ex/mjcf p)
        js (joint-attrs doc)]
    (is (= 9 (count joints)))
    (is (empty? loops))
    (is (empty? skipped))
    (is (= ["ground" "torso"] roots))
    (is (= (set (map :name joints)) flipped))
    (is (= 1 (count (re-seq #"<freejoint" doc))))
    (is (= 27 (count js)))
    (doseq [{:keys [name settings]} joints
            a ["x" "y" "z"]
            :let [lo (get settings (keyword (str "limit-ang-" a "-lower")))
                  hi (get settings (keyword (str "limit-ang-" a "-upper")))]]
      (is (= (str (double lo) " " (double hi)) (get-in js [(str name "/" a) "range"]))))
    (is (not (str/includes? doc "<equality")))
    (let [u (ex/urdf p)]
      (is (= 27 (count (re-seq #"type=\"revolute\"" u))))
      (is (not (str/includes? u "<link name=\"ground\"")))
      (is (str/includes? u "left out, passive and joined to nothing (the world's, where the loader puts it): ground")))
    (is (= ["head/free"] (map second (re-seq #"<freejoint name=\"([^\"]*)\"" (ex/mjcf p {:root "head"}))))))
  (let [c (physics-tab/load-creature (tab-fixtures "ragdoll"))
        p (plan/plan c)]
    (physics-tab/physics-body! c)
    (is (= (ex/mjcf p) (ex/mjcf c)))
    (is (= (ex/urdf p) (ex/urdf c)))))

(defn- made-up
  "A constraint of `type` between a and b, its frame the world's, with
  `limits` ({[kind axis] [lo hi]}) and `extra` settings."
  [type limits & [extra]]
  {:name "c" :type type :segments ["a" "b"] :pivot [0.0 0.0 0.0] :rotation [0 0 0 1]
   :settings (into (merge {:ob1 "a" :ob2 "b"} extra)
                   (for [[[kind axis] [lo hi]] limits
                         kv [[(keyword (str "use-limit-" kind "-" axis)) true]
                             [(keyword (str "limit-" kind "-" axis "-lower")) lo]
                             [(keyword (str "limit-" kind "-" axis "-upper")) hi]]]
                     kv))})

(deftest each-constraint-type-as-joints
  (let [locked {["lin" "x"] [0 0] ["lin" "y"] [0 0] ["lin" "z"] [0 0]}
        generic (made-up "GENERIC" (merge locked {["ang" "x"] [0.1 0.2] ["ang" "z"] [-0.3 0.4]}))
        seen (fn [c flipped?] (mapv (juxt :name :range :axis :slide?) (model/tab-dofs c flipped?)))]
    (is (= [["c/z" [-0.4 0.3] [0.0 0.0 1.0] false] ["c/y" nil [0.0 1.0 0.0] false]
            ["c/x" [-0.2 -0.1] [1.0 0.0 0.0] false]]
           (seen generic false)))
    (is (= [["c/x" [0.1 0.2] [1.0 0.0 0.0] false] ["c/y" nil [0.0 1.0 0.0] false]
            ["c/z" [-0.3 0.4] [0.0 0.0 1.0] false]]
           (seen generic true)))
    (is (= [["c/slide-y" [-0.5 0.25] [0.0 1.0 0.0] true]]
           (seen (made-up "GENERIC" (merge locked {["lin" "y"] [-0.5 0.25]}
                                           {["ang" "x"] [0 0] ["ang" "y"] [0 0] ["ang" "z"] [0 0]}))
                 false))
        "a slide along the first body's Y, nothing turning")
    (is (= [["c" [-0.7 0.5] [0.0 0.0 1.0] false]] (seen (made-up "HINGE" {["ang" "z"] [-0.5 0.7]}) false)))
    (is (= [["c" [-0.5 0.7] [0.0 0.0 1.0] false]] (seen (made-up "HINGE" {["ang" "z"] [-0.5 0.7]}) true)))
    (is (= [["c" [-0.3 0.8] [1.0 0.0 0.0] true]] (seen (made-up "SLIDER" {["lin" "x"] [-0.3 0.8]}) false)))
    (is (= [["c/slide-x" [-0.8 0.3] [1.0 0.0 0.0] true] ["c/x" [-0.2 -0.1] [1.0 0.0 0.0] false]]
           (seen (made-up "PISTON" {["lin" "x"] [-0.3 0.8] ["ang" "x"] [0.1 0.2]}) true)))
    (is (= [] (model/tab-dofs (made-up "FIXED" {}) false)))
    (is (= [{:name "c" :ball true}] (model/tab-dofs (made-up "POINT" {}) false)))
    (is (= [{:name "c/x" :stiffness 50.0 :damping 2.0}]
           (->> (model/tab-dofs (made-up "GENERIC_SPRING" (merge locked {["ang" "x"] [-1 1]})
                                         {:use-spring-ang-x true :spring-stiffness-ang-x 50.0
                                          :spring-damping-ang-x 2.0})
                                false)
                (filter :stiffness)
                (map #(select-keys % [:name :stiffness :damping]))))
        "a spring is its joint's stiffness and damping")
    (let [neck (made-up "GENERIC" (merge locked {["ang" "x"] [0.2 0.2] ["ang" "y"] [0 0] ["ang" "z"] [0 0]}))]
      (is (= [["c/x" [-0.2 -0.2] [1.0 0.0 0.0] false]] (seen neck false))
          "an axis locked away from 0 is a joint whose range is that one angle")
      (is (= [["c/x" [0.2 0.2] [1.0 0.0 0.0] false]] (seen neck true)))
      (is (= 0.2 (model/held-at (first (model/tab-dofs neck true)))))
      (is (nil? (model/held-at (first (model/tab-dofs generic true))))))))

(deftest what-cannot-be-written-is-named
  (let [line {:creature "line.blend" :joints []
              :segments [{:id "rod" :mass 1.0 :friction 0.5 :position [0.0 0.0 0.0]
                          :rotation [0 0 0 1] :inertia {:source :box}
                          :shape {:type :hull :points [[0 0 0] [1 0 0] [2 0 0] [3 0 0]]}}]}]
    (is (re-find #"^segment \"rod\" of creature line.blend has no area: its 4 points lie on a line"
                 (str (refusal #(ex/mjcf line)))))
    (is (= (refusal #(ex/mjcf line)) (refusal #(ex/urdf line))))
    (doseq [m ["heavy" -1.0 nil Double/NaN Double/POSITIVE_INFINITY]
            :let [bad (assoc-in line [:segments 0 :mass] m)]]
      (is (re-find #"^segment \"rod\" of line.blend has mass .* give it a number of kilograms"
                   (str (refusal #(ex/mjcf bad))))
          (pr-str m))
      (is (= (refusal #(ex/mjcf bad)) (refusal #(ex/urdf bad)) (refusal #(ex/muscles bad))))))
  (let [empty-plan (plan/plan (body/body! (util/load-blender-model "test/fixtures/poses/scenes.blend")))]
    (is (= [] (:segments empty-plan)))
    (is (str/includes? (ex/mjcf empty-plan) "<worldbody/>") "MJCF takes a world with nothing in it")
    (is (re-find #"creature .*scenes.blend has no segment: a URDF robot needs a link"
                 (str (refusal #(ex/urdf empty-plan)))))))

(deftest an-add-on-s-ragdoll-exports
  (let [p (tab-plan "addon-ragdoll")
        doc (ex/mjcf p)
        {:keys [skipped]} (model/tab-joints p)]
    (is (= [["torso [Head]" "a GENERIC that limits no axis frees every axis"]]
           (map (fn [[c why]] [(:name c) why]) skipped)))
    (is (str/includes? doc "<freejoint name=\"torso [Active]/free\"/>"))
    (is (nil? (get (joint-attrs doc) "torso [Head]/x")))
    (is (= {"name" "head [Head]/x" "type" "hinge"}
           (select-keys (get (joint-attrs doc) "head [Head]/x") ["name" "type" "range"]))
        "the locked neck has no range")
    (is (re-find #"<joint name=\"head \[Head\]/x/held\" joint1=\"head \[Head\]/x\" polycoef=\"0.17499\d* 0.0 0.0 0.0 0.0\"/>" doc))
    (is (re-find #"<limit lower=\"0.17499\d*\" upper=\"0.17499\d*\"" (ex/urdf p))
        "URDF says it as a range of one angle")
    (is (re-find #"<exclude body1=\"Armature \[Root\]\" body2=\"torso \[Active\]\"/>" doc)
        "the left-out constraint still keeps its bodies apart"))
  (testing "a constraint that limits nothing joins nothing, but a spring does"
    (let [free (fn [c] (:skipped (model/tab-joints {:segments [{:id "a" :mass 1.0} {:id "b" :mass 1.0}]
                                                     :constraints [(assoc c :enabled? true)]})))]
      (is (= ["a GENERIC that limits no axis frees every axis"]
             (map second (free (made-up "GENERIC" {} {:use-spring-x true})))))
      (is (= [] (free (made-up "GENERIC_SPRING" {} {:use-spring-ang-y true}))))
      (is (= ["a GENERIC_SPRING that limits no axis frees every axis"]
             (map second (free (made-up "GENERIC_SPRING" {})))))))
  (testing "a hinge of cortex's own limited to one angle is held there too"
    (let [p (plan/plan (util/load-blender-model "test/fixtures/designer/quadruped.blend"))
          doc (ex/mjcf (update p :joints (partial mapv #(cond-> %
                                                          (= "knee-front-r" (:name %))
                                                          (assoc-in [:description :limit] [0.3 0.3])))))]
      (is (nil? (get-in (joint-attrs doc) ["knee-front-r" "range"])))
      (is (str/includes? doc "<joint name=\"knee-front-r/held\" joint1=\"knee-front-r\" polycoef=\"0.3 0.0 0.0 0.0 0.0\"/>")))))

(deftest loops-and-refusals
  (let [p (tab-plan "kick")
        {:keys [joints loops]} (model/tab-joints p)
        doc (ex/mjcf p)]
    (is (= ["ring"] (map :name loops)))
    (is (= 5 (count joints)))
    (is (re-find #"<connect name=\"ring\" body1=\"bone-1\" body2=\"bone-5\"" doc))
    (is (str/includes? doc "constraint ring closes a loop: a connect at its pivot, its angular limits lost"))
    (is (re-find #"rigid body constraint \"ring\" closes a loop.*a URDF robot is a tree"
                 (str (refusal #(ex/urdf p)))))
    (is (= 15 (count (joint-attrs doc))) "the five others, three hinges each")
    (is (re-find #"<equality solref=\"0.00833\d* 1.0\" solimp=\"0.99 0.999 0.001\"/>" doc)
        "loops as hard as limits"))
  (let [weld (ex/mjcf (tab-plan "welded-ring"))
        hinge (ex/mjcf (tab-plan "four-bar"))]
    (is (re-find #"<weld name=\"ring\" body1=\"bar-4\" body2=\"bar-1\"/>" weld))
    (is (= ["ring" "ring/axis"]
           (map second (re-seq #"<connect name=\"([^\"]*)\" body1=\"coupler\" body2=\"rocker\"" hinge))))
    (is (str/includes? hinge "constraint ring closes a loop: two connects on its axis, its limits lost"))
    (doseq [f ["welded-ring" "four-bar"]]
      (is (re-find #"rigid body constraint \"ring\" closes a loop.*a URDF robot is a tree"
                   (str (refusal #(ex/urdf (tab-plan f))))))))
  (let [p (plan/plan (physics-tab/load-creature "test/fixtures/blend/b45/physics.blend"))
        tab (update p :segments #(filterv (comp #{:rigid-body} :kind) %))]
    (is (re-find #"has both cortex's joints \(seg-joint\) and the Physics tab's rigid bodies"
                 (str (refusal #(ex/mjcf p)))))
    (is (re-find #"rigid body \"ground\": has a MESH collision shape.*Convex Hull"
                 (str (refusal #(ex/mjcf (assoc tab :joints []))))))
    (is (re-find #"rigid body constraint \"motor-joint\": is a MOTOR"
                 (str (refusal #(model/tab-joints tab)))))))

(defn- loop-parting
  "How far the two bodies of each loop of plan `p` part over cortex's
  observations `obs` (:segments every 1/60 s): {name {:apart m :turn
  rad :apart-after-1s :turn-after-1s}}."
  [p obs]
  (let [placed (into {} (map (juxt :id identity)) (:segments p))
        frame (fn [{:keys [position rotation]}] [position (geo/quat->matrix rotation)])
        angle (fn [m] (Math/acos (max -1.0 (min 1.0 (/ (- (+ (get-in m [0 0]) (get-in m [1 1])
                                                              (get-in m [2 2]))
                                                           1.0)
                                                        2.0)))))]
    (into {} (for [{:keys [name type segments pivot rotation]} (:loops (model/tab-joints p))
                   :let [[a b] segments
                         [[xa Ra0] [xb Rb0]] (map (comp frame placed) segments)
                         ;; the hinge's axis, Blender's Z, is the Y of its jME frame
                         z (mapv #(nth % 1) (geo/quat->matrix rotation))
                         pts (if (= "HINGE" type) [pivot (geo/v+ pivot (geo/v* 0.1 z))] [pivot])
                         la (map #(geo/mv (geo/transpose Ra0) (geo/v- % xa)) pts)
                         lb (map #(geo/mv (geo/transpose Rb0) (geo/v- % xb)) pts)
                         at (fn [o id] (frame (or (get-in o [:segments id]) (placed id))))
                         seen (vec (for [o obs
                                         :let [[ya Ra] (at o a) [yb Rb] (at o b)]]
                                     [(apply max (map (fn [pa pb] (geo/norm (geo/v- (geo/v+ ya (geo/mv Ra pa))
                                                                                   (geo/v+ yb (geo/mv Rb pb)))))
                                                      la lb))
                                      (if (= "FIXED" type)
                                        (angle (geo/mm (geo/transpose (geo/mm Ra (geo/transpose Ra0)))
                                                       (geo/mm Rb (geo/transpose Rb0))))
                                        0.0)]))
                         worst (fn [k from] (apply max 0.0 (map #(nth % k) (subvec seen (min from (count seen))))))]]
               [name {:apart (worst 0 0) :turn (worst 1 0)
                      :apart-after-1s (worst 0 60) :turn-after-1s (worst 1 60)}]))))

(defn- tab-run
  "Physics-tab fixture `f` loaded, planned, built and dropped in cortex
  for `seconds`: {:plan :creature :heights (centre of mass, every 1/60
  s) :size :parting (see `loop-parting`)}."
  [f seconds]
  (let [c (physics-tab/load-creature (tab-fixtures f))
        p (plan/plan c)
        _ (physics-tab/physics-body! c)
        mass (into {} (map (juxt :id :mass)) (:segments p))
        total (reduce + (vals mass))
        s (sim/simulation c {:observe #{:segments}})
        obs (vec (repeatedly (long (* 60 seconds)) #(sim/step! s)))
        pts (for [{:keys [position rotation shape mass]} (:segments p)
                  :when (pos? mass)
                  q (model/shape-points shape)]
              (geo/v+ position (geo/mv (geo/quat->matrix rotation) q)))]
    {:plan p :creature c :parting (loop-parting p obs)
     :heights (mapv (fn [o] (/ (reduce + (for [[n {[_ y] :position}] (:segments o)]
                                           (* (get mass n 0.0) y)))
                               total))
                    obs)
     :size (apply max (map - (apply mapv max pts) (apply mapv min pts)))}))

(defn- built-moments
  "The principal moments of each rigid body cortex built for `creature`,
  by name, read from the engine."
  [creature]
  (into {} (for [n (rigid-body/rigid-body-objects creature)
                 :let [^RigidBodyControl c (.getControl (rigid-body/body-spatial n) RigidBodyControl)]
                 :when (and c (pos? (.getMass c)))]
             [(.getName ^com.jme3.scene.Spatial n)
              (mapv #(/ 1.0 (double %)) (engine/inverse-inertia (engine/rigid-body c)))])))

(def ^:private mjx-diverges
  "The Physics-tab fixtures MJX is not run on, with why (see the text on MJX below)."
  {"addon-ragdoll" (str "at the add-on's step of 1/60 s MJX diverges after the landing"
                        " (0.9 s), where MuJoCo lies still; at 1/240 s the two agree")})

(defn- tab-entry
  "What check_export.py needs of the run of fixture `f`, written into `dir`."
  [f {:keys [plan]} dir]
  (let [mj (str (io/file dir (str f ".xml")))
        tree? (empty? (:loops (model/tab-joints plan)))
        u (when tree? (str (io/file dir (str f ".urdf"))))
        {:keys [roots joint children]} (model/tab-tree plan)
        by-id (into {} (map (juxt :id identity)) (:segments plan))
        ;; the URDF's root: the root that is not scenery
        root (by-id (first (filter #(or (pos? (:mass (by-id %))) (seq (children %))) roots)))]
    (ex/write! plan mj u)
    (cond-> {:name f :mjcf mj :urdf u :seconds 5.0 :joints [] :held true
             :mjx_seconds (when-not (mjx-diverges f) 1.0)
             :pairs (for [{:keys [segments settings]} (vals joint)
                          :when (:disable-collisions settings)]
                      segments)
             :tab_limits (for [{:keys [name type segments rotation] :as c} (:constraints plan)
                               :when (#{"GENERIC" "GENERIC_SPRING" "HINGE"} type)]
                           {:name name :type type :segments segments
                            :frame (geo/z-up-rotation (geo/quat->matrix rotation))
                            :limits (mapv #(when (vector? %) %) (model/axis-limits c "ang"))})
             :loops (for [{:keys [name type segments pivot rotation]} (:loops (model/tab-joints plan))
                          :let [pin (geo/z-up pivot)
                                z (mapv #(nth % 2) (geo/z-up-rotation (geo/quat->matrix rotation)))]]
                      {:name name :segments segments :weld (= "FIXED" type)
                       :points (if (= "HINGE" type) [pin (mapv + pin (map #(* 0.1 %) z))] [pin])})}
      root (assoc :base {:link (:id root) :pos (geo/z-up (:position root))
                         :quat (geo/matrix->quat (geo/z-up-rotation (geo/quat->matrix (:rotation root))))}))))

(def ^:private mjx-without-jdotv
  "The Physics-tab fixtures whose loop moves so fast in its first second
  that MJX, which leaves out an equality's J'v term, parts from MuJoCo
  (see the text): the kicking ring."
  #{"kick"})

(defn- check-mjx
  "MJX took fixture `f`'s document as it is, and its held drop's centre
  of mass is MuJoCo's (`mj-held`) within 1% of size `sz` after 1 s, and
  within 5% all through that second (landing, float32 against float64
  finds a contact a step apart), but for a `loop?` whose equality MJX
  solves without MuJoCo's J'v term, where that was measured to matter
  (`mjx-without-jdotv`, see the text): there only printed."
  ([f sz mjx mj-held] (check-mjx f sz mjx mj-held false))
  ([f sz mjx mj-held loop?]
   (if-let [why (get mjx "skipped")]
     (println (str "SKIPPED cortex.export-test, " f " in MJX: " why))
     (do (is (nil? (get mjx "error")) (str f ": MJX refused the document: " (get mjx "error")))
         (when-let [hs (seq (get mjx "heights"))]
           (let [apart (apply max (map #(Math/abs (- (double %1) (double %2))) hs (mj-held "heights")))
                 mine (double (last hs))
                 theirs (double (nth (mj-held "heights") (dec (count hs))))]
             (println (format "%s, held, in MJX (JAX %s, rotation chain %s%s): centre of mass %.4f m after 1 s, MuJoCo's %.4f; at most %.5f m apart, size %.3f"
                              f (get mjx "jax") (get mjx "chain") (if (false? (get mjx "fusion")) ", XLA's fusion off" "")
                              mine theirs apart (double sz)))
             (is (= 60 (count hs)))
             (is (< (Math/abs (- mine theirs)) (* 0.01 sz)) (str f ": MJX's held drop after 1 s " mine ", MuJoCo's " theirs))
             (when-not loop?
               (is (< apart (* 0.05 sz)) (str f ": MJX's held drop " apart " m from MuJoCo's, size " sz)))))))))

(deftest a-physics-tab-creature-in-mujoco
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-tab-export" (make-array FileAttribute 0)))
          runs (into {} (for [f (sort (keys tab-fixtures))] [f (tab-run f 5.0)]))
          result (check-export py dir (for [[f r] runs] (tab-entry f r dir)))]
      (doseq [[f {:keys [plan creature heights size parting]}] runs
              :let [{:strs [mujoco bodies tab_limits urdf loops mjx] mj-drop "drop" mj-held "held"} (get result f)
                    moments (built-moments creature)]
              :when result]
        (testing f
          (is (nil? (get mujoco "error")))
          (is (empty? (get mujoco "warnings")))
          (is (= (set (map :id (:segments plan))) (set (keys bodies))))
          (doseq [{:keys [id mass position rotation]} (:segments plan)
                  :when (pos? mass)
                  :let [{m "mass" com "com" I "inertia"} (bodies id)
                        R (geo/mm geo/C (geo/quat->matrix rotation))
                        want (geo/mm (geo/mm R (mapv #(assoc [0.0 0.0 0.0] % ((moments id) %)) (range 3)))
                                     (geo/transpose R))
                        norm (fn [m] (Math/sqrt (reduce + (map #(* % %) (flatten m)))))]]
            (testing id
              (is (close? m mass 1e-6))
              (is (< (norm (map - com (geo/z-up position))) (* 1e-6 size)))
              (is (< (norm (map #(map - %1 %2) I want)) (* 1e-6 (norm want))) (pr-str I want))))
          (println (str "Physics tab, " f ": centre of mass after 1 s and at the end: "
                        (format "MuJoCo %.3f m and %.3f m (fastest body then %.3f m/s)"
                                (nth (mj-drop "heights") 59) (peek (mj-drop "heights"))
                                (mj-drop "rest_speed"))
                        (format "; cortex %.3f m and %.3f m" (nth heights 59) (peek heights))
                        (when-let [h (get-in urdf ["drop" "heights"])]
                          (format "; PyBullet %.3f m and %.3f m" (nth h 59) (peek h)))
                        "; size " (format "%.2f" size)
                        (format "; limits passed in MuJoCo by at most %.3f rad"
                                (double (apply max 0.0 (mapcat val (dissoc tab_limits "ring")))))))
          (doseq [[label i] [["after 1 s" 59] ["at the end" (dec (count heights))]]]
            (is (< (Math/abs (- (double (nth (mj-drop "heights") i)) (nth heights i))) (* 0.05 size))
                (str label ": MuJoCo's centre of mass " (nth (mj-drop "heights") i) " m up, cortex's "
                     (nth heights i) ", size " size)))
          (is (= {} (mj-drop "warnings")) "MuJoCo warned during the drop")
          (if-let [why (mjx-diverges f)]
            (println (str "Physics tab, " f ": not run in MJX: " why))
            (check-mjx f size mjx mj-held (contains? mjx-without-jdotv f)))
          (doseq [[n past] tab_limits
                  :when (not= n "ring")]
            (is (every? #(< % 0.05) past) (str n " past its limits by " past)))
          ;; each loop holds in MuJoCo: its bodies part by less than 1 cm, a weld's turn by 0.02 rad
          (is (= (set (map :name (:loops (model/tab-joints plan)))) (set (keys loops))))
          (doseq [[n {:strs [apart turn apart_after_1s turn_after_1s]}] loops
                  :let [{:keys [apart-after-1s turn-after-1s] :as mine} (parting n)]]
            (println (format (str "Physics tab, %s: loop %s parts by at most %.4f m (%.4f after 1 s),"
                                  " turns by %.4f rad (%.4f) in MuJoCo; in cortex %.4f m (%.4f), %.4f rad (%.4f)")
                             f n apart apart_after_1s turn turn_after_1s
                             (:apart mine) apart-after-1s (:turn mine) turn-after-1s))
            ;; the kicking ring starts outside its limits: judged after its first second
            (let [[apart turn] (if (= f "kick") [apart_after_1s turn_after_1s] [apart turn])]
              (is (< apart 0.01) (str n ": its bodies part by " apart " m"))
              (is (< turn 0.02) (str n ": its bodies turn by " turn " rad"))))
          (when urdf
            (doseq [{:keys [id mass]} (:segments plan) :when (pos? mass)]
              (is (close? (get-in urdf ["masses" id]) mass 1e-6) id)))
          (when (#{"ragdoll" "addon-ragdoll"} f)
            ;; PyBullet's chain sags away from the others (see the text)
            (let [h (get-in urdf ["drop" "heights"])]
              (doseq [[label i] [["after 1 s" 59] ["at the end" (dec (count heights))]]]
                (is (< (Math/abs (- (double (nth h i)) (nth heights i))) (* 0.05 size))
                    (str label ": PyBullet's centre of mass " (nth h i) " m up, cortex's "
                         (nth heights i) ", size " size))))))))
    (skip "cortex.export-test/a-physics-tab-creature-in-mujoco")))

(def ^:private stations
  "The stations of physics.blend that MJCF can say: each anchor (-a)
  and its body (-b)."
  ["fixed" "point" "hinge" "slider" "piston" "generic" "spring"])

(defn- stations-plan
  "Plan `p` of physics.blend with only the `stations`, its MESH bodies
  boxes."
  [p]
  (let [keep? (set (for [s stations k ["-a" "-b"]] (str s k)))]
    (-> p
        (assoc :joints [])
        (update :segments (fn [ss] (vec (for [s ss :when (keep? (:id s))]
                                          (cond-> s
                                            (= :mesh (:type (:shape s)))
                                            (assoc :shape {:type :box :half-extents [0.5 0.1 0.1]}))))))
        (update :constraints (fn [cs] (filterv #(every? keep? (:segments %)) cs))))))

(deftest every-constraint-type-moves-as-in-cortex
  (if-let [py (python)]
    (let [c (physics-tab/load-creature "test/fixtures/blend/b45/physics.blend")
          p (stations-plan (plan/plan c))
          _ (physics-tab/physics-body! c)
          s (sim/simulation c {:observe #{:segments}})
          obs (vec (repeatedly 240 #(sim/step! s)))
          dir (str (Files/createTempDirectory "cortex-tab-stations" (make-array FileAttribute 0)))
          mj (str (io/file dir "stations.xml"))
          _ (ex/write! p mj nil)
          result (get (check-export py dir [{:name "stations" :mjcf mj :urdf nil :seconds 1.0
                                             :joints [] :track [1.0 4.0]}])
                      "stations")]
      (when result
        (is (nil? (get-in result ["mujoco" "error"])))
        (is (empty? (get-in result ["mujoco" "warnings"])))
        (doseq [[t i] [["1.0" 59] ["4.0" 239]]
                st stations
                :let [id (str st "-b")
                      ours (geo/z-up (:position (get-in obs [i :segments id])))
                      theirs (get-in result ["track" t id])
                      gap (geo/norm (geo/v- ours theirs))]]
          (if (= st "point")
            (println (format "physics.blend's point joint after %s s: cortex's body at %s, MuJoCo's at %s"
                             t (pr-str (mapv #(/ (Math/round (* 1000.0 %)) 1000.0) ours))
                             (pr-str (mapv #(/ (Math/round (* 1000.0 %)) 1000.0) theirs))))
            (is (< gap 0.01) (str st " after " t " s: cortex's body at " ours ", MuJoCo's at " theirs))))))
    (skip "cortex.export-test/every-constraint-type-moves-as-in-cortex")))

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

(defn- held
  "The actions that hold every joint of `plan` at 0, the pose it was
  built in, as the exported servos hold it told 0."
  [plan]
  (into {} (for [{:keys [name type]} (:joints plan)]
             [name {:target (if (= type :hinge) 0.0 [0.0 0.0 0.0])}])))

(defn- com-height
  "A function of an observation: the height of the centre of mass of
  `plan`'s segments in it."
  [plan]
  (let [mass (into {} (map (juxt :id :mass)) (:segments plan))
        total (reduce + (vals mass))]
    (fn [o] (/ (reduce + (for [[n {[_ y] :position}] (:segments o)] (* (mass n) y))) total))))

(defn- up-of
  "How far segment `id`'s own y points up in observation `o` (1
  upright, 0 on its side)."
  [o id]
  (get-in (geo/quat->matrix (get-in o [:segments id :rotation])) [1 1]))

(defn- cortex-drop
  "Heights of `creature`'s centre of mass after each 1/60 s step, and
  its fastest segment over the last half second; its muscles sent
  `actions` every step (none: limp), for `secs` (default `seconds`);
  with `up-segment`, also :up, how far that segment's own y points up
  at the end (1 upright, 0 on its side); :across, where the centre of
  mass is across the floor after each step, [x y] as MuJoCo has it;
  :scale, what the simulation chose (see cortex.sim/simulation); with
  `after`, :after, what (after simulation observations) returns at the
  end, before the simulation is destroyed."
  ([creature plan actions] (cortex-drop creature plan actions seconds nil))
  ([creature plan actions secs up-segment] (cortex-drop creature plan actions secs up-segment nil))
  ([creature plan actions secs up-segment after]
   (let [mass (into {} (map (juxt :id :mass)) (:segments plan))
         total (reduce + (vals mass))
         s (sim/simulation creature {:floor {:height 0 :friction 1.0} :observe #{:segments}})
         [obs later] (try (let [obs (vec (repeatedly (long (* 60 secs)) #(sim/step! s actions)))]
                            [obs (when after (after s obs))])
                          (finally (sim/destroy! s)))]
     (cond-> {:scale (sim/scale s)
              :heights (mapv (com-height plan) obs)
              ;; across the floor, as MuJoCo has it (Z up): jME's x and -z
              :across (mapv (fn [o] (let [[x _ z] (reduce (fn [acc [n {p :position}]]
                                                           (mapv + acc (map #(* (mass n) %) p)))
                                                         [0.0 0.0 0.0] (:segments o))]
                                      [(/ x total) (/ (- z) total)]))
                            obs)
              :rest-speed (apply max (for [o (subvec obs (- (count obs) 30))
                                           [_ {v :velocity}] (:segments o)]
                                       (Math/sqrt (reduce + (map * v v)))))}
       up-segment (assoc :up (up-of (peek obs) up-segment))
       after (assoc :after later)))))


(defn- urdf-base
  "Where PyBullet puts the root link of `plan`'s URDF so that the
  creature stands where the plan has it, Z up: {:link :pos :quat}."
  [plan]
  (let [{:keys [roots]} (ex/tree plan)
        root (first (filter #(= (first roots) (:id %)) (:segments plan)))]
    {:link (:id root) :pos (geo/z-up (:position root))
     :quat (geo/matrix->quat (z-up-rotation (geo/quat->matrix (:rotation root))))}))

(defn- manifest-entry
  "What check_export.py needs of fixture `f`, written into `dir`."
  [f plan dir]
  (let [mj (str (io/file dir (str f ".xml")))
        inscribed (str (io/file dir (str f "-inscribed.xml")))
        urdf (str (io/file dir (str f ".urdf")))
        dofs (ex/joint-dofs plan)]
    (ex/write! plan mj urdf)
    (ex/write! plan inscribed nil {:cone-strength :inscribed})
    {:name f :mjcf mj :mjcf_inscribed inscribed :urdf urdf :seconds seconds :held true
     :mjx_seconds 1.0 :random_seconds seconds
     :pairs (map :segments (:joints plan))
     :base (urdf-base plan)
     :joints (for [{:keys [name type segments rotation description]} (:joints plan)
                   :when (not= type :point)
                   :let [{ds :dofs} (dofs name)]]
               (cond-> {:name name :type type :segments segments
                        :dofs (for [d ds] {:joint (:name d) :actuator (str "muscle/" (:name d))
                                           :range (:range d)})}
                 (= type :hinge) (assoc :axis (:axis (first ds)))
                 (#{:cone :spring} type) (assoc :frame (let [[turn] (model/cone-frame description)]
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
  text: cortex's limp four-legged creature rolls onto its side)."
  #{"worm" "hand" "humanoid"})

(def ^:private stays-put
  "The fixtures that do not topple when dropped, lying as they were
  built: where they end across the floor is compared too."
  #{"worm" "hand"})

(def ^:private stands-when-held
  "The fixtures that do not topple when held: the four-legged creature
  stands on its legs."
  #{"quadruped"})

(defn- check-across
  "Where fixture `f`'s centre of mass is across the floor in `theirs`
  (a drop of check_export.py, by `who`) and in `cortex`'s drop, after 1
  s and at the end: printed, and where it `put?` (does not topple),
  within 5% of size `sz`."
  [f who sz theirs cortex put?]
  (doseq [[label i] [["after 1 s" 59] ["at the end" (dec (count (:across cortex)))]]
          :let [a (nth (theirs "across") i) b (nth (:across cortex) i)
                apart (Math/sqrt (reduce + (map #(let [d (- (double %1) (double %2))] (* d d)) a b)))]]
    (println (format "%s, %s %s: centre of mass across the floor %.4f m from cortex's (size %.3f)"
                     f who label apart (double sz)))
    (when put?
      (is (< apart (* 0.05 sz)) (str who ", " label ": " (pr-str a) " across the floor, cortex's "
                                     (pr-str b) ", size " sz)))))

(defn- drop-figures [who heights rest-speed]
  (format "%s: centre of mass %.3f m up after 1 s, %.3f m at the end, fastest segment then %.3f m/s"
          who (double (nth heights 59)) (double (peek (vec heights))) (double rest-speed)))

(def ^:private holds-its-pose
  "The fixtures whose muscles hold their pose, held, so that they come
  to rest (see the text)."
  #{"worm" "hand"})

(def ^:private inscribed-rests
  "The fixtures whose inscribed MuJoCo copy, held, comes to rest: those
  that hold their pose, and the humanoid, whose cones can no longer
  rock it (see the text)."
  (conj holds-its-pose "humanoid"))

(defn- check-held
  "Fixture `f`'s held drop: cortex's centre of mass where MuJoCo's is,
  within 5% of size `sz`, after 1 s and at the end, for both of MuJoCo's
  copies (`mj-held`, each cone servo bounded by the strength;
  `mj-inscribed`, by the strength over sqrt 3); MuJoCo's inscribed copy
  at rest where it `inscribed-rests`, and every copy where the creature
  `holds-its-pose`."
  [f sz cortex-held mj-held mj-inscribed]
  (testing "held"
    (doseq [[who mj] [["MuJoCo" mj-held] ["MuJoCo, inscribed" mj-inscribed]]]
      (println (str f ", held: " (drop-figures who (mj "heights") (mj "rest_speed"))
                    "; " (drop-figures "cortex" (:heights cortex-held) (:rest-speed cortex-held))))
      (is (= {} (mj "warnings")) (str who " warned during the held drop"))
      (check-across f (str who ", held,") sz mj cortex-held (or (stays-put f) (stands-when-held f)))
      (doseq [[label i] [["after 1 s" 59] ["at the end" (dec (count (mj "heights")))]]]
        (is (< (Math/abs (- (double (nth (mj "heights") i)) (nth (:heights cortex-held) i)))
               (* 0.05 sz))
            (str who ", " label ": centre of mass " (nth (mj "heights") i) " m up, cortex's "
                 (nth (:heights cortex-held) i) ", size " sz))))
    (when (inscribed-rests f)
      (is (< (double (mj-inscribed "rest_speed")) 0.1)
          (str "MuJoCo's inscribed copy, held, still moving at " (mj-inscribed "rest_speed") " m/s")))
    (when (holds-its-pose f)
      (is (< (double (mj-held "rest_speed")) 0.1)
          (str "MuJoCo's copy, held, still moving at " (mj-held "rest_speed") " m/s"))
      (is (< (double (:rest-speed cortex-held)) 0.1)
          (str "cortex's creature, held, still moving at " (:rest-speed cortex-held) " m/s")))))

(defn- norm [m] (Math/sqrt (reduce + (map #(* % %) (flatten m)))))

(defn- inertial
  "Segment `seg` of a plan as a simulator holds it, Z up: {:com its
  centre of mass, :inertia its inertia about it in the world's axes}."
  [{:keys [position rotation inertia]}]
  (let [R (geo/quat->matrix rotation)
        axes (mm C (mm R (geo/quat->matrix (:rotation inertia))))]
    {:com (geo/z-up (v+ position (mv R (:centre inertia))))
     :inertia (mm (mm axes (mapv #(assoc [0.0 0.0 0.0] % (nth (:moments inertia) %)) (range 3)))
                  (apply mapv vector axes))}))

(defn- check-inertial
  "`got` ({\"com\" \"inertia\"}, as a simulator read it) is segment
  `seg`'s, to a millionth of the creature's size `sz` and of the
  inertia."
  [sz seg {com "com" I "inertia" :as got}]
  (let [{want-com :com want :inertia} (inertial seg)]
    (is (some? got) "no centre of mass and inertia read")
    (when got
      (is (< (norm (map - com want-com)) (* 1e-6 sz)) (pr-str com want-com))
      (is (< (norm (map #(map - %1 %2) I want)) (* 1e-6 (norm want))) (pr-str I want)))))

(defn- check-bodies
  "MuJoCo compiled `plan`'s document without an error or a warning, and
  its `bodies` are the plan's segments with the plan's masses, centres of
  mass and inertias, to a millionth."
  [plan mujoco bodies]
  (is (nil? (get mujoco "error")))
  (is (empty? (get mujoco "warnings")))
  (is (= (set (map :id (:segments plan))) (set (keys bodies))))
  (doseq [{:keys [id mass] :as seg} (:segments plan)]
    (testing id
      (is (close? (get-in bodies [id "mass"]) mass 1e-6))
      (check-inertial (size plan) seg (bodies id)))))

(defn- check-urdf
  "check_urdf accepted `plan`'s URDF, saying no error (it exits 0 even
  when it drops a link's geometry), and PyBullet loaded it with the
  plan's masses, and, but for a Physics-tab creature's (whose inertias
  are Blender's, checked in MuJoCo by its own test), the plan's centres
  of mass and inertias."
  [plan urdf]
  (let [{code "code" out "output"} (get urdf "check_urdf")]
    (is (zero? (or code 0)) out)
    (is (not (str/includes? (str out) "Error")) out))
  (doseq [{:keys [id mass] :as seg} (:segments plan)]
    (testing (str "PyBullet's " id)
      (is (close? (get-in urdf ["masses" id]) mass 1e-6) id)
      (when-not (model/physics-tab? plan)
        (check-inertial (size plan) seg (get-in urdf ["inertias" id]))))))

(defn- check-limp-drop
  "Fixture `f`'s limp drop `d` in `who` (a drop of check_export.py)
  against `cortex`'s, `sz` the creature's size: printed; the centre of
  mass's height after 1 s within 5% of the size, and where the two are
  `alike?`, at the end too, and `d` at rest; across the floor as
  `check-across` compares it, asserted where the creature does not
  topple (`put?`)."
  [f sz who {:strs [heights rest_speed] :as d} cortex alike? put?]
  (println (str f (if alike? ", limp: " ", limp, its end not yet alike: ")
                (drop-figures who heights rest_speed) "; "
                (drop-figures "cortex" (:heights cortex) (:rest-speed cortex))))
  (testing who
    (check-across f (str who ", limp,") sz d cortex put?)
    (doseq [[label i] (cond-> [["after 1 s" 59]]
                        alike? (conj ["at the end" (dec (count heights))]))]
      (is (< (Math/abs (- (double (nth heights i)) (nth (:heights cortex) i))) (* 0.05 sz))
          (str label ": centre of mass " (nth heights i) " m up, cortex's "
               (nth (:heights cortex) i) ", size " sz)))
    (when alike?
      (is (< (double rest_speed) 0.1) (str "still moving at " rest_speed " m/s")))))

(defn- check-random
  "MuJoCo took random controls within their ranges (`random` of
  check_export.py, three runs) without a warning, and every actuator of
  fixture `f` has a range."
  [f {:strs [unlimited runs]}]
  (println (format "%s, random controls in MuJoCo for %.0f s: fastest joint %s rad/s" f seconds
                   (str/join ", " (map #(format "%.1f" (double (% "fastest"))) runs))))
  (is (empty? unlimited) (str "actuators without a ctrlrange: " (pr-str unlimited)))
  (is (= 3 (count runs)))
  (doseq [{:strs [warnings]} runs]
    (is (= {} warnings) (str "random controls: MuJoCo warned " (pr-str warnings)))))

(defn- check-fixture
  [f plan cortex cortex-held {:strs [mujoco bodies drives drop urdf mjx random] mj-held "held"
                              mj-inscribed "held_inscribed"}]
  (testing f
    (check-bodies plan mujoco bodies)
    (is (= {} (get drop "warnings")) "MuJoCo warned during the limp drop")
    (let [sz (size plan)
          dofs (ex/joint-dofs plan)]
      (doseq [{:strs [joint dof end angles]} drives
              :let [[k want] (expected-angle (dofs joint) dof end)]]
        (is (< (Math/abs (- (double (nth angles k)) want)) 0.05)
            (str joint " " dof " to its " end ": " (nth angles k) ", cortex's limit " want)))
      (doseq [[who d] [["MuJoCo" drop] ["PyBullet" (get urdf "drop")]]]
        (check-limp-drop f sz who d cortex (settles-alike f) (stays-put f)))
      (when (settles-alike f)
        (is (< (:rest-speed cortex) 0.1) (str "cortex still moving at " (:rest-speed cortex))))
      (check-held f sz cortex-held mj-held mj-inscribed)
      (check-random f random)
      (check-mjx f sz mjx mj-held)
      (check-urdf plan urdf))))

(deftest mujoco-and-pybullet-agree-with-cortex
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-export" (make-array FileAttribute 0)))
          runs (vec (for [f (sort (keys fixtures))]
                      (let [[c plan] (placed f)
                            [c2] (placed f)]
                        {:f f :plan plan :entry (manifest-entry f plan dir)
                         :cortex (cortex-drop c plan nil)
                         :cortex-held (cortex-drop c2 plan (held plan))})))]
      (when-let [result (check-export py dir (map :entry runs))]
        (doseq [{:keys [f plan cortex cortex-held]} runs]
          (check-fixture f plan cortex cortex-held (result f)))))
    (skip "cortex.export-test/mujoco-and-pybullet-agree-with-cortex")))

(def ^:private headings
  "Twelve turns about the vertical, 30 degrees apart, in radians."
  (mapv #(* % (/ Math/PI 6)) (range 12)))

(defn- pose-of [up] (if (> (double up) 0.5) :belly :side))

(defn- check-two-rests
  "`drops`: per heading, {:heading :cortex :mujoco}, each a drop with
  :heights, :rest-speed and :up; `sz` the creature's size."
  [sz drops]
  (let [ends (for [{:keys [cortex mujoco]} drops
                   [who d] [["cortex" cortex] ["MuJoCo" mujoco]]]
               {:who who :pose (pose-of (:up d)) :end (peek (:heights d))})]
    (doseq [{:keys [heading cortex mujoco]} drops
            :let [deg (Math/round (Math/toDegrees heading))]]
      (println (format "four-legged, limp, turned %3d degrees: MuJoCo %.3f m up after 1 s, %.3f at the end (%s, %.3f m/s); cortex %.3f, %.3f (%s, %.3f m/s)"
                       deg (nth (:heights mujoco) 59) (peek (:heights mujoco))
                       (name (pose-of (:up mujoco))) (:rest-speed mujoco)
                       (nth (:heights cortex) 59) (peek (:heights cortex))
                       (name (pose-of (:up cortex))) (:rest-speed cortex)))
      (testing (str "turned " deg " degrees")
        (is (< (double (:rest-speed mujoco)) 0.1) (str "MuJoCo's still moving at " (:rest-speed mujoco)))
        (is (< (double (:rest-speed cortex)) 0.1) (str "cortex's still moving at " (:rest-speed cortex)))))
    (is (some (fn [pose] (= #{"cortex" "MuJoCo"} (set (map :who (filter #(= pose (:pose %)) ends)))))
              [:belly :side])
        "no pose that both simulators end in")
    (doseq [pose [:belly :side]
            :let [at (filter #(= pose (:pose %)) ends)
                  hs (map :end at)]
            :when (seq hs)]
      (is (< (- (apply max hs) (apply min hs)) (* 0.05 sz))
          (str "on its " (name pose) " at " (pr-str (map (juxt :who :end) at)))))))


(defn- check-elliptic
  "MuJoCo's drops with the elliptic cone, one per heading: all at rest,
  all in one pose, their ends within 1% of size `sz` of each other."
  [sz drops]
  (let [ends (map #(peek (% "heights")) drops)
        poses (map #(pose-of (% "up")) drops)]
    (println (format "four-legged, limp, elliptic friction cone: MuJoCo at %.3f to %.3f m at the end, on its %s at the 12 headings, fastest segment %.3f m/s at most"
                     (apply min ends) (apply max ends) (str/join " or " (map name (distinct poses)))
                     (apply max (map #(% "rest_speed") drops))))
    (is (= 1 (count (distinct poses))) (str "poses " (pr-str poses)))
    (is (< (- (apply max ends) (apply min ends)) (* 0.01 sz)) (str "ends " (pr-str ends)))
    (doseq [d drops]
      (is (< (double (d "rest_speed")) 0.1)))))

(def ^:private pushes
  "The unturned drops' sideways pushes (m/s), 5 s in, and the pose each
  must end in, in MuJoCo with either cone (see the text)."
  {0.05 :belly 0.4 :side})

(defn- check-basin
  "MuJoCo's unturned drops, pushed: `drops` {[cone push] drop}."
  [drops]
  (doseq [[[cone push] d] (sort drops)
          :let [want (pushes push)]]
    (println (format "four-legged, limp, unturned, %s cone, pushed sideways at %.2f m/s after 5 s: on its %s at %.3f m, fastest segment %.3f m/s"
                     cone push (name (pose-of (d "up"))) (peek (d "heights")) (d "rest_speed")))
    (testing (str cone " cone, pushed at " push " m/s")
      (is (= want (pose-of (d "up"))))
      (is (< (double (d "rest_speed")) 0.1)))))

(defn- wake-and-push
  "An `after` for cortex-drop: where `creature` (of `plan`, turned by
  `heading`) lies on its belly, wake every segment for good, push it
  at 0.05 m/s toward its own side and go on for 10 s: {:up :end}, where
  its torso points and its centre of mass's height then; nil where it
  lies on its side."
  [creature plan heading]
  (let [height (com-height plan)
        up #(up-of % "torso")]
    (fn [s obs]
      (when (= :belly (pose-of (up (peek obs))))
        (let [side (Vector3f. (float (Math/sin heading)) 0 (float (Math/cos heading)))]
          (doseq [^RigidBodyControl rb (keep #(.getControl ^Spatial % RigidBodyControl)
                                             (segment/segments creature))]
            (.setSleepingThresholds rb 0 0)
            (.activate rb)
            (.setLinearVelocity rb (.add (.getLinearVelocity rb) (.mult side (float 0.05)))))
          (let [o (last (repeatedly 600 #(sim/step! s nil)))]
            {:up (up o) :end (height o)}))))))

(defn- check-woken
  "At least half of cortex's belly rests in `runs` keep the belly when
  woken and pushed (`wake-and-push`)."
  [runs]
  (let [woken (for [{:keys [heading cortex]} runs
                    :when (:after cortex)]
                (assoc (:after cortex) :heading heading :was (peek (:heights cortex))))]
    (doseq [{:keys [heading up end was]} woken]
      (println (format "four-legged, limp, turned %3d degrees, on its belly at %.3f m in cortex: woken and pushed sideways at 0.05 m/s, on its %s at %.3f m 10 s later"
                       (Math/round (Math/toDegrees heading)) was (name (pose-of up)) end)))
    (if (empty? woken)
      (println (str "four-legged, limp: no drop ends on its belly on " (name engine/name)
                    ", so no belly rest to wake"))
      (is (<= (count woken) (* 2 (count (filter #(= :belly (pose-of (:up %))) woken))))
          (str "belly rests that rolled when woken: "
               (pr-str (map :heading (remove #(= :belly (pose-of (:up %))) woken))))))))

(deftest the-four-legged-creature-rests-as-mujocos-does
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-turned" (make-array FileAttribute 0)))
          secs 30.0
          runs (vec (for [h headings]
                      (let [[c p] (placed "quadruped" h)
                            mj (str (io/file dir (format "quadruped-%.2f.xml" h)))
                            ellipse (str (io/file dir (format "quadruped-%.2f-elliptic.xml" h)))
                            files [["" mj] [" elliptic" ellipse]]]
                        (ex/write! p mj nil)
                        (ex/write! p ellipse nil {:friction-cone :elliptic})
                        {:heading h :plan p
                         :entries (concat
                                   (for [[k path] files]
                                     {:name (str h k) :mjcf path :seconds secs :limp_only true
                                      :up_body "torso"})
                                   (when (zero? (double h))
                                     (for [[k path] files, v (keys pushes)]
                                       {:name (str "pushed " v k) :mjcf path :seconds secs
                                        :limp_only true :up_body "torso" :push {:at 5.0 :speed v}})))
                         :cortex (cortex-drop c p nil secs "torso" (wake-and-push c p h))})))
          sz (size (:plan (first runs)))]
      (when-let [result (check-export py dir (mapcat :entries runs))]
        (doseq [{:keys [entries]} runs
                {:keys [name]} entries]
          (is (nil? (get-in result [name "mujoco" "error"])))
          (is (= {} (get-in result [name "drop" "warnings"]))))
        (check-two-rests sz (for [{:keys [heading cortex]} runs
                                  :let [{:strs [heights rest_speed up]} (get-in result [(str heading) "drop"])]]
                              {:heading heading :cortex cortex
                               :mujoco {:heights heights :rest-speed rest_speed :up up}}))
        (check-elliptic sz (for [{:keys [heading]} runs]
                             (get-in result [(str heading " elliptic") "drop"])))
        (check-basin (into {} (for [[cone k] [["pyramidal" ""] ["elliptic" " elliptic"]]
                                    v (keys pushes)]
                                [[cone v] (get-in result [(str "pushed " v k) "drop"])])))
        (check-woken runs)))
    (skip "cortex.export-test/the-four-legged-creature-rests-as-mujocos-does")))

(def ^:private on-its-side
  "jME's angles that lay the four-legged creature on its side: a
  quarter turn about its length."
  [(/ Math/PI 2) 0.0 0.0])

(deftest the-four-legged-creature-laid-on-its-side-lands-alike
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-side" (make-array FileAttribute 0)))
          [c p] (placed "quadruped" on-its-side)
          f "four-legged, laid on its side"
          entry (assoc (manifest-entry "quadruped-side" p dir) :limp_only true :up_body "torso")
          cortex (cortex-drop c p nil seconds "torso")
          sz (size p)]
      (when-let [result (check-export py dir [entry])]
        (let [{:strs [mujoco drop urdf]} (result "quadruped-side")]
          (is (nil? (get mujoco "error")))
          (is (= {} (get drop "warnings")) "MuJoCo warned during the drop")
          (check-urdf p urdf)
          (doseq [[who d] [["MuJoCo" drop] ["PyBullet" (get urdf "drop")]]]
            (check-limp-drop f sz who d cortex true true))
          (is (< (:rest-speed cortex) 0.1) (str "cortex still moving at " (:rest-speed cortex)))
          (is (= [:side :side] [(pose-of (:up cortex)) (pose-of (drop "up"))])
              (str "the torso's up at the end: cortex's " (:up cortex) ", MuJoCo's " (drop "up"))))))
    (skip "cortex.export-test/the-four-legged-creature-laid-on-its-side-lands-alike")))

(defn- hanging-angle
  "The angle a at which a beam of `m` kg, its centre `l` from a spring
  of stiffness `k`, hangs: k a = m g l cos a."
  [k m l]
  (loop [a 0.0 n 0]
    (let [a' (/ (* m 9.81 l (Math/cos a)) k)]
      (if (or (< (Math/abs (- a' a)) 1e-12) (> n 1000)) a' (recur a' (inc n))))))

(defn- spring-creature
  "cortex.joint-fixtures' two boxes at height 2 joined by `description`."
  [description turn masses]
  (jf/two-segments description turn masses 2))

(defn- cortex-hang
  "How far (radians) the lower box of `c` hangs below the joint's
  height after 5 s in cortex, and its speed then. Its body never
  sleeps: cortex's thresholds (0.8 m/s, 3 rad/s) would put the stiff
  beam, which swings slower, to sleep wherever it is two seconds in
  (0.0472 rad, where it hangs at 0.0490)."
  [c]
  (let [s (sim/simulation (body/body! c {:sleeping-thresholds [0 0]}) {:observe #{:segments}})]
    (try
      (let [{{{[_ y] :position v :velocity} "lower"} :segments} (last (repeatedly 300 #(sim/step! s)))]
        [(Math/asin (- 2.0 (double y))) (Math/sqrt (reduce + (map * v v)))])
      (finally (sim/destroy! s)))))

(def ^:private soft-spring
  "{:type :spring :stiffness 20 :damping 2 :twist 0.3 :limit-xz 0.5 :limit-xy 0.4}")

(deftest a-spring-joint-is-mujoco-s-joint-spring
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-spring" (make-array FileAttribute 0)))
          beams (vec (for [k [1000 100]
                           :let [d (str "{:type :spring :stiffness " k " :damping 20}")
                                 p (plan/plan (spring-creature d com.jme3.math.Quaternion/IDENTITY [0 5]))
                                 mj (str (io/file dir (str "beam-" k ".xml")))]]
                       (do (ex/write! p mj nil)
                           {:k k :d d :mjcf mj :text (slurp mj)})))
          turn (jf/turned 0.4 [1 1 0])
          soft (plan/plan (spring-creature soft-spring turn [1 1]))
          entry (dissoc (manifest-entry "soft-spring" soft dir) :mjx_seconds :mjcf_inscribed :held)
          result (check-export py dir (conj (for [{:keys [k mjcf]} beams]
                                              {:name (str "beam-" k) :mjcf mjcf :seconds seconds
                                               :limp_only true})
                                            entry))]
      (when result
        (doseq [{:keys [k d text]} beams
                :let [{{:strs [error warnings]} "mujoco" {:strs [heights rest_speed]} "drop"}
                      (result (str "beam-" k))
                      want (hanging-angle k 5.0 1.0)
                      mj (Math/asin (- 2.0 (double (peek heights))))]]
          (testing (str "the beam on a spring of " k " N m/rad")
            (is (nil? error))
            (is (empty? warnings))
            (is (= 3 (count (re-seq (re-pattern (str "stiffness=\"" (double k) "\" damping=\"20.0\""))
                                    text))))
            (is (< (Math/abs (- mj want)) (* 0.01 want)) (str "MuJoCo's beam hangs at " mj ", k a = m g l cos a at " want))
            (is (< (double rest_speed) 0.01) (str "MuJoCo's beam still moving at " rest_speed))
            (println (format "beam on a spring of %d N m/rad: hangs at %.4f rad in MuJoCo, %.4f by k a = m g l cos a"
                             k mj want))
            (let [[a v] (cortex-hang (spring-creature d com.jme3.math.Quaternion/IDENTITY [0 5]))]
              (println (format "  and at %.4f rad in cortex (%s), moving at %.4f m/s" a engine/name v))
              (is (< (Math/abs (- a mj)) (* 0.01 mj)) (str "cortex's beam hangs at " a ", MuJoCo's at " mj))
              (is (< v 0.01)))))
        (testing "a soft spring, limited, its empty turned"
          (check-bodies soft (get-in result ["soft-spring" "mujoco"]) (get-in result ["soft-spring" "bodies"]))
          (let [dofs (ex/joint-dofs soft)
                text (slurp (:mjcf entry))]
            (is (= 3 (count (re-seq #"stiffness=\"20.0\" damping=\"2.0\"" text))))
            (is (= 6 (count (get-in result ["soft-spring" "drives"]))))
            (doseq [{:strs [joint dof end angles]} (get-in result ["soft-spring" "drives"])
                    :let [[i want] (expected-angle (dofs joint) dof end)]]
              (is (< (Math/abs (- (double (nth angles i)) want)) 0.05)
                  (str dof " to its " end ": " (nth angles i) ", cortex's limit " want))))
          (check-urdf soft (get-in result ["soft-spring" "urdf"]))
          (is (str/includes? (slurp (:urdf entry)) "its springs are lost")))))
    (skip "cortex.export-test/a-spring-joint-is-mujoco-s-joint-spring")))

(deftest the-export-is-a-gymnasium-environment
  (if-let [py (python)]
    (let [dir (io/file (str (Files/createTempDirectory "cortex-gym" (make-array FileAttribute 0))))
          [_ p] (placed "quadruped")
          _ (ex/write! p (str (io/file dir "quadruped.xml")) nil)
          scene (io/file dir "scene.xml")
          _ (spit scene (str "<mujoco>\n  <include file=\"quadruped.xml\"/>\n  <worldbody>\n"
                             "    <geom name=\"floor\" type=\"plane\" size=\"0 0 1\"/>\n"
                             "  </worldbody>\n</mujoco>\n"))
          {:keys [exit out err]} (shell/sh py "scripts/export/gym_check.py" (str scene) "torso" "1000")]
      (if (= 3 exit)
        (println "SKIPPED cortex.export-test/the-export-is-a-gymnasium-environment:" (str/trim out))
        (let [{:strs [observations actions low high steps warnings]}
              ((requiring-resolve 'cortex.blender-test/read-json) out)
              jd (ex/joint-dofs p)
              ;; in the document's order: the plan's joints in turn
              dofs (for [{:keys [name]} (:joints p) d (:dofs (jd name))] d)
              ;; a servo's range; a ball's three servos, pi each way
              ranges (mapcat #(if (:ball %) (repeat 3 [(- Math/PI) Math/PI]) [(:range %)]) dofs)
              balls (count (filter :ball dofs))
              hinges (- (count dofs) balls)]
          (is (zero? exit) err)
          (println (format "the four-legged creature in Gymnasium's Ant-v5: %d observations, %d actions, %d steps, warnings %s"
                           observations actions steps (pr-str warnings)))
          (is (= (count ranges) actions) "an action per servo")
          ;; qpos less the root's x and y, and qvel: a free joint 7 and
          ;; 6, a hinge 1 and 1, a ball 4 and 3
          (is (= (+ (- (+ 7 hinges (* 4 balls)) 2) (+ 6 hinges (* 3 balls))) observations))
          (is (close? low (map first ranges) 1e-6))
          (is (close? high (map second ranges) 1e-6))
          (is (= 1000 steps))
          (is (= {} warnings)))))
    (skip "cortex.export-test/the-export-is-a-gymnasium-environment")))

(deftest a-scene-puts-the-creature-on-a-floor
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-scene" (make-array FileAttribute 0)))]
      (doseq [[f path] (assoc fixtures
                              "paddle" "test/fixtures/flat-strangers/flat-hexagon-paddle.blend"
                              "walker" "test/fixtures/flat-strangers/leaf-walker.blend")
              :when (not= f "humanoid")
              :let [c (util/load-blender-model path)
                    p (plan/plan c)
                    scene (str (io/file dir (str f "-scene.xml")))
                    written (ex/write! p (str (io/file dir (str f ".xml"))) nil {:scene true})
                    {:keys [exit out err]} (shell/sh py "scripts/export/scene_check.py" scene "3")
                    {:strs [error warnings floor gap heights rest_speed sim_warnings]}
                    (when (zero? exit) ((requiring-resolve 'cortex.blender-test/read-json) out))]]
        (testing f
          (is (zero? exit) err)
          (is (= scene (peek written)) "the scene is written last, beside the MJCF")
          (is (nil? error))
          (is (empty? warnings))
          (is (= {} sim_warnings))
          (is (< (Math/abs (double gap)) 1e-4) (str "the floor " gap " m from the creature"))
          (println (format "%s in its scene: the floor at %.4f m, %.2g m from the creature" f
                           (double floor) (double gap)))
          (when (stays-put f)
            (let [_ (.move c 0 (float (- (double floor))) 0)
                  ours (cortex-drop c p nil 3.0 nil)
                  sz (size p)]
              (doseq [[label i] [["after 1 s" 59] ["at the end" (dec (count heights))]]
                      :let [a (- (double (nth heights i)) (double floor))
                            b (double (nth (:heights ours) i))]]
                (println (format "  %s, limp, %s: centre of mass %.4f m above the floor in MuJoCo, %.4f in cortex (%s)"
                                 f label a b (name engine/name)))
                (is (< (Math/abs (- a b)) (* 0.05 sz))
                    (str label ": " a " m above the floor in MuJoCo, " b " in cortex")))
              (is (< (double rest_speed) 0.1) "MuJoCo's comes to rest")
              (is (< (double (:rest-speed ours)) 0.1) "cortex's comes to rest"))))))
    (skip "cortex.export-test/a-scene-puts-the-creature-on-a-floor")))

(def ^:private stranger-files
  "The strangers' creatures exported at every size they were saved at."
  (vec (for [n ["worm-eye" "hand" "humanoid"] k ["" "-0.01" "-100"]]
         (str n k))))

(deftest strangers-creatures-export-at-any-scale
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-strangers" (make-array FileAttribute 0)))
          plans (into {} (for [f (conj stranger-files "hand-b52")]
                           [f (plan/plan (util/load-blender-model
                                          (str "test/fixtures/strangers/" f ".blend")))]))
          mjx-hand "hand, cylinders as meshes"
          plans (assoc plans mjx-hand (ex/cylinders-as-meshes (plans "hand")))
          entries (for [[f p] plans
                        :let [file (str dir "/" (str/replace f #"[^a-z0-9-]" "_"))
                              mj (str file ".xml")
                              urdf (str file ".urdf")]]
                    (do (ex/write! p mj urdf)
                        (cond-> {:name f :mjcf mj :urdf urdf :compile_only true :base (urdf-base p)}
                          (= f mjx-hand) (assoc :mjx_seconds 1.0))))]
      (when-let [result (check-export py dir entries)]
        (is (= (set (keys plans)) (set (keys result))))
        (doseq [[f p] plans
                :let [{:strs [mujoco bodies urdf mjx held]} (result f)]]
          (testing f
            (check-bodies p mujoco bodies)
            (check-urdf p urdf)
            (when (= f mjx-hand)
              (is (not (re-find #"<geom [^>]*type=\"cylinder\"" (ex/mjcf p))))
              (check-mjx f (size p) mjx held))))))
    (skip "cortex.export-test/strangers-creatures-export-at-any-scale")))

(def ^:private hexagon
  "transforms.blend's lone hexagon, a flat segment: [creature plan], the
  plan of the hexagon alone, so that it is one tree for URDF."
  (delay (let [c (util/load-blender-model "test/fixtures/blend/b34/transforms.blend")
               p (update (plan/plan c) :segments (partial filterv #(= "ngon-hexagon" (:id %))))]
           [c p])))

(def ^:private hexagon-moments
  "The principal moments (jME's axes) of the hexagon's body, as cortex
  built it."
  (delay (let [[c] @hexagon
               _ (body/body! c)
               g (first (filter #(= "ngon-hexagon" (segment/segment-name %)) (segment/segments c)))]
           (mapv #(/ 1.0 (double %)) (engine/inverse-inertia
                                      (engine/rigid-body (.getControl ^Geometry g RigidBodyControl)))))))

(deftest a-flat-segment-is-written-as-a-plate
  (let [[_ p] @hexagon]
    (is (close? (get-in p [:segments 0 :inertia :moments]) @hexagon-moments 1e-6)
        "the plan keeps the moments the body is built with"))
  (let [[_ p] @hexagon
        polygon (map geo/z-up (get-in p [:segments 0 :shape :points]))
        [[_ {:keys [points thickness file]}] :as ms] (seq (geo/mesh-files p))]
    (is (= 1 (count ms)))
    (is (= geo/flat-thickness thickness 0.002))
    (testing "the prism is the polygon, moved half the thickness to each side"
      (is (= 12 (count points)))
      (is (= (set (for [q polygon dz [0.001 -0.001]] (mapv #(Math/round (* 1e6 (double %))) (update (vec q) 2 + dz))))
             (set (map (fn [q] (mapv #(Math/round (* 1e6 (double %))) q)) points))))
      (is (< (Math/abs (- (engine/hull-volume points) (* 1.5 (Math/sqrt 3.0) 0.002))) 1e-9)
          "the hexagon's area times 0.002"))
    (is (str/starts-with? ((ex/meshes p) file) "# flat segment ngon-hexagon's polygon as a prism 0.002 thick"))
    (doseq [doc [(ex/mjcf p) (ex/urdf p)]]
      (is (str/includes? doc "<!-- segment ngon-hexagon is flat: its polygon is written as a prism 0.002 thick"))))
  (testing "a small polygon's prism is a hundredth of its extent thick"
    (let [tiny {:creature "tiny.blend" :joints []
                :segments [{:id "leaf" :mass 1.0 :friction 0.5 :position [0.0 0.0 0.0]
                            :rotation [0 0 0 1] :inertia {:source :box}
                            :shape {:type :hull :points [[0 0 0] [0.01 0 0] [0 0 0.008] [0.01 0 0.008]]}}]}
          [[_ {:keys [points thickness]}]] (seq (geo/mesh-files tiny))]
      (is (= 1.0E-4 thickness))
      (is (< (Math/abs (- (engine/hull-volume points) (* 0.01 0.008 1e-4))) 1e-15))))
  (if-let [py (python)]
    (let [[_ p] @hexagon
          dir (str (Files/createTempDirectory "cortex-flat" (make-array FileAttribute 0)))
          mj (str dir "/hexagon.xml")
          urdf (str dir "/hexagon.urdf")
          _ (ex/write! p mj urdf)
          ;; what cortex's engine gives the plate: jME's axes, Z up's X, Z, Y
          [ix iy iz] @hexagon-moments
          {:strs [mujoco bodies urdf]} (get (check-export py dir [{:name "hexagon" :mjcf mj :urdf urdf
                                                                   :compile_only true
                                                                   :base (urdf-base p)}])
                                            "hexagon")]
      (is (nil? (get mujoco "error")))
      (is (empty? (get mujoco "warnings")))
      (is (close? (get-in bodies ["ngon-hexagon" "mass"]) 1.0 1e-9))
      (is (close? (get-in bodies ["ngon-hexagon" "inertia"]) [[ix 0 0] [0 iz 0] [0 0 iy]] 1e-6)
          "MuJoCo's inertia is the plate's cortex built")
      (check-urdf p urdf))
    (skip "cortex.export-test/a-flat-segment-is-written-as-a-plate, in MuJoCo")))

(deftest a-plan-written-without-moments-exports-as-built
  (doseq [f ["fish" "flat-hexagon-paddle"]
          :let [c (util/load-blender-model (str "test/fixtures/flat-strangers/" f ".blend"))
                p (plan/plan c)
                by-hand (update p :segments
                                (partial mapv #(cond-> % (= :box (get-in % [:inertia :source]))
                                                 (update :inertia dissoc :moments))))
                _ (body/body! c)
                mine (ex/muscles by-hand)]]
    (testing f
      (is (some #(= :box (get-in % [:inertia :source])) (:segments p))
          "a segment massed by Bullet's approximation")
      (doseq [[n {:keys [strength kp kd]}] (muscle/muscles c)]
        (is (close? (:strength (mine n)) strength 1e-4) n)
        (is (close? (:kp (mine n)) kp 1e-4) (str n " stiffness"))
        (is (close? (:kd (mine n)) kd 1e-4) (str n " damping")))
      (is (= (ex/mjcf p) (ex/mjcf by-hand)))
      (is (= (ex/urdf p) (ex/urdf by-hand))))))

(deftest flat-strangers-drop-as-in-mujoco
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-flat" (make-array FileAttribute 0)))
          runs (vec (for [[f mujoco-rests?] [["leaf-walker" true] ["flat-hexagon-paddle" false]]]
                      (let [c (util/load-blender-model (str "test/fixtures/flat-strangers/" f ".blend"))
                            _ (drops/lift! c)
                            p (plan/plan c)
                            mj (str dir "/" f ".xml")]
                        (ex/write! p mj nil)
                        {:f f :plan p :mujoco-rests? mujoco-rests?
                         :entry {:name f :mjcf mj :limp_only true :seconds seconds}
                         ;; without its body yet: simulated as cortex.sim chooses
                         :cortex (cortex-drop c p nil)})))]
      (when-let [result (check-export py dir (map :entry runs))]
        (doseq [{:keys [f plan cortex mujoco-rests?]} runs
                :let [{:strs [mujoco drop]} (result f)
                      sz (size plan)]]
          (testing f
            (is (= 10.0 (:scale cortex)) "under 1 across: simulated ten times larger")
            (is (nil? (get mujoco "error")))
            (is (empty? (get mujoco "warnings")))
            (is (= {} (get drop "warnings")) "MuJoCo warned during the drop")
            (doseq [[label i] [["after 1 s" 59] ["at the end" (dec (count (:heights cortex)))]]
                    :let [a (double (nth (get drop "heights") i)) b (double (nth (:heights cortex) i))]]
              (println (format "%s, limp, %s, %s: MuJoCo %.4f m, cortex %.4f m (size %.3f)"
                               f (name engine/name) label a b sz))
              (is (< (Math/abs (- a b)) (* 0.05 sz)) label))
            (when mujoco-rests?
              (is (< (double (get drop "rest_speed")) 0.1) "MuJoCo's comes to rest"))
            (is (< (double (:rest-speed cortex)) 0.1) "cortex's comes to rest")))))
    (skip "cortex.export-test/flat-strangers-drop-as-in-mujoco")))

(defn- fixture-files
  "Every .blend file under test/fixtures, sorted, and then the shared
  corpus's (cortex.blender-test/corpus-files; none, with a message,
  where it is missing)."
  []
  (concat (sort (for [^java.io.File f (file-seq (io/file "test/fixtures"))
                      :let [p (str f)]
                      :when (str/ends-with? p ".blend")]
                  p))
          (map str ((requiring-resolve 'cortex.blender-test/corpus-files)))))

(defn- written
  "Fixture file `f` planned and written into `dir` as `n`: {:plan :entry}
  (the entry compile-only), with :urdf-refused e (or :urdf-error e)
  where the plan is written as MJCF alone; or {:refused e} for what
  cortex refuses to plan or write, or {:error e}."
  [f n dir]
  (let [attempt (fn [g] (try {:ok (g)}
                             (catch clojure.lang.ExceptionInfo e {:refused e})
                             (catch Exception e {:error e})))
        {p :ok :as planned} (attempt #(plan/plan (util/load-blender-model f)))
        mj (str (io/file dir (str n ".xml")))]
    (if-not p
      planned
      (let [{both :ok :as urdf} (attempt #(manifest-entry n p dir))
            {alone :ok :as mjcf} (when-not both (attempt #(do (ex/write! p mj nil)
                                                              {:name n :mjcf mj :urdf nil})))]
        (if-let [e (or both alone)]
          (merge {:plan p :entry (-> e (dissoc :mjx_seconds :mjcf_inscribed :held)
                                     (assoc :compile_only true))}
                 (set/rename-keys (select-keys urdf [:refused :error])
                                  {:refused :urdf-refused :error :urdf-error}))
          mjcf)))))

(defn- moving [plan]
  (update plan :segments (fn [ss] (filterv #(pos? (double (:mass %))) ss))))

(deftest every-fixture-that-plans-exports
  (if-let [py (python)]
    (let [dir (str (Files/createTempDirectory "cortex-every" (make-array FileAttribute 0)))
          runs (vec (for [[i f] (map-indexed vector (fixture-files))]
                      (assoc (written f (str "f" i) dir) :f f)))
          out (filter :entry runs)]
      (println (format "every fixture: %d files, %d exported (%d as URDF too), %d refused"
                       (count runs) (count out) (count (filter (comp :urdf :entry) out))
                       (count (filter :refused runs))))
      (is (<= 60 (count out)) "fewer than 60 fixtures exported")
      (doseq [{:keys [f error urdf-error refused urdf-refused]} runs]
        (testing f
          (is (nil? error) (str "not an ex-info: " error))
          (is (nil? urdf-error) (str "not an ex-info: " urdf-error))
          (doseq [^Exception e [refused urdf-refused] :when e]
            (is (or (str/includes? (ex-message e) f) (re-find #"\"[^\"]+\"" (ex-message e)))
                (ex-message e)))))
      (when-let [result (check-export py dir (map :entry out))]
        (doseq [{:keys [f plan entry]} out
                :let [{:strs [mujoco bodies urdf]} (result (:name entry))]]
          (testing f
            (is (nil? (get mujoco "error")))
            (is (empty? (get mujoco "warnings")))
            (is (= (set (map :id (:segments plan))) (set (keys bodies))))
            (doseq [{:keys [id mass]} (:segments plan)]
              (is (close? (get-in bodies [id "mass"]) mass 1e-6) id))
            (when-not (model/physics-tab? plan)
              (check-bodies (moving plan) mujoco (select-keys bodies (map :id (:segments (moving plan))))))
            (when (:urdf entry)
              (check-urdf (moving plan) urdf))))))
    (skip "cortex.export-test/every-fixture-that-plans-exports")))

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
