;; Generated from org/sim.org by lein tangle: edit the chapter, not this file.
(ns cortex.pictures
  "Pictures for the book, drawn from simulations with java.awt.
  Entry point: `-main` writes org/images/proprioception.png."
  (:require [cortex.body :as body]
            [cortex.proprioception :as p]
            [cortex.sim :as sim]
            [cortex.blender]
            [cortex.util :as util])
  (:import (java.awt BasicStroke Color Font Graphics2D RenderingHints)
           (java.awt.geom AffineTransform Arc2D$Double Line2D$Double Rectangle2D$Double)
           (java.awt.image BufferedImage)
           (java.io File)
           (javax.imageio ImageIO)))

(set! *warn-on-reflection* true)

(defn bent-worm
  "The worm after 2 s holding its hinge at `target`, gravity off: its
  segments' :segments states and the angle proprioception reads."
  [target]
  (let [s (sim/simulation (util/load-blender-model "Models/test-creature/worm.blend")
                          {:gravity [0 0 0]})
        obs (last (for [_ (range 120)] (sim/step! s {"worm-joint" {:target target}})))]
    {:segments (:segments obs)
     :angle (get-in obs [:joints "worm-joint" :angle])
     :pivot (let [^com.jme3.bullet.joints.PhysicsJoint j
                  (:physics-joint (first (body/joint-records (:creature s))))
                  v (body/pivot-in-world (.getBodyA j) (first (cortex.engine/pivots j)))]
              [(.x v) (.y v) (.z v)])}))

(defn- side-angle
  "The angle, in the X-Z plane of Blender's axes, by which the rotation
  `q` (jME's axes) turns Blender's +X."
  ^double [q]
  (let [[x _ z] (p/jme->blender (p/rotate q [1 0 0]))]
    (Math/atan2 z x)))

(defn draw-proprioception
  "The proprioception picture, as a BufferedImage."
  ^BufferedImage []
  (let [{:keys [segments angle pivot]} (bent-worm 0.5)
        w 900 h 420 scale 150.0
        [px _ pz] (p/jme->blender pivot)
        to-screen (fn [[x _ z]] [(+ (/ w 2) (* scale (- x px))) (- 250 (* scale (- z pz)))])
        img (BufferedImage. w h BufferedImage/TYPE_INT_RGB)
        g ^Graphics2D (.createGraphics img)]
    (doto g
      (.setRenderingHint RenderingHints/KEY_ANTIALIASING RenderingHints/VALUE_ANTIALIAS_ON)
      (.setColor Color/WHITE) (.fillRect 0 0 w h)
      (.setFont (Font. Font/SANS_SERIF Font/PLAIN 18)))
    (doseq [[n colour label] [["worm-1" (Color. 140 190 90) "A: worm-1 (first)"]
                              ["worm-2" (Color. 115 165 75) "B: worm-2 (second)"]]
            :let [{:keys [position rotation]} (segments n)
                  [sx sy] (to-screen (p/jme->blender position))
                  a (side-angle rotation)
                  old (.getTransform g)]]
      (.translate g (double sx) (double sy))
      (.rotate g (- a))
      (.setColor g colour)
      (.fill g (Rectangle2D$Double. (- scale) (* -0.3 scale) (* 2 scale) (* 0.6 scale)))
      (.setColor g Color/DARK_GRAY)
      (.draw g (Rectangle2D$Double. (- scale) (* -0.3 scale) (* 2 scale) (* 0.6 scale)))
      (.setTransform g old)
      (.setColor g Color/BLACK)
      (.drawString g ^String label (float (- sx 80)) (float (+ sy 70))))
    (let [[cx cy] (to-screen (p/jme->blender pivot))
          a-dir (side-angle (:rotation (segments "worm-1")))
          b-dir (side-angle (:rotation (segments "worm-2")))
          r 110.0]
      ;; A's axis line carried on past the joint, and B's
      (.setStroke g (BasicStroke. 2 BasicStroke/CAP_ROUND BasicStroke/JOIN_ROUND 1
                                  (float-array [8 6]) 0))
      (.setColor g Color/GRAY)
      (.draw g (Line2D$Double. cx cy (+ cx (* 1.4 r (Math/cos a-dir))) (- cy (* 1.4 r (Math/sin a-dir)))))
      (.setStroke g (BasicStroke. 3))
      (.setColor g (Color. 200 40 40))
      (.draw g (Arc2D$Double. (- cx r) (- cy r) (* 2 r) (* 2 r)
                              (Math/toDegrees a-dir) (Math/toDegrees (- b-dir a-dir)) Arc2D$Double/OPEN))
      ;; the axis, Blender's +Y, points into the picture
      (.setColor g Color/BLACK)
      (.drawOval g (int (- cx 12)) (int (- cy 12)) 24 24)
      (.drawLine g (int (- cx 8)) (int (- cy 8)) (int (+ cx 8)) (int (+ cy 8)))
      (.drawLine g (int (- cx 8)) (int (+ cy 8)) (int (+ cx 8)) (int (- cy 8)))
      (.setColor g (Color. 200 40 40))
      (.drawString g (format "angle %+.3f rad" (double angle))
                   (float (+ cx 20)) (float (+ cy 150)))
      (.setColor g Color/BLACK)
      (.drawString g "hinge axis: Blender +Y, into the picture" (float 20) (float 30))
      (.drawString g "positive = right-hand rule about the axis: B's far end turns from +X to -Z"
                   (float 20) (float 56))
      (.drawString g "X" (float (- w 40)) (float 395))
      (.drawLine g (- w 110) 390 (- w 50) 390)
      (.drawString g "Z" (float 28) (float 330))
      (.drawLine g 30 400 30 340))
    (.dispose g)
    img))

(defn -main
  "Write the book's pictures to org/images/."
  [& _]
  (let [f (File. "org/images/proprioception.png")]
    (.mkdirs (.getParentFile f))
    (ImageIO/write (draw-proprioception) "png" f)
    (println "wrote" (str f))
    (shutdown-agents)))
