(ns cortex.blender.jme
  "Scene data (see cortex.blender.scene) as a jME scene graph shaped as
  jme3-blender shapes it: root Node, scene Node, a Node per object
  parented as in Blender, a Geometry per material under each mesh
  object's Node."
  (:require [cortex.blender.math :as m]
            [cortex.blender.mesh :as mesh])
  (:import [com.jme3.scene Node Geometry Mesh VertexBuffer$Type Spatial]
           [com.jme3.math Vector3f Quaternion Matrix3f ColorRGBA Transform]
           [com.jme3.material Material]
           [com.jme3.util BufferUtils]
           [com.jme3.asset AssetManager]))

(set! *warn-on-reflection* true)

(defn world-trs
  "Blender world matrix `w` (4x4 rows, Z up) as jME sees it (Y up),
  split into :translation, :rotation (3x3), :scale and :residual, the
  3x3 that translation-rotation-scale cannot express (shear, from
  non-uniform scale under a rotated parent), or nil when there is none."
  [w]
  (let [wy (m/to-y-up w)
        {:keys [rotation scale]} (m/decompose wy)
        res (m/residual (m/mat4->mat3 wy) rotation scale)]
    {:translation (m/translation wy)
     :rotation rotation
     :scale scale
     :residual (when-not (m/near-identity? res 1e-5) res)}))

(defn- vec3 ^Vector3f [[x y z]] (Vector3f. (float x) (float y) (float z)))

(defn- quat
  "A jME Quaternion from a 3x3 rotation (rows)."
  ^Quaternion [r]
  (let [[[a b c] [d e f] [g h i]] r]
    (.normalizeLocal
     (.fromRotationMatrix (Quaternion.)
                          (Matrix3f. (float a) (float b) (float c)
                                     (float d) (float e) (float f)
                                     (float g) (float h) (float i))))))

(defn trs->transform
  "A jME Transform of world-trs map `t`."
  ^Transform [t]
  (Transform. (vec3 (:translation t)) (quat (:rotation t)) (vec3 (:scale t))))

(defn local-transform
  "The local Transform that puts a child at world Transform `w` under a
  parent at world Transform `p`, undoing jME's composition (world =
  parent.rot * (parent.scale * local.translation) + parent.translation;
  rotations multiply; scales multiply per axis). A zero parent scale
  axis is treated as 1."
  ^Transform [^Transform p ^Transform w]
  (let [safe (fn [^double x] (if (< (Math/abs x) 1e-12) 1.0 x))
        ps (.getScale p)
        ps (Vector3f. (float (safe (.x ps))) (float (safe (.y ps))) (float (safe (.z ps))))
        pinv (.inverse (.getRotation p))
        t (.divideLocal (.mult pinv (.subtract (.getTranslation w) (.getTranslation p))) ps)
        r (.mult pinv (.getRotation w))
        s (.divide (.getScale w) ps)]
    (Transform. t r s)))

(defn user-value
  "A property value as jME 3.2's UserData accepts it: String, Integer,
  Float, Boolean, Long, List, Map. jME 3.2 has no Double type, so
  doubles become Floats."
  [v]
  (cond
    (string? v) v
    (instance? Boolean v) v
    (instance? Float v) v
    (instance? Double v) (float v)
    (integer? v) (if (<= Integer/MIN_VALUE v Integer/MAX_VALUE) (int v) (long v))
    (map? v) (java.util.HashMap. ^java.util.Map (into {} (map (fn [[k x]] [(str k) (user-value x)])) v))
    (sequential? v) (java.util.ArrayList. ^java.util.Collection (mapv user-value v))
    (nil? v) nil
    :else (str v)))

(defn set-user-data!
  "Store each of `props` (name -> value) on spatial `s` as user data
  under its own name."
  [^Spatial s props]
  (doseq [[k v] props
          :let [u (user-value v)]
          :when (some? u)]
    (.setUserData s (str k) u))
  s)

(defn material
  "A lit material of colour [r g b a]: Lighting.j3md with material
  colours. Needs only the asset manager, not a GPU."
  ^Material [^AssetManager am [r g b a]]
  (let [c (ColorRGBA. (float r) (float g) (float b) (float (or a 1.0)))]
    (doto (Material. am "Common/MatDefs/Light/Lighting.j3md")
      (.setBoolean "UseMaterialColors" true)
      (.setColor "Diffuse" c)
      (.setColor "Ambient" c))))

