;; Generated from org/strength.org by lein tangle: edit the chapter, not this file.
(ns cortex.strength
  "A joint's default strength and PD gains, from masses, distances and
  moments of inertia alone: what cortex.muscle works out from a built
  creature's bodies, and what a plan (see cortex.plan) says of each
  joint before anything is built.

  Entry points: `default-strength`, `default-gains`, `plan-muscles`,
  `gravity`, `step`, and the plan's geometry `shape-points`,
  `box-moments`, `axis-of`, `blender->jme`."
  (:require [cortex.export.geometry :refer [dot identity3 mm mv norm quat->matrix v+ v- v*]])
  (:import (com.jme3.math Vector3f)))

(set! *warn-on-reflection* true)

(def gravity
  "The gravity, m/s^2, that default strengths are sized against."
  9.81)

(def step
  "The physics step the default gains are sized for, s."
  (/ 1.0 60))

(defn default-strength
  "Twice the torque that holds the lighter moving segment straight out
  against gravity: 2 g m d, over `loads`, [mass distance] of each
  segment (mass 0 for a static one). 0 when neither moves."
  ^double [loads]
  (let [moving (for [[m d] loads :when (pos? (double m))] (* (double m) (double d)))]
    (if (seq moving) (* 2.0 gravity (apply min moving)) 0.0)))

(defn default-gains
  "{:kp :kd} for a muscle of `strength` at a joint whose two segments
  have a reduced moment of inertia `inertia` about the pin and `own`
  about their centres of mass: kp = strength / 0.02, at most inertia
  (0.5/dt)^2; kd = 2 sqrt(kp inertia), critical damping, but at most
  own/dt, so that one step never overshoots (see the text)."
  [^double strength ^double inertia ^double own]
  (let [kp (min (/ strength 0.02) (* inertia (Math/pow (/ 0.5 step) 2)))]
    {:kp kp :kd (min (* 2.0 (Math/sqrt (* kp inertia))) (/ own step))}))

(defn box-moments
  "Bullet's box rule: the principal moments of mass `m` spread as a box
  the size of the bounding box of `points` (plus `margin` on every
  side), about the origin."
  [m points margin]
  (let [[lx ly lz] (for [k (range 3)
                         :let [xs (map #(double (nth % k)) points)]]
                     (+ (- (reduce max xs) (reduce min xs)) (* 2 (double margin))))
        k (/ (double m) 12)]
    [(* k (+ (* ly ly) (* lz lz))) (* k (+ (* lx lx) (* lz lz))) (* k (+ (* lx lx) (* ly ly)))]))

(defn shape-points
  "The points (the segment's own frame, jME's axes) that bound `shape`:
  a hull's own; a primitive's bounding box's corners."
  [{:keys [type points half-extents radius height axis children] :as shape}]
  (case type
    (:hull :mesh) points
    :box (let [[x y z] half-extents] (for [a [-1 1] b [-1 1] c [-1 1]] [(* a x) (* b y) (* c z)]))
    :sphere (let [r radius] (for [a [-1 1] b [-1 1] c [-1 1]] [(* a r) (* b r) (* c r)]))
    (:capsule :cone :cylinder)
    (let [r (or radius (first half-extents))
          h (case type :capsule (+ (/ (double height) 2) r) :cone (/ (double height) 2)
                  :cylinder (nth half-extents (or axis 1)))
          ext (assoc [r r r] (or axis 1) h)]
      (for [a [-1 1] b [-1 1] c [-1 1]] (mapv * [a b c] ext)))
    :compound (for [{s :shape p :position q :rotation} children
                    pt (shape-points s)]
                (v+ p (mv (quat->matrix q) pt)))))

(defn axis-of
  "A hinge description's axis as [x y z] (Blender's axes), unit; X
  when it gives none."
  [{:keys [axis]}]
  (let [a (cond (nil? axis) [1 0 0]
                (instance? Vector3f axis) (let [^Vector3f v axis] [(.x v) (.y v) (.z v)])
                :else axis)]
    (v* (/ 1.0 (norm a)) a)))

(defn blender->jme [[x y z]] [x z (- y)])

(defn- world-inertia
  "A segment's (jME world) centre of mass, principal axes (columns) and
  moments."
  [{:keys [position rotation inertia shape mass]}]
  (let [R (quat->matrix rotation)
        box? (= :box (:source inertia))]
    {:com (v+ position (mv R (if box? [0 0 0] (:centre inertia))))
     :axes (mm R (if box? identity3 (quat->matrix (:rotation inertia))))
     :moments (or (:moments inertia)
                  (box-moments mass (shape-points shape) (or (:margin shape) 0.0)))
     :mass (double mass)}))

(defn- pin-inertia
  "cortex.muscle/pivot-inertia of a segment (see `world-inertia`) about
  the world axis `axis` through `pin` (relative to its centre of mass)."
  ^double [{:keys [axes moments mass]} axis pin]
  (if (zero? (double mass))
    Double/POSITIVE_INFINITY
    (let [inv (reduce + (map (fn [i k] (let [a (dot axis (mapv #(nth % k) axes))]
                                          (/ (* a a) (double i))))
                             moments (range 3)))
          own (if (pos? inv) (/ 1.0 inv) Double/POSITIVE_INFINITY)
          along (dot pin axis)]
      (+ own (* (double mass) (- (dot pin pin) (* along along)))))))

(defn plan-muscles
  "Each joint's muscle, by name, as cortex.muscle works it out from the
  built creature, here from the plan: {:strength s :kp k :kd d} for a
  hinge, :kp and :kd [x y z] about the joint frame's axes (jME's
  order) for a cone or point joint."
  [plan]
  (let [segs (into {} (map (juxt :id world-inertia)) (:segments plan))]
    (into {}
          (for [{:keys [name type description pivot rotation] [a b] :segments} (:joints plan)]
            (let [A (segs a) B (segs b)
                  pa (v- pivot (:com A)) pb (v- pivot (:com B))
                  given (fn [k default] (if-some [v (get description k)] (double v) (default)))
                  strength (given :strength
                                  #(default-strength [[(:mass A) (norm pa)] [(:mass B) (norm pb)]]))
                  about (fn [ax pin-a pin-b]
                          (let [i (/ 1.0 (+ (/ 1.0 (pin-inertia A ax pin-a))
                                            (/ 1.0 (pin-inertia B ax pin-b))))]
                            (if (and (Double/isFinite i) (pos? i)) i 1.0)))
                  sized (fn [ax] (let [i (about ax pa pb)]
                                   (default-gains strength i
                                                         (min i (about ax [0 0 0] [0 0 0])))))
                  E (quat->matrix rotation)]
              [name
               (if (= type :hinge)
                 (let [g (sized (mv E (blender->jme (axis-of description))))]
                   {:strength strength :kp (given :kp #(:kp g)) :kd (given :kd #(:kd g))})
                 (let [gs (mapv #(sized (mapv (fn [row] (nth row %)) E)) (range 3))
                       per (fn [k] (if-some [v (get description k)]
                                     (vec (repeat 3 (double v)))
                                     (mapv k gs)))]
                   {:strength strength :kp (per :kp) :kd (per :kd)}))])))))
