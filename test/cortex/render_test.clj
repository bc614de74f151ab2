;; Generated from org/render.org by lein tangle: edit the chapter, not this file.
(ns cortex.render-test
  (:require [clojure.java.io :as io]
            [clojure.test :refer [deftest is testing]]
            [cortex.render :as render]
            [cortex.util :as util]
            [cortex.world :as world])
  (:import (com.jme3.math ColorRGBA Vector3f)
           (java.awt.image BufferedImage)
           (java.nio ByteBuffer)
           (java.nio.file Files)
           (java.nio.file.attribute FileAttribute)
           (javax.imageio ImageIO)))

(set! *warn-on-reflection* true)

(defn- temp-dir []
  (str (Files/createTempDirectory "cortex-render" (into-array FileAttribute []))))

(defn- rgb [^BufferedImage image x y]
  (let [p (.getRGB image (int x) (int y))]
    [(bit-and 0xff (bit-shift-right p 16)) (bit-and 0xff (bit-shift-right p 8)) (bit-and 0xff p)]))

(defn- live-threads [] (set (filter #(.isAlive ^Thread %) (keys (Thread/getAllStackTraces)))))

(deftest display-names
  (is (= {:host nil :number 0} (render/parse-display ":0")))
  (is (= {:host nil :number 1} (render/parse-display ":1.0")))
  (is (= {:host nil :number 2} (render/parse-display "unix:2")))
  (is (= {:host "example" :number 10} (render/parse-display "example:10.0")))
  (is (nil? (render/parse-display "")))
  (is (nil? (render/parse-display nil)))
  (is (false? (render/display? nil)))
  (is (false? (render/display? ":4242")) "a display nobody serves is no display"))

(deftest frame-sizes
  (is (= [640 480] (render/parse-size "640x480")))
  (is (= [320 240] (render/parse-size " 320X240 ")))
  (doseq [bad ["640" "640x" "axb" "0x480" "641x480" "99999x480" "640x480x3" nil]]
    (is (thrown-with-msg? clojure.lang.ExceptionInfo #"frame size" (render/parse-size bad))
        (pr-str bad))))

(deftest bottom-up-bgra-rows-become-a-picture
  (let [;; 2x2, bottom row first: blue, green / red, white
        bytes (byte-array (map unchecked-byte [255 0 0 255, 0 255 0 255,
                                               0 0 255 255, 255 255 255 255]))
        image (render/bgra->image! (ByteBuffer/wrap bytes)
                                   (BufferedImage. 2 2 BufferedImage/TYPE_INT_RGB))]
    (is (= [[255 0 0] [255 255 255] [0 0 255] [0 255 0]]
           [(rgb image 0 0) (rgb image 1 0) (rgb image 0 1) (rgb image 1 1)]))))

(deftest ffmpeg-arguments
  (let [args (render/gif-args "out/x" 60 "out/x/x.gif" {:gif-fps 12 :width 200})]
    (is (= "out/x/frame-%06d.png" (nth args (inc (.indexOf args "-i")))))
    (is (re-find #"fps=12,scale=200:" (nth args (inc (.indexOf args "-vf"))))))
  (is (= "60" (second (drop-while #(not= "-framerate" %)
                                  (render/mp4-args "d" 60 "d/d.mp4"))))))

(defn- falling-box-world []
  (let [b (util/box 0.5 0.5 0.5 :position (Vector3f. 0 3 0) :color ColorRGBA/Red :name "box")
        floor (util/box 10 1 10 :position (Vector3f. 0 -1 0) :color ColorRGBA/Gray
                        :mass 0 :name "floor")]
    [b (world/world (util/nodify [b floor]) {}
                    (fn [w]
                      (doto (.getCamera w)
                        (.setLocation (Vector3f. 0 2 10))
                        (.lookAt (Vector3f. 0 1 0) Vector3f/UNIT_Y)))
                    world/no-op)]))

(defn- red-rows
  "The rows of `image` holding reddish pixels."
  [^BufferedImage image]
  (for [y (range (.getHeight image))
        :when (some #(let [[r g b] (rgb image % y)] (and (> r 150) (< g 80) (< b 80)))
                    (range (.getWidth image)))]
    y))

(deftest recording-offscreen
  (let [dir (temp-dir)
        [box w] (falling-box-world)
        before (live-threads)
        start (System/nanoTime)]
    (render/record! w dir {:progress nil})
    (render/run-offscreen! w 120 {:size [320 240]})
    (let [seconds (/ (- (System/nanoTime) start) 1e9)
          frames (render/frames-in dir)
          first-frame (ImageIO/read ^java.io.File (first frames))
          last-frame (ImageIO/read ^java.io.File (last frames))]
      (println (format "recorded 120 frames at 320x240 offscreen in %.2f s" seconds))
      (testing "2 simulated seconds at 1/60 s a frame are 120 pictures"
        (is (= 120 (:frames @w) (count frames))))
      (is (= [320 240] [(.getWidth last-frame) (.getHeight last-frame)]))
      (testing "the sky is black, the floor grey"
        (is (= [0 0 0] (rgb last-frame 5 5)))
        (is (every? #(< 100 % 160) (rgb last-frame 160 230))))
      (testing "the box is drawn, and lower at the end than at the start"
        (is (seq (red-rows first-frame)))
        (is (seq (red-rows last-frame)))
        (is (> (apply min (red-rows last-frame)) (apply max (red-rows first-frame)))))
      (testing "no thread outlives the run"
        (is (empty? (remove before (live-threads)))))
      (testing "the physics is the same as a headless run's, to the bit"
        (let [[box2 w2] (falling-box-world)]
          (world/run-world! w2 120)
          (is (= (.getWorldTranslation box) (.getWorldTranslation box2)))
          (is (= (.getWorldRotation box) (.getWorldRotation box2))))))))

(deftest one-offscreen-world-after-another
  (dotimes [i 3]
    (let [[_ w] (falling-box-world)
          frames (atom [])]
      (render/grab-frames! w (fn [image] (swap! frames conj (seq (red-rows image)))))
      (render/run-offscreen! w 5 {:size [160 120]})
      (is (every? some? @frames) (str "world " (inc i) " drew the box in every frame")))))

(deftest recording-refuses-what-cannot-work
  (let [file (io/file (temp-dir) "not-a-folder")]
    (spit file "")
    (is (thrown-with-msg? clojure.lang.ExceptionInfo #"cannot make folder"
                          (render/record! (second (falling-box-world)) (io/file file "frames")))))
  (let [[_ w] (falling-box-world)]
    (render/record! w (temp-dir) {:progress nil})
    (is (thrown-with-msg? clojure.lang.ExceptionInfo #"null renderer"
                          (world/run-world! w 5)))))

(deftest videos
  (let [dir (temp-dir)
        [_ w] (falling-box-world)]
    (render/record! w dir {:progress nil})
    (render/run-offscreen! w 30 {:size [160 120]})
    (if (render/ffmpeg)
      (let [{:keys [mp4 gif]} (render/make-videos! dir 60 {:name "box" :width 80})]
        (is (.endsWith ^String mp4 "box.mp4"))
        (is (pos? (.length (io/file mp4))))
        (is (= 80 (.getWidth (ImageIO/read (io/file gif))))))
      (do (println "ffmpeg is not installed: the video test only checks that it is skipped")
          (is (nil? (render/make-videos! dir 60)))))))

(deftest offscreen-beside-the-caller
  (let [dir (temp-dir)
        err (java.io.StringWriter.)
        [_ w] (falling-box-world)]
    (binding [*err* err]
      (render/record! w dir {:progress (render/progress-printer)}))
    (let [start (System/nanoTime)]
      (render/start-offscreen! w {:size [160 120]})
      (is (< (/ (- (System/nanoTime) start) 1e9) 1.0) "start-offscreen! returns at once"))
    (let [deadline (+ (System/currentTimeMillis) 20000)]
      (while (and (< (count (render/frames-in dir)) 20) (< (System/currentTimeMillis) deadline))
        (Thread/sleep 20)))
    (world/stop! w)
    (is (not (world/running? w)))
    (is (nil? (:error @w)))
    (let [n (count (render/frames-in dir))]
      (is (<= 20 n) "frames were recorded while the caller went on")
      (is (re-find (re-pattern (str "recording: " n " frames\n")) (str err))
          "the counter wrote to the *err* of the caller"))
    (testing "started again, it draws again"
      (let [frames (atom 0)]
        (render/grab-frames! w (fn [_] (swap! frames inc)))
        (render/start-offscreen! w)
        (let [deadline (+ (System/currentTimeMillis) 20000)]
          (while (and (< @frames 5) (< (System/currentTimeMillis) deadline))
            (Thread/sleep 20)))
        (world/stop! w)
        (is (<= 5 @frames))
        (is (nil? (:error @w)))))))

(deftest no-window-without-a-display
  (if (render/display?)
    (println "there is a display: the test of start-window! without one is skipped")
    (let [[_ w] (falling-box-world)]
      (is (thrown-with-msg? clojure.lang.ExceptionInfo #"no display"
                            (render/start-window! w)))
      (is (not (world/running? w))))))