(defn- normalize! [^doubles v]
  (let [l (Math/sqrt (+ (* (aget v 0) (aget v 0)) (* (aget v 1) (aget v 1)) (* (aget v 2) (aget v 2))))]
    (when (> l 1e-30)
      (dotimes [k 3] (aset v k (/ (aget v k) l))))
    v))

(defn face-normals
  "Unit normal of each face (Blender coordinates), as double arrays."
  [{:keys [^floats positions ^ints starts ^ints counts ^ints corners]}]
  (vec (for [i (range (alength starts))
             :let [s (aget starts i) n (aget counts i)
                   pts (mapv #(mesh/vertex positions (aget corners (+ s (long %)))) (range n))]]
         (normalize! (double-array (if (>= n 3) (mesh/newell-normal pts) [0 0 1]))))))

(defn vertex-normals
  "Unit normal of each vertex: the sum of the area-weighted normals of
  the smooth faces around it."
  [{:keys [^floats positions ^ints starts ^ints counts ^ints corners ^booleans smooth]}]
  (let [nv (quot (alength positions) 3)
        acc (double-array (* 3 nv))]
    (dotimes [i (alength starts)]
      (when (aget smooth i)
        (let [s (aget starts i) n (aget counts i)
              pts (mapv #(mesh/vertex positions (aget corners (+ s (long %)))) (range n))
              [x y z] (if (>= n 3) (mesh/newell-normal pts) [0.0 0.0 0.0])]
          (dotimes [k n]
            (let [v (aget corners (+ s k))]
              (aset acc (* 3 v) (+ (aget acc (* 3 v)) (double x)))
              (aset acc (+ 1 (* 3 v)) (+ (aget acc (+ 1 (* 3 v))) (double y)))
              (aset acc (+ 2 (* 3 v)) (+ (aget acc (+ 2 (* 3 v))) (double z))))))))
    acc))

(defn- apply3
  "3x3 `m` (rows) times [x y z], written to `out` at `i`."
  [m ^floats out i x y z]
  (let [[[a b c] [d e f] [g h k]] m
        i (long i)
        x (double x) y (double y) z (double z)]
    (aset out i (float (+ (* a x) (* b y) (* c z))))
    (aset out (+ i 1) (float (+ (* d x) (* e y) (* f z))))
    (aset out (+ i 2) (float (+ (* g x) (* h y) (* k z))))))

(defn mesh-buffers
  "Position, normal and index arrays for the faces of mesh data `md`
  whose slot is in `slots`: a vertex per face corner (so flat faces
  keep their own normal), positions mapped by 3x3 `pm` (Blender to Y
  up, and any residual) and normals by `nm`."
  [md face-ids pm nm]
  (let [{:keys [^floats positions ^ints starts ^ints counts ^ints corners ^booleans smooth]} md
        fnorm (face-normals md)
        ^doubles vnorm (vertex-normals md)
        nverts (reduce + (map #(aget counts (int %)) face-ids))
        ntris (reduce + (map #(max 0 (- (aget counts (int %)) 2)) face-ids))
        pos (float-array (* 3 nverts))
        nor (float-array (* 3 nverts))
        idx (int-array (* 3 ntris))]
    (loop [[f & more] face-ids vbase 0 tbase 0]
      (if (nil? f)
        {:positions pos :normals nor :indices idx}
        (let [s (aget starts (int f)) n (aget counts (int f))
              ^doubles fnv (fnorm f)
              pts (mapv #(mesh/vertex positions (aget corners (+ s (long %)))) (range n))
              tris (mesh/triangulate pts)]
          (dotimes [k n]
            (let [v (aget corners (+ s k))
                  o (* 3 (+ vbase k))
                  ^doubles nv (if (aget smooth (int f))
                                (normalize! (double-array [(aget vnorm (* 3 v)) (aget vnorm (+ 1 (* 3 v)))
                                                           (aget vnorm (+ 2 (* 3 v)))]))
                                fnv)]
              (apply3 pm pos o (aget positions (* 3 v)) (aget positions (+ 1 (* 3 v)))
                      (aget positions (+ 2 (* 3 v))))
              (apply3 nm nor o (aget nv 0) (aget nv 1) (aget nv 2))))
          (doseq [[t [a b c]] (map-indexed vector tris)]
            (let [o (* 3 (+ tbase (long t)))]
              (aset idx o (int (+ vbase (long a))))
              (aset idx (+ o 1) (int (+ vbase (long b))))
              (aset idx (+ o 2) (int (+ vbase (long c))))))
          (recur more (+ vbase n) (+ tbase (count tris))))))))

(defn jme-mesh
  "A jME Mesh of the arrays from `mesh-buffers`."
  ^Mesh [{:keys [^floats positions ^floats normals ^ints indices]}]
  (doto (Mesh.)
    (.setBuffer VertexBuffer$Type/Position 3 (BufferUtils/createFloatBuffer positions))
    (.setBuffer VertexBuffer$Type/Normal 3 (BufferUtils/createFloatBuffer normals))
    (.setBuffer VertexBuffer$Type/Index 3 (BufferUtils/createIntBuffer indices))
    (.updateBound)
    (.updateCounts)))

(defn- normal-matrix
  "Inverse transpose of 3x3 `m`, for normals (the identity if singular)."
  [m]
  (let [[[a b c] [d e f] [g h i]] m
        det (m/det3 m)]
    (if (< (Math/abs (double det)) 1e-30)
      (m/identity-matrix 3)
      (let [inv [[(- (* e i) (* f h)) (- (* c h) (* b i)) (- (* b f) (* c e))]
                 [(- (* f g) (* d i)) (- (* a i) (* c g)) (- (* c d) (* a f))]
                 [(- (* d h) (* e g)) (- (* b g) (* a h)) (- (* a e) (* b d))]]]
        (m/transpose (mapv (fn [row] (mapv #(/ % det) row)) inv))))))

(defn geometries
  "The Geometries of a mesh object: one per material slot its faces use
  (slot numbers clamped to the slots there are, as Blender does), in
  slot order, named object name + 1, 2, ... as jme3-blender names them.
  Vertices are in the object's frame, Y up, with `residual` (if any)
  baked in so that they land where Blender puts them."
  [am {:keys [name mesh materials color]} residual]
  (let [nslots (count materials)
        ^ints mats (:mats mesh)
        slot-of (fn [f] (max 0 (min (dec (max 1 nslots)) (aget mats (int f)))))
        by-slot (group-by slot-of (range (alength mats)))
        pm (if residual (m/mat-mul residual m/y-up) m/y-up)
        nm (normal-matrix pm)]
    (vec (map-indexed
          (fn [i slot]
            (let [g (Geometry. (str name (inc (long i)))
                               (jme-mesh (mesh-buffers mesh (by-slot slot) pm nm)))]
              (when am
                (.setMaterial g (material am (or (:color (get materials slot)) color))))
              g))
          (sort (keys by-slot))))))

(defn scene-graph
  "A jME Node named `root-name` holding a Node named as the scene, under
  which each object of scene data `sd` is a Node named as the object,
  parented as in Blender, whose world transform is the object's world
  matrix in Y-up. Mesh objects get Geometry children; custom
  properties become user data, plus \"blender-type\" (MESH, EMPTY,
  LIGHT, CAMERA, ...) unless a property of that name exists.
  Materials are made with asset manager `am` (none when nil)."
  ^Node [am root-name sd]
  (let [root (Node. (str root-name))
        scene (Node. (str (:scene sd)))
        objects (:objects sd)
        trs (into {} (map (fn [o] [(:key o) (world-trs (:world o))])) objects)
        xf (into {} (map (fn [[k t]] [k (trs->transform t)])) trs)
        nodes (into {} (for [o objects]
                         [(:key o)
                          (let [n (Node. (str (:name o)))]
                            (set-user-data! n (:properties o))
                            (when-not (contains? (:properties o) "blender-type")
                              (.setUserData n "blender-type" (str (:type o))))
                            n)]))]
    (.attachChild root scene)
    (doseq [o objects
            :let [^Node n (nodes (:key o))
                  parent (:parent-key o)
                  ^Node pn (if (and parent (nodes parent)) (nodes parent) scene)
                  ^Transform pw (if (and parent (nodes parent)) (xf parent) (Transform.))]]
      (.setLocalTransform n (local-transform pw (xf (:key o))))
      (when (:mesh o)
        (doseq [g (geometries am o (:residual (trs (:key o))))]
          (.attachChild n ^Spatial g)))
      (.attachChild pn n))
    root))
