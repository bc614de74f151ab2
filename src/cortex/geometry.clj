;; Generated from org/geometry.org by lein tangle: edit the chapter, not this file.
(ns cortex.geometry
  "Geometry of point sets, as plain data: the volume of a convex hull,
  and how thin a set of points is, and the thickness below which a body
  is small.

  Entry points: `hull-volume`, `points-sides`, `points-thickness`,
  `sheet-thickness`, `thin`."
  (:require [cortex.export.geometry :as xg]))

(set! *warn-on-reflection* true)

(def thin
  "The thickness below which a body is small, on either engine: 0.05,
  under the thinnest segment of any pinned drop (a stranger's lower arm,
  0.062). See the shapes chapter, \"Small and thin bodies\"."
  0.05)

(defn points-sides
  "The extents of `points` ([[x y z] ...], at least one) along each
  axis, [x y z]."
  [points]
  (vec (for [i (range 3) :let [xs (map #(double (nth % i)) points)]]
         (- (double (apply max xs)) (double (apply min xs))))))

(defn points-thickness
  "The smallest extent of `points` ([[x y z] ...], at least one) along
  an axis."
  ^double [points]
  (apply min (points-sides points)))

(defn sheet-thickness
  "How thick a body whose extents along its own axes are `sides` counts
  as: its smallest extent, or for a sheet (smallest under a tenth of the
  next; a plane's polygon has none) a tenth of the next. See the shapes
  chapter, \"Flat parts\"."
  ^double [sides]
  (let [[a b] (sort (map double sides))]
    (max a (* 0.1 b))))

(defn hull-volume
  "The volume of the convex hull of `points` ([[x y z] ...]); 0 when
  they enclose none (fewer than four, or all on a plane)."
  ^double [points]
  (let [ps (vec (distinct (map #(mapv double %) points)))]
    (if (< (count ps) 4)
      0.0
      (if-let [faces (try (xg/hull-faces ps) (catch clojure.lang.ExceptionInfo _ nil))]
        (let [o (ps 0)]
          (/ (reduce + (for [[a b c] faces]
                         (xg/dot (xg/v- (ps a) o) (xg/cross (xg/v- (ps b) o) (xg/v- (ps c) o)))))
             6.0))
        0.0))))
