;; Generated from org/export.org by lein tangle: edit the chapter, not this file.
(ns cortex.export-picture
  "doc/export-side-by-side.png: one creature dropped in cortex and,
  exported, in MuJoCo (scripts/export/side_by_side.py), side by side;
  see org/export.org, \"One creature in both\".

  bin/lein run -m cortex.export-picture [OUT.png [SECONDS]], with
  CORTEX_PYTHON a Python with MuJoCo (or target/python)."
  (:require [clojure.java.io :as io]
            [clojure.java.shell :as shell]
            [cortex.blender :as blender]
            [cortex.body :as body]
            [cortex.compare :as compare]
            [cortex.demo :as demo]
            [cortex.engine :as engine]
            [cortex.export :as export]
            [cortex.export.geometry :as geo]
            [cortex.plan :as plan]
            [cortex.render :as render]
            [cortex.sim :as sim])
  (:import (com.jme3.app SimpleApplication)
           (com.jme3.light Light)
           (com.jme3.material MatParam Material)
           (com.jme3.math ColorRGBA Vector3f)
           (com.jme3.scene Geometry)
           (java.awt Color Font RenderingHints)
           (java.awt.image BufferedImage)
           (javax.imageio ImageIO)))

(set! *warn-on-reflection* true)

(def creature-file "test/fixtures/designer/quadruped.blend")

(def ^:private size [640 480])

(def ^:private ground [0.55 0.6 0.5])

(defn- colour-of
  "The colour segment `g` is drawn in, [r g b] from 0 to 1."
  [^Geometry g]
  (let [m (.getMaterial g)
        ^MatParam p (or (.getParam m "Diffuse") (.getParam m "Color"))
        ^ColorRGBA c (if p (.getValue p) ColorRGBA/Gray)]
    [(.r c) (.g c) (.b c)]))

(defn- v3 [^Vector3f v] [(.x v) (.y v) (.z v)])

(defn- stage!
  "Light world `w` as lein run's stage is lit (in place of the
  simulation's world's lights), its floor in a lit colour, and frame the
  box from `lo` to `hi`. Returns the camera as Z-up data."
  [^SimpleApplication w lo hi]
  (let [root (.getRootNode w)
        [r g b] ground
        colour (ColorRGBA. (float r) (float g) (float b) 1)]
    (doseq [l (vec (.getLocalLightList root))] (.removeLight root ^Light l))
    (demo/light! w)
    (.setMaterial ^Geometry (.getChild root "floor")
                  (doto (Material. (.getAssetManager w) "Common/MatDefs/Light/Lighting.j3md")
                    (.setBoolean "UseMaterialColors" true)
                    (.setColor "Diffuse" colour)
                    (.setColor "Ambient" colour)))
    (demo/frame! w lo hi)
    (let [cam (.getCamera w)]
      {:pos (geo/z-up (v3 (.getLocation cam))) :forward (geo/z-up (v3 (.getDirection cam)))
       :up (geo/z-up (v3 (.getUp cam))) :fovy 45.0})))

