;; Generated from org/main.org by lein tangle: edit the chapter, not this file.
(ns cortex.main-test
  (:require [clojure.string :as str]
            [clojure.test :refer [deftest is testing]]
            [cortex.body :as body]
            [cortex.demo :as demo]
            [cortex.main :as main]
            [cortex.render :as render]
            [cortex.blender]
            [cortex.sim :as sim]
            [cortex.util :as util])
  (:import (com.jme3.bullet.control RigidBodyControl)
           (com.jme3.math Vector3f)
           (com.jme3.scene Geometry)
           (com.jme3.renderer Camera)
           (java.awt.image BufferedImage)
           (javax.imageio ImageIO)))

(set! *warn-on-reflection* true)

(deftest reading-the-command-line
  (testing "defaults: a window when there is a display, offscreen when not"
    (is (= {:action :window :creature "worm" :frames 240 :out "out/worm"
            :record? false :fallback? true :size [640 480]}
           (main/plan [] true)))
    (is (= {:action :offscreen :creature "worm" :frames 240 :out "out/worm"
            :record? true :fallback? true :size [640 480]}
           (main/plan [] false))))
  (testing "options"
    (is (= {:action :offscreen :creature "hand" :frames 90 :out "x" :record? true
            :fallback? true :size [320 240]}
           (main/plan ["--creature" "hand" "-s" "1.5" "-o" "x" "-r" "320x240" "--headless"] true)))
    (is (:record? (main/plan ["--out" "y"] true)) "a window records when given a folder")
    (is (false? (:fallback? (main/plan ["--window"] true)))
        "an explicit --window fails rather than falling back"))
  (testing "help"
    (is (= :help (:action (main/plan ["--help"] false))))
    (is (re-find #"--creature" (:message (main/plan ["-h"] false)))))
  (testing "bad input is a message"
    (doseq [[args pattern] [[["--creature" "cat"] #"worm, hand|hand, worm"]
                            [["-r" "640"] #"640x480"]
                            [["-r" "641x480"] #"even"]
                            [["-s" "0"] #"more than 0"]
                            [["-s" "soon"] #"seconds"]
                            [["--bogus"] #"bogus"]
                            [["--headless" "--window"] #"contradict"]]]
      (let [p (main/plan args true)]
        (is (= :error (:action p)) (pr-str args))
        (is (re-find pattern (:message p)) (pr-str args))))
    (is (re-find #"no display" (:message (main/plan ["--window"] false))))))


(deftest creatures-from-files
  (testing "a .blend file on the command line"
    (is (= {:action :offscreen :creature "quadruped" :file "test/fixtures/designer/quadruped.blend"
            :frames 120 :out "out/quadruped" :record? true :fallback? true :size [640 480]}
           (main/plan ["test/fixtures/designer/quadruped.blend" "-s" "2"] false)))
    (is (= {:action :report :file "q.blend"} (main/plan ["q.blend" "--report"] false)))
    (is (re-find #"needs a FILE" (:message (main/plan ["--report"] false))))
    (is (= {:action :export :file "q.blend" :mjcf "q.xml" :urdf nil}
           (main/plan ["q.blend" "--mjcf" "q.xml"] false)))
    (is (= {:action :export :file "q.blend" :mjcf "q.xml" :urdf "q.urdf" :cone-strength :inscribed}
           (main/plan ["q.blend" "--mjcf" "q.xml" "--urdf" "q.urdf" "--cone-strength" "inscribed"] false)))
    (is (re-find #"per-axis or inscribed"
                 (:message (main/plan ["q.blend" "--mjcf" "q.xml" "--cone-strength" "equal"] false))))
    (is (re-find #"goes with --mjcf"
                 (:message (main/plan ["q.blend" "--urdf" "q.urdf" "--cone-strength" "inscribed"] false))))
    (is (= {:action :export :file "q.blend" :mjcf "q.xml" :urdf nil :friction-cone :elliptic}
           (main/plan ["q.blend" "--mjcf" "q.xml" "--friction-cone" "elliptic"] false)))
    (is (re-find #"pyramidal or elliptic"
                 (:message (main/plan ["q.blend" "--mjcf" "q.xml" "--friction-cone" "round"] false))))
    (is (re-find #"--friction-cone goes with --mjcf"
                 (:message (main/plan ["q.blend" "--urdf" "q.urdf" "--friction-cone" "elliptic"] false))))
    (is (re-find #"one creature file at a time" (:message (main/plan ["a.blend" "b.blend"] false))))
    (is (= [10.0 :auto nil] (map #(:scale (main/plan ["q.blend" "--scale" %] false)) ["10" "auto" "0"])))
    (is (re-find #"--scale -1\": must be auto or a positive number"
                 (:message (main/plan ["q.blend" "--scale" "-1"] false))))
    (is (re-find #"--scale goes with showing a creature"
                 (:message (main/plan ["q.blend" "--report" "--scale" "10"] false)))))
  (testing "the report as tables"
    (let [c (body/body! (util/load-blender-model "test/fixtures/designer/quadruped.blend"))
          text (main/report-text (body/report c))
          lines (clojure.string/split-lines text)]
      (is (re-find #"14 segments, 13 joints \(tolerance 0\.050\)" text))
      (is (some #(re-matches #"torso\s+4\.000\s+box\s+0\.8000\s*" %) lines))
      (is (some #(re-matches #"knee-front-r\s+hinge\s+HingeJoint\s+upper-leg-front-r\s+lower-leg-front-r\s+\[0\.700 -0\.300 0\.515\]\s+\[0\.015 0\.015\].*" %) lines))
      (is (re-find #"no warnings" text))))
  (testing "run offscreen: frames, the report, how it held and settled"
    (let [out (str (System/getProperty "java.io.tmpdir") "/cortex-main-" (System/nanoTime))
          printed (with-out-str
                    (#'main/show-offscreen! (assoc (main/plan ["test/fixtures/designer/quadruped.blend"
                                                               "-s" "0.5" "-o" out "-r" "160x120"] false)
                                                   :record? true)))]
      (is (re-find (re-pattern (str "hip-front-r\\s+cone\\s+"
                                    (.getSimpleName ^Class cortex.engine/six-dof-class)))
                   printed))
      (is (re-find #"largest joint gap 0\.0[0-9]+; (still moving after|at rest from) " printed))
      (is (= 30 (count (render/frames-in out)))))))

(deftest unknown-creatures
  (is (thrown-with-msg? clojure.lang.ExceptionInfo #"no creature called \"cat\""
                        (main/named-creature "cat"))))

(defn- rgb [^BufferedImage image x y]
  (let [p (.getRGB image (int x) (int y))]
    [(bit-and 0xff (bit-shift-right p 16)) (bit-and 0xff (bit-shift-right p 8)) (bit-and 0xff p)]))

(defn- copy-image ^BufferedImage [^BufferedImage image]
  (doto (BufferedImage. (.getWidth image) (.getHeight image) BufferedImage/TYPE_INT_RGB)
    (.setData (.getData image))))

(defn- patch
  "The colours of the 7x7 pixels around (x, y)."
  [image [x y]]
  (for [dx (range -3 4) dy (range -3 4)] (rgb image (+ x dx) (+ y dy))))

(defn- scenery?
  "Whether a colour is the blue sky's or the floor's, lit or in shadow
  (a grey with a little green: its channels within 45 of each other);
  the worm is a strong green."
  [[r g b]]
  (or (and (> b (+ r 40)) (> b g))
      (< (- (max r g b) (min r g b)) 45)))

(defn- mostly-creature?
  "Whether at least 60% of the pixels around `at` are neither sky nor
  floor: a worm segment seen edge-on at rest is a few pixels thick,
  and the hinge at the worm's middle has a sliver of gap."
  [image at]
  (let [colours (patch image at)]
    (>= (count (remove scenery? colours)) (* 0.6 (count colours)))))

(defn- on-screen
  "Where the centre of `spatial`'s bounds is on the picture taken by
  `cam`, in pixels from the top left."
  [^Camera cam spatial]
  (let [s (.getScreenCoordinates cam (.getCenter (.getWorldBound spatial)))]
    [(Math/round (.x s)) (- (.getHeight cam) 1 (Math/round (.y s)))]))

(deftest the-worm-is-seen-falling
  (let [worm (main/named-creature "worm")
        [w _] (main/demo-world worm)
        keep #{1 30 80}
        seen (atom {})
        start (System/nanoTime)]
    (render/grab-frames!
     w (fn [image]
         (let [n (inc (count (:all @seen)))
               cam (.getCamera w)
               at (on-screen cam worm)]
           (swap! seen update :all (fnil conj []) at)
           (when (keep n)
             (swap! seen assoc n {:image (copy-image image) :at at
                                  :segments (mapv #(on-screen cam %) (body/segments worm))})))))
    (render/run-offscreen! w 80 {:size [320 240]})
    (println (format "drew 80 frames of the worm offscreen in %.2f s"
                     (/ (- (System/nanoTime) start) 1e9)))
    (doseq [n (sort keep)
            :let [{:keys [image at segments]} (get @seen n)
                  [x y] at]]
      (testing (str "frame " n ": the worm is on the picture where the camera sees it " at)
        (is (< 3 x 316))
        (is (< 3 y 236))
        (is (mostly-creature? image at)
            (str "colours around the worm: " (vec (distinct (patch image at)))))
        (is (= 2 (count segments)))
        (doseq [s segments]
          (is (mostly-creature? image s) (str "and around its segment at " s)))))
    (testing "the picture is not blank"
      (let [image (:image (get @seen 80))]
        (is (< 10 (count (distinct (for [x (range 0 320 4) y (range 0 240 4)] (rgb image x y))))))))
    (testing "the worm moves: down the picture, and the pictures differ"
      (let [[_ y1] (:at (get @seen 1))
            [_ y80] (:at (get @seen 80))]
        (is (> y80 (+ y1 20))))
      (is (not= (vec (.getRGB ^BufferedImage (:image (get @seen 1)) 0 0 320 240 nil 0 320))
                (vec (.getRGB ^BufferedImage (:image (get @seen 80)) 0 0 320 240 nil 0 320)))))))

(defn- printing
  "[value printed]: what `f` returns and what it prints."
  [f]
  (let [out (java.io.StringWriter.)]
    [(binding [*out* out] (f)) (str out)]))

(deftest a-small-creature-from-a-file-is-shown-larger
  (let [f "test/fixtures/strangers/worm-eye-0.01.blend"
        twin (main/report-text (body/report (body/body! (util/load-blender-model f))))
        [[w seen c] printed] (printing #(#'main/planned-world (main/plan [f "-s" "3" "-r" "160x120"] false)))
        [[_ _ at-size]] (printing #(#'main/planned-world (main/plan [f "--scale" "1"] false)))]
    (is (= [100.0 1.0] [(sim/built-scale c) (sim/built-scale at-size)]) "--scale 1: at its size")
    ;; hull volumes aside: native Bullet builds a hull a little
    ;; differently at each scale (the body chapter's strangers)
    (is (= (str/replace (str twin "\n") #"hull\s+\S+" "hull") (str/replace printed #"hull\s+\S+" "hull"))
        "its report, at its size")
    (render/run-offscreen! w 180 {:size [160 120]})
    (let [fastest (apply max (for [g (body/segments c)
                                   :let [^RigidBodyControl rb (.getControl ^Geometry g RigidBodyControl)]
                                   :when rb]
                               (/ (.length (.getLinearVelocity rb)) 100.0)))]
      (is (< fastest 0.001) (str "still moving at " fastest " m/s")))
    (is (re-find #"at rest from" (demo/watched @seen)))))

(deftest lein-run-with-eyes
  (let [plan (main/plan ["--eyes" "-s" "0.2" "-r" "160x120"] false)
        out (str (System/getProperty "java.io.tmpdir") "/cortex-eyes-" (System/nanoTime))]
    (is (= "worm-eyes" (:creature plan)))
    (is (:eyes? plan))
    (is (= "q" (:creature (main/plan ["q.blend" "--eyes"] false))))
    (with-out-str (#'main/show-offscreen! (assoc plan :out out)))
    (let [frames (render/frames-in out)
          ^BufferedImage last-frame (ImageIO/read ^java.io.File (last frames))]
      (is (= 12 (count frames)))
      (is (= 160 (.getWidth last-frame)))
      (is (< 120 (.getHeight last-frame)) "the eyes' strip is under the world"))))
