;; Generated from org/geometry.org by lein tangle: edit the chapter, not this file.
(ns cortex.geometry
  "Geometry of point sets, as plain data: the volume of a convex hull,
  and how thin a set of points is, and the thickness below which a body
  is small.

  Entry points: `hull-volume`, `points-thickness`, `thin`."
  )

(set! *warn-on-reflection* true)

(defn- v- [[ax ay az] [bx by bz]] [(- ax bx) (- ay by) (- az bz)])
(defn- cross [[ax ay az] [bx by bz]]
  [(- (* ay bz) (* az by)) (- (* az bx) (* ax bz)) (- (* ax by) (* ay bx))])
(defn- dot ^double [[ax ay az] [bx by bz]] (+ (* ax bx) (* ay by) (* az bz)))

(defn- cross-2d ^double [[ax ay] [bx by] [cx cy]]
  (- (* (- (double bx) (double ax)) (- (double cy) (double ay)))
     (* (- (double by) (double ay)) (- (double cx) (double ax)))))

(defn- polygon-area
  "The area of the convex hull of `ps`, which lie on a plane of normal
  `n`: their convex hull in the plane (Andrew's monotone chain), so that
  a point inside the face, or in the middle of an edge, adds nothing."
  ^double [ps n]
  (let [c (mapv #(/ (double %) (count ps)) (reduce #(mapv + %1 %2) ps))
        far (apply max-key #(let [d (v- % c)] (dot d d)) ps)
        u (let [d (v- far c) l (Math/sqrt (dot d d))] (mapv #(/ (double %) l) d))
        w (let [d (cross n u) l (Math/sqrt (dot d d))] (mapv #(/ (double %) l) d))
        flat (sort (distinct (map #(let [d (v- % c)] [(dot d u) (dot d w)]) ps)))
        half (fn [pts] (reduce (fn [h p]
                                 (loop [h h]
                                   (if (and (>= (count h) 2)
                                            (<= (cross-2d (h (- (count h) 2)) (peek h) p) 0.0))
                                     (recur (pop h))
                                     (conj h p))))
                               [] pts))
        lower (half flat)
        upper (half (reverse flat))
        hull (concat (pop lower) (pop upper))]
    (if (< (count flat) 3)
      0.0
      (/ (Math/abs (double (reduce + (map (fn [[ax ay] [bx by]]
                                            (- (* (double ax) (double by)) (* (double bx) (double ay))))
                                          hull (concat (rest hull) [(first hull)])))))
         2.0))))

(defn hull-volume
  "The volume of the convex hull of `points` ([[x y z] ...]); 0 for
  fewer than four."
  ^double [points]
  (let [ps (vec (distinct (map #(mapv double %) points)))
        n (count ps)]
    (if (< n 4)
      0.0
      (let [c (mapv #(/ (double %) n) (reduce #(mapv + %1 %2) ps))
            size (reduce max 1e-12 (map #(Math/sqrt (dot (v- % c) (v- % c))) ps))
            eps (* 1e-5 size)
            ;; every plane through three vertices with all on one side,
            ;; as its outward unit normal, its height above the centroid
            ;; and the vertices on it
            planes (for [i (range n) j (range (inc i) n) k (range (inc j) n)
                         :let [a (ps i) nrm (cross (v- (ps j) a) (v- (ps k) a))
                               len (Math/sqrt (dot nrm nrm))]
                         :when (> len (* eps size))
                         :let [unit (mapv #(/ (double %) len) nrm)
                               sides (mapv #(dot unit (v- % a)) ps)]
                         :when (or (every? #(<= (double %) eps) sides)
                                   (every? #(>= (double %) (- eps)) sides))
                         :let [h (dot unit (v- a c))
                               [unit h] (if (neg? h) [(mapv - unit) (- h)] [unit h])]]
                     {:unit unit :height h
                      :on (set (filter #(< (Math/abs (double (sides %))) eps) (range n)))})
            ;; one face per outward direction: planes whose normals agree
            ;; within a thousandth of a radian are one face
            faces (reduce (fn [faces {:keys [unit on] :as plane}]
                            (if-let [i (first (keep-indexed
                                               #(when (> (dot unit (:unit %2)) (- 1.0 5e-7)) %1)
                                               faces))]
                              (update-in faces [i :on] into on)
                              (conj faces plane)))
                          [] planes)]
        (reduce + (for [{:keys [unit height on]} faces]
                    (/ (* (Math/abs (polygon-area (mapv ps on) unit)) (double height)) 3.0)))))))

(def thin
  "The thickness below which a body is small, on either engine: 0.05,
  under the thinnest segment of any pinned drop (a stranger's lower arm,
  0.062). See the shapes chapter, \"Small and thin bodies\"."
  0.05)

(defn points-thickness
  "The smallest extent of `points` ([[x y z] ...], at least one) along
  an axis."
  ^double [points]
  (apply min (for [i (range 3) :let [xs (map #(double (nth % i)) points)]]
               (- (double (apply max xs)) (double (apply min xs))))))