(defn cortex-half
  "The creature in `file`, planned, built and dropped for `seconds` in
  cortex, drawn offscreen: {:plan (before the drop) :floor (its top)
  :camera :picture (the last frame) :colours (by segment) :height (the
  centre of mass above the floor at the end)}."
  [file seconds]
  (let [c (blender/load-blender-model file)
        p (plan/plan c)
        _ (body/body! c)
        [lo hi] (demo/bounds c)
        drop (max 0.05 (* 0.1 (- (double (second hi)) (double (second lo)))))
        top (- (double (second lo)) drop)
        s (sim/simulation c {:floor {:height top :friction 1.0} :observe #{:segments}})
        camera (promise)
        picture (atom nil)
        w (sim/world s (constantly nil) #(deliver camera (stage! % (assoc lo 1 top) hi)))]
    (try
      (render/grab-frames! w (fn [^BufferedImage image]
                               (reset! picture (doto (BufferedImage. (.getWidth image) (.getHeight image)
                                                                     BufferedImage/TYPE_INT_RGB)
                                                 (.setData (.getData image))))))
      (render/run-offscreen! w (Math/round (* 60 (double seconds))) {:size size})
      (let [mass (into {} (map (juxt :id :mass)) (:segments p))
            {:keys [segments]} (sim/observe s #{:segments})]
        {:plan p :floor top :camera @camera :picture @picture
         :colours (into {} (for [^Geometry g (body/segments c)] [(body/segment-name g) (colour-of g)]))
         :height (- (/ (reduce + (for [[n {[_ y] :position}] segments] (* (double (mass n)) (double y))))
                       (reduce + (map double (vals mass))))
                    top)})
      (finally (sim/destroy! s)))))

(defn- labelled
  "`left` and `right` side by side, each under its label."
  ^BufferedImage [^BufferedImage left ^BufferedImage right [^String left-label ^String right-label]]
  (let [w (.getWidth left) gap 8 band 40
        out (BufferedImage. (+ w gap (.getWidth right)) (+ band (.getHeight left))
                            BufferedImage/TYPE_INT_RGB)
        g (.createGraphics out)]
    (.setRenderingHint g RenderingHints/KEY_TEXT_ANTIALIASING RenderingHints/VALUE_TEXT_ANTIALIAS_ON)
    (.setColor g Color/WHITE)
    (.fillRect g 0 0 (.getWidth out) (.getHeight out))
    (.drawImage g left 0 band nil)
    (.drawImage g right (int (+ w gap)) (int band) nil)
    (.setColor g Color/BLACK)
    (.setFont g (Font. Font/SANS_SERIF Font/BOLD 18))
    (let [fm (.getFontMetrics g)]
      (doseq [[^String label x0 iw] [[left-label 0 w] [right-label (+ w gap) (.getWidth right)]]]
        (.drawString g label (int (+ x0 (quot (- iw (.stringWidth fm label)) 2))) (int 27))))
    (.dispose g)
    out))

(defn -main
  "Write the picture to `target` (default doc/export-side-by-side.png),
  `seconds` (default 1) after the drop; the pieces go to
  out/side-by-side."
  [& [target seconds]]
  (let [target (or target "doc/export-side-by-side.png")
        seconds (Double/parseDouble (or seconds "1"))
        py (first (filter #(and % (.exists (io/file ^String %)))
                          [(System/getenv "CORTEX_PYTHON") "target/python/bin/python"]))
        _ (when-not py
            (binding [*out* *err*]
              (println "cortex.export-picture: no Python with MuJoCo: set CORTEX_PYTHON (see org/export.org)"))
            (System/exit 2))
        dir (doto (io/file "out/side-by-side") (.mkdirs))
        {:keys [plan floor camera picture colours height]} (cortex-half creature-file seconds)
        mjcf (str (io/file dir "quadruped.xml"))
        scene (str (io/file dir "scene.json"))
        mujoco-png (io/file dir "mujoco.png")
        when-label (format "%s s after the drop" (if (== seconds (Math/rint seconds))
                                                   (str (long seconds)) (str seconds)))]
    (export/write! plan mjcf nil)
    (spit scene (compare/json {:mjcf mjcf :floor floor :seconds seconds
                               :width (first size) :height (second size) :camera camera
                               :sky [(.r demo/sky) (.g demo/sky) (.b demo/sky)] :ground ground
                               :colours colours}))
    (ImageIO/write ^BufferedImage picture "png" (io/file dir "cortex.png"))
    (println (format "cortex (%s): centre of mass %.3f m above the floor after %s s"
                     engine/label (double height) seconds))
    (let [{:keys [exit out err]} (shell/sh py "scripts/export/side_by_side.py" scene (str mujoco-png))
          version (second (re-find #"MuJoCo (\S+):" out))]
      (print out)
      (when-not (zero? exit)
        (binding [*out* *err*] (println "cortex.export-picture:" err))
        (System/exit 1))
      (ImageIO/write (labelled picture (ImageIO/read mujoco-png)
                               [(str "cortex (" engine/label "), " when-label)
                                (str "MuJoCo " version ", the exported MJCF, " when-label)])
                     "png" (doto (io/file target) (io/make-parents)))
      (println "wrote" target)
      (shutdown-agents))))
