;; Generated from org/blender-mesh.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender-mesh-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.blender.file :as file]
            [cortex.blender.mesh :as mesh])
  (:import [java.nio.file Files Paths]))

(set! *warn-on-reflection* true)

(defn- mesh-named
  "The mesh data of the Mesh ID `name` in the .blend file at `path`,
  read with the struct reader alone."
  [path name]
  (let [bf (file/parse path (Files/readAllBytes (Paths/get ^String path (make-array String 0))))
        me (some #(when (= name (file/id-name %)) %)
                 (keep #(file/block-ref bf %) (file/blocks-with-code bf "ME")))]
    (mesh/mesh-data bf me)))

(defn- plain
  "Mesh data with its arrays as vectors, to compare."
  [md]
  (into {} (for [[k v] md] [k (if (and v (.isArray (class v))) (vec v) v)])))

(deftest one-mesh-three-layouts
  (let [[b34 b45 b50] (for [v ["b34" "b45" "b50"]]
                        (plain (mesh-named (str "test/fixtures/blender-reader/" v "/reader.blend")
                                           "l-shape")))]
    (is (= {:name "l-shape"
            :positions [0.0 0.0 0.0 2.0 0.0 0.0 2.0 1.0 0.0 1.0 1.0 0.0 1.0 2.0 0.0 0.0 2.0 0.0]
            :starts [0] :counts [6] :corners [0 1 2 3 4 5] :mats [0] :smooth [false] :uvs nil}
           b34))
    (is (= b34 b45 b50))
    (is (= 4 (mesh/triangle-count (mesh-named "test/fixtures/blender-reader/b50/reader.blend"
                                              "l-shape"))))))

(deftest concave-faces-triangulate
  (let [l-shape [[0 0] [2 0] [2 1] [1 1] [1 2] [0 2]]
        pts (mapv (fn [[x y]] (double-array [x y 0.0])) l-shape)
        tris (mesh/triangulate pts)
        area (fn [[a b c]]
               (let [[ax ay] (l-shape a) [bx by] (l-shape b) [cx cy] (l-shape c)]
                 (/ (- (* (- bx ax) (- cy ay)) (* (- by ay) (- cx ax))) 2.0)))]
    (is (= 4 (count tris)))
    (is (every? pos? (map area tris)))
    (is (< (Math/abs (- 3.0 (reduce + (map area tris)))) 1e-9)))
  (testing "a convex face is fanned"
    (is (= [[0 1 2] [0 2 3] [0 3 4]]
           (mesh/triangulate (mapv #(double-array [(Math/cos %) (Math/sin %) 0.0])
                                   (map #(* % 2 (/ Math/PI 5)) (range 5))))))))

(deftest a-mirror-shares-what-lies-on-its-plane
  (let [md {:positions (float-array [0 0 0, 0 1 0, 0 1 1, 0 0 1, 0.0004 2 0, 1 2 0, 1 2 1])
            :starts (int-array [0 4]) :counts (int-array [4 3]) :corners (int-array [0 1 2 3 4 5 6])
            :mats (int-array [0 1]) :smooth (boolean-array [false true]) :uvs nil}
        out (plain (mesh/mirrored md (fn [[x y z]] [(- x) y z]) true 0.001))
        corner (fn [f k] (let [i ((:corners out) (+ ((:starts out) f) k))]
                           (subvec (:positions out) (* 3 i) (+ 3 (* 3 i)))))]
    (is (= 9 (quot (count (:positions out)) 3)) "seven vertices and the copies of the two off the plane")
    (is (= [0.0 2.0 0.0] (mapv double (subvec (:positions out) 12 15))) "the corner moved onto the plane")
    (is (= [4 3 3] (:counts out)) "the square's copy left out")
    (is (= [0 1 1] (:mats out)))
    (is (= [[0.0 2.0 0.0] [-1.0 2.0 1.0] [-1.0 2.0 0.0]] (mapv #(mapv double (corner 2 %)) [0 1 2]))
        "the copy keeps its first corner and runs backwards"))
  (testing "without merging, every vertex and face is copied"
    (let [md {:positions (float-array [0 0 0, 1 0 0, 0 1 0]) :starts (int-array [0]) :counts (int-array [3])
              :corners (int-array [0 1 2]) :mats (int-array [0]) :smooth (boolean-array [false])
              :uvs (float-array [0 0 1 0 0 1])}
          out (plain (mesh/mirrored md (fn [[x y z]] [(- x) y z]) false 0.001))]
      (is (= 6 (quot (count (:positions out)) 3)))
      (is (= [3 3] (:counts out)))
      (is (= [0 1 2 3 5 4] (:corners out)))
      (is (= [0.0 0.0 1.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0 1.0 0.0] (mapv double (:uvs out)))))))
