;; Generated from org/blender.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender.jme
  "Scene data (see cortex.blender.scene) as a jME scene graph shaped as
  jme3-blender shapes it: root Node, scene Node, a Node per object
  parented as in Blender, a Geometry per material under each mesh
  object's Node.

  Entry points: `scene-graph` (scene data to a Node), `material`,
  `set-user-data!`."
  (:require [cortex.blender.math :as m]
            [cortex.blender.mesh :as mesh]
            [cortex.blender.rigid-body :as physics]
            [cortex.blender.scene :as scene]
            [cortex.sense :as sense]
            [cortex.util :as util :refer [vec3]])
  (:import [com.jme3.scene Node Geometry Mesh VertexBuffer$Type Spatial]
           [com.jme3.math Vector3f Quaternion Matrix3f ColorRGBA Transform]
           [com.jme3.material Material RenderState$FaceCullMode]
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

(defn- quat
  "A jME Quaternion from a 3x3 rotation (rows)."
  ^Quaternion [r]
  (let [[[a b c] [d e f] [g h i]] r]
    (.normalizeLocal
     (.fromRotationMatrix (Quaternion.)
                          (Matrix3f. (float a) (float b) (float c)
                                     (float d) (float e) (float f)
                                     (float g) (float h) (float i))))))

(defn- trs->transform
  "A jME Transform of world-trs map `t`."
  ^Transform [t]
  (Transform. (vec3 (:translation t)) (quat (:rotation t)) (vec3 (:scale t))))

(defn- local-transform
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

(defn- user-value
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

(defn- keep-user-data!
  "Store each of `data` (user data name -> Clojure value) on spatial
  `s` as it is (see cortex.blender.rigid-body for the names)."
  [^Spatial s data]
  (doseq [[k v] data :when (some? v)]
    (.setUserData s ^String k v))
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

(defn- vertex-normals
  "For each vertex, the sum of the (area-weighted) Newell normals of the
  smooth faces around it, as a flat double array; normalised when
  used."
  ^doubles [{:keys [^floats positions ^ints starts ^ints counts ^ints corners ^booleans smooth]}]
  (let [acc (double-array (alength positions))
        nrm (double-array 3)]
    (dotimes [i (alength starts)]
      (when (aget smooth i)
        (let [s (aget starts i) n (aget counts i)]
          (mesh/face-normal! positions corners s n nrm)
          (let [x (aget nrm 0) y (aget nrm 1) z (aget nrm 2)]
            (dotimes [k n]
              (let [v (unchecked-multiply-int 3 (aget corners (unchecked-add-int s (int k))))
                    v1 (unchecked-inc-int v)
                    v2 (unchecked-inc-int v1)]
                (aset acc v (+ (aget acc v) x))
                (aset acc v1 (+ (aget acc v1) y))
                (aset acc v2 (+ (aget acc v2) z))))))))
    acc))

(defn- put3!
  "Write 3x3 `m` (flat, rows) times (x y z), normalised when `unit?`,
  into float array `out` at `i`."
  [^doubles m ^floats out i ^doubles v unit?]
  (let [i (long i)
        x (aget v 0) y (aget v 1) z (aget v 2)
        rx (+ (* (aget m 0) x) (* (aget m 1) y) (* (aget m 2) z))
        ry (+ (* (aget m 3) x) (* (aget m 4) y) (* (aget m 5) z))
        rz (+ (* (aget m 6) x) (* (aget m 7) y) (* (aget m 8) z))
        l (if unit? (Math/sqrt (+ (* rx rx) (* ry ry) (* rz rz))) 1.0)
        l (if (> l 1e-30) l 1.0)]
    (aset out i (float (/ rx l)))
    (aset out (+ i 1) (float (/ ry l)))
    (aset out (+ i 2) (float (/ rz l)))))

(defn- mesh-buffers
  "Position, normal, texture coordinate (when there are UVs) and index
  arrays for faces `face-ids` of mesh data `md`: a vertex per face
  corner (so flat faces keep their own normal;
  smooth ones get their vertex's), positions mapped by 3x3 `pm`
  (Blender to Y up, and any residual) and normals by `nm`."
  [md face-ids pm nm]
  (let [{:keys [^floats positions ^ints starts ^ints counts ^ints corners ^booleans smooth]} md
        pm (double-array (flatten pm))
        nm (double-array (flatten nm))
        ^doubles vnorm (when (some #(aget smooth (int %)) face-ids) (vertex-normals md))
        nverts (reduce + (map #(aget counts (int %)) face-ids))
        ntris (reduce + (map #(max 0 (- (aget counts (int %)) 2)) face-ids))
        ^floats uvs (:uvs md)
        pos (float-array (* 3 nverts))
        nor (float-array (* 3 nverts))
        tex (when uvs (float-array (* 2 nverts)))
        idx (int-array (* 3 ntris))
        fnrm (double-array 3)
        v3 (double-array 3)]
    (loop [[f & more] face-ids vbase 0 tbase 0]
      (if (nil? f)
        {:positions pos :normals nor :texcoords tex :indices idx}
        (let [f (long f)
              s (aget starts f) n (aget counts f)
              _ (mesh/face-normal! positions corners s n fnrm)
              tris (mesh/face-triangles md f fnrm)
              smooth? (aget smooth f)]
          (dotimes [k n]
            (let [v (* 3 (aget corners (+ s k)))
                  o (* 3 (+ vbase k))]
              (dotimes [d 3] (aset v3 d (double (aget positions (+ v d)))))
              (put3! pm pos o v3 false)
              (when tex
                (aset tex (* 2 (+ vbase k)) (aget uvs (* 2 (+ s k))))
                (aset tex (+ 1 (* 2 (+ vbase k))) (aget uvs (+ 1 (* 2 (+ s k))))))
              (if smooth?
                (do (dotimes [d 3] (aset v3 d (aget vnorm (+ v d))))
                    (put3! nm nor o v3 true))
                (put3! nm nor o fnrm true))))
          (let [tend (loop [[[a b c] & ts] tris t tbase]
                       (if (nil? a)
                         t
                         (let [o (* 3 t)]
                           (aset idx o (int (+ vbase (long a))))
                           (aset idx (+ o 1) (int (+ vbase (long b))))
                           (aset idx (+ o 2) (int (+ vbase (long c))))
                           (recur ts (inc t)))))]
            (recur more (+ vbase n) (long tend))))))))

(defn- jme-mesh
  "A jME Mesh of the arrays from `mesh-buffers` (texture coordinates
  when the mesh has a UV map)."
  ^Mesh [{:keys [^floats positions ^floats normals ^floats texcoords ^ints indices]}]
  (let [m (Mesh.)]
    (.setBuffer m VertexBuffer$Type/Position 3 (BufferUtils/createFloatBuffer positions))
    (.setBuffer m VertexBuffer$Type/Normal 3 (BufferUtils/createFloatBuffer normals))
    (when texcoords
      (.setBuffer m VertexBuffer$Type/TexCoord 2 (BufferUtils/createFloatBuffer texcoords)))
    (.setBuffer m VertexBuffer$Type/Index 3 (BufferUtils/createIntBuffer indices))
    (.updateBound m)
    (.updateCounts m)
    m))

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

(defn- open?
  "Has mesh data `md` an edge that only one face uses (a plane, a fin, a
  bowl): a surface whose back can be seen?"
  [{:keys [^ints starts ^ints counts ^ints corners]}]
  ;; every face's edges as longs (lower vertex, higher vertex), sorted:
  ;; an edge one face uses is a run of one
  (let [total (long (loop [f 0 t 0] (if (< f (alength counts)) (recur (inc f) (+ t (aget counts f))) t)))
        edges (long-array total)]
    (loop [f 0 i 0]
      (when (< f (alength counts))
        (let [s (aget starts f) n (aget counts f)]
          (dotimes [k n]
            (let [a (aget corners (+ s k)) b (aget corners (+ s (rem (inc k) n)))]
              (aset edges (+ i k) (+ (* (long (min a b)) 4294967296) (long (max a b))))))
          (recur (inc f) (+ i n)))))
    (java.util.Arrays/sort edges)
    (loop [i 0]
      (if (>= i total)
        false
        (let [j (long (loop [j (inc i)]
                        (if (and (< j total) (== (aget edges j) (aget edges i))) (recur (inc j)) j)))]
          (if (== j (inc i)) true (recur j)))))))

(defn- geometries
  "The Geometries of a mesh object: one per material slot its faces use
  (slot numbers clamped to the slots there are, as Blender does), in
  slot order, named object name + 1, 2, ... as jme3-blender names them.
  Vertices are in the object's frame, Y up, with `residual` (if any)
  baked in so that they land where Blender puts them. An open mesh
  (see `open?`) is drawn on both sides, as Blender draws it."
  [am {:keys [name mesh materials color]} residual]
  (let [nslots (count materials)
        both-sides? (open? mesh)
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
                (let [mat (material am (or (:color (get materials slot)) color))]
                  (when both-sides?
                    (.setFaceCullMode (.getAdditionalRenderState mat) RenderState$FaceCullMode/Off))
                  (.setMaterial g mat)))
              g))
          (sort (keys by-slot))))))

(defn scene-graph
  "A jME Node named `root-name` holding a Node named as the scene, under
  which each object of scene data `sd` is a Node named as the object,
  parented as in Blender, whose world transform is the object's world
  matrix in Y-up. Mesh objects get Geometry children; custom
  properties become user data, plus \"blender-type\" (MESH, EMPTY,
  LIGHT, CAMERA, ...) unless a property of that name exists, plus the
  object's Blender physics (see cortex.blender.rigid-body/user-data),
  as it is, and a camera's settings (see
  cortex.blender.scene/camera-data) under cortex.sense/camera-key, and
  a mesh's unapplied modifiers (see cortex.blender.scene/unapplied)
  under cortex.sense/modifiers-key. The scene Node carries the scene's Rigid Body World, when
  it has one, as user data cortex.blender.rigid-body/world-key.
  Materials are made with asset manager `am` (none when nil)."
  ^Node [am root-name sd]
  (let [root (Node. (str root-name))
        scene (keep-user-data! (Node. (str (:scene sd)))
                               {physics/world-key (:rigid-body-world sd)})
        objects (:objects sd)
        trs (into {} (map (fn [o] [(:key o) (world-trs (:world o))])) objects)
        xf (into {} (map (fn [[k t]] [k (trs->transform t)])) trs)
        nodes (into {} (for [o objects]
                         [(:key o)
                          (let [n (Node. (str (:name o)))]
                            (set-user-data! n (:properties o))
                            (keep-user-data! n (:physics o))
                            (keep-user-data! n {sense/camera-key (:camera o)
                                                sense/modifiers-key (not-empty (scene/unapplied o))})
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
