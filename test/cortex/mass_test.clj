;; Generated from org/mass.org by lein tangle: edit the chapter, not this file.
(ns cortex.mass-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.mass :as mass]))

(defn- box-triangles
  "The 12 outward triangles of a box from `lo` to `hi`."
  [[x0 y0 z0] [x1 y1 z1]]
  (let [p (fn [i j k] [(if (zero? i) x0 x1) (if (zero? j) y0 y1) (if (zero? k) z0 z1)])
        quad (fn [a b c d] [[a b c] [a c d]])]
    (concat (quad (p 0 0 0) (p 0 1 0) (p 1 1 0) (p 1 0 0))   ; -z
            (quad (p 0 0 1) (p 1 0 1) (p 1 1 1) (p 0 1 1))   ; +z
            (quad (p 0 0 0) (p 1 0 0) (p 1 0 1) (p 0 0 1))   ; -y
            (quad (p 0 1 0) (p 0 1 1) (p 1 1 1) (p 1 1 0))   ; +y
            (quad (p 0 0 0) (p 0 0 1) (p 0 1 1) (p 0 1 0))   ; -x
            (quad (p 1 0 0) (p 1 1 0) (p 1 1 1) (p 1 0 1))))) ; +x

(defn- prism-triangles
  "A regular `n`-sided prism of radius `r` along z, from z0 to z1."
  [n r z0 z1]
  (let [ring (fn [z] (vec (for [i (range n) :let [a (/ (* 2 Math/PI i) n)]]
                            [(* r (Math/cos a)) (* r (Math/sin a)) z])))
        lo (ring z0) hi (ring z1)
        c0 [0.0 0.0 z0] c1 [0.0 0.0 z1]]
    (concat (for [i (range n) :let [j (mod (inc i) n)]] [c0 (lo j) (lo i)])
            (for [i (range n) :let [j (mod (inc i) n)]] [c1 (hi i) (hi j)])
            (mapcat (fn [i] (let [j (mod (inc i) n)]
                              [[(lo i) (lo j) (hi j)] [(lo i) (hi j) (hi i)]]))
                    (range n)))))

(defn- within [pct expected actual]
  (<= (Math/abs (- (double actual) (double expected))) (* pct 0.01 (Math/abs (double expected)))))

(deftest a-box
  (let [{:keys [volume centre inertia]} (mass/mesh-properties (box-triangles [-1 -0.5 -0.25] [1 0.5 0.25]) 3.0)]
    (is (within 1e-6 1.0 volume))
    (is (every? #(< (Math/abs (double %)) 1e-12) centre))
    (is (within 1e-6 (/ (* 3 (+ 1 0.25)) 12) (get-in inertia [0 0])))
    (is (within 1e-6 (/ (* 3 (+ 4 0.25)) 12) (get-in inertia [1 1])))
    (is (within 1e-6 (/ (* 3 (+ 4 1)) 12) (get-in inertia [2 2])))
    (is (< (Math/abs (double (get-in inertia [0 1]))) 1e-12))))

(deftest a-32-sided-cylinder
  (let [r 0.3 h 2.0 m 5.0
        {:keys [centre inertia]} (mass/mesh-properties (prism-triangles 32 r (- (/ h 2)) (/ h 2)) m)]
    (is (every? #(< (Math/abs (double %)) 1e-9) centre))
    (is (within 1 (/ (* m r r) 2) (get-in inertia [2 2])) "about its axis")
    (is (within 1 (/ (* m (+ (* 3 r r) (* h h))) 12) (get-in inertia [0 0])) "about a diameter")))

(deftest origin-off-the-centre
  (testing "the origin on the box's bottom face: the centre is half a side up, the moments as before"
    (let [{:keys [centre inertia]} (mass/mesh-properties (box-triangles [-1 -0.5 0] [1 0.5 0.5]) 3.0)]
      (is (within 1e-6 0.25 (nth centre 2)))
      (is (within 1e-6 (/ (* 3 (+ 4 1)) 12) (get-in inertia [2 2])))
      (is (within 1e-6 (/ (* 3 (+ 1 0.25)) 12) (get-in inertia [0 0])))))
  (testing "inward-facing triangles give the same solid"
    (let [tris (map (fn [[a b c]] [a c b]) (box-triangles [-1 -0.5 0] [1 0.5 0.5]))]
      (is (within 1e-6 0.25 (nth (:centre (mass/mesh-properties tris 3.0)) 2)))))
  (testing "a flat mesh encloses nothing"
    (is (nil? (mass/mesh-properties [[[0 0 0] [1 0 0] [0 1 0]]] 1.0)))))

(deftest principal-axes-of-a-turned-box
  (let [a (/ Math/PI 6) c (Math/cos a) s (Math/sin a)
        turn (fn [[x y z]] [(- (* c x) (* s y)) (+ (* s x) (* c y)) z])
        tris (map #(mapv turn %) (box-triangles [-1 -0.5 -0.25] [1 0.5 0.25]))
        {:keys [inertia]} (mass/mesh-properties tris 3.0)
        {:keys [moments axes]} (mass/principal inertia)
        expected (sort [(/ (* 3 1.25) 12) (/ (* 3 4.25) 12) (/ (* 3 5) 12)])]
    (is (> (Math/abs (double (get-in inertia [0 1]))) 0.1) "turned, the tensor is not diagonal")
    (is (every? true? (map #(within 1e-6 %1 %2) expected (sort moments))))
    (testing "the axis of the smallest moment is the box's long side, turned"
      (let [i (first (apply min-key second (map-indexed vector moments)))
            axis (mapv #(nth % i) axes)]
        (is (within 1e-6 1.0 (Math/abs (+ (* c (axis 0)) (* s (axis 1))))))))))
