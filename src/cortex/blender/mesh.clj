;; Generated from org/blender-mesh.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender.mesh
  "The base mesh of a Blender Mesh ID in any of the layouts Blender has
  saved since 2.4x, as plain data: vertex positions and polygons, each
  with its corners, material slot and smooth flag; then triangles.

  Entry points: `mesh-data`, `positions`, `face-triangles`, `uvs`,
  `triangle-count`."
  (:require [cortex.blender.file :as f])
  (:import [java.nio ByteBuffer]))

(set! *warn-on-reflection* true)

(defn- mesh-fail
  "Throw an ex-info naming the file and the mesh."
  [bf mesh msg]
  (f/fail (:source bf) (str "mesh " (pr-str (f/id-name mesh)) ": " msg)
          {:mesh (f/id-name mesh)}))

(defn- checked-bytes
  "The buffer offset of `n` elements of `size` bytes at pointer `ptr`,
  after checking the block holds them; nil for a NULL pointer."
  [bf mesh ptr n size what]
  (when-let [[off avail] (f/pointed-bytes bf ptr)]
    (when (or (neg? (long n)) (> (* (long n) (long size)) (long avail)))
      (mesh-fail bf mesh (str what " needs " n " x " size " bytes, its block has " avail)))
    off))

(defn- read-ints
  "`n` ints at pointer `ptr`, each `stride` bytes apart from `start`."
  [bf mesh ptr n stride start what]
  (when-let [off (checked-bytes bf mesh ptr n stride what)]
    (let [^ByteBuffer buf (:buf bf)
          out (int-array n)]
      (dotimes [i n]
        (aset out i (.getInt buf (int (+ (long off) (long start) (* i (long stride)))))))
      out)))

(defn- read-floats3
  "`n` float triples at `ptr`, `stride` bytes apart from `start`, as a
  flat float array of 3n."
  [bf mesh ptr n stride start what]
  (when-let [off (checked-bytes bf mesh ptr n stride what)]
    (let [^ByteBuffer buf (:buf bf)
          out (float-array (* 3 (long n)))]
      (dotimes [i n]
        (dotimes [k 3]
          (aset out (+ (* 3 i) k)
                (.getFloat buf (int (+ (long off) (long start) (* i (long stride)) (* 4 k)))))))
      out)))

(defn- read-small
  "`n` integers of `width` bytes (1, 2 or 4) at `ptr`, `stride` apart."
  [bf mesh ptr n stride start width what]
  (when-let [off (checked-bytes bf mesh ptr n stride what)]
    (let [^ByteBuffer buf (:buf bf)
          out (int-array n)]
      (dotimes [i n]
        (let [o (int (+ (long off) (long start) (* i (long stride))))]
          (aset out i (int (case (long width)
                             1 (.get buf o)
                             2 (.getShort buf o)
                             (.getInt buf o))))))
      out)))

(defn- cd-layers
  "The layers of CustomData `cd`: maps of :type, :name and :data."
  [bf cd]
  (vec (for [r (f/deref-array bf (f/fget cd "layers") "CustomDataLayer"
                              (or (f/fget cd "totlayer") 0))]
         {:type (f/fget r "type") :name (f/fget r "name") :data (f/fget r "data")})))

(defn- storage-attributes
  "The attributes of Blender 5.0's `Mesh.attribute_storage`, as maps of
  :name, :domain (0 point, 1 edge, 2 face, 3 corner), :single? and
  :data (the pointer to the values)."
  [bf mesh]
  (when-let [st (f/fget mesh "attribute_storage")]
    (vec (for [r (f/deref-array bf (f/fget st "dna_attributes") "Attribute"
                                (or (f/fget st "dna_attributes_num") 0))
               :let [single? (= 1 (f/fget r "storage_type"))
                     holder (f/deref-ptr bf (f/fget r "data")
                                         (if single? "AttributeSingle" "AttributeArray"))
                     name (when-let [[o a] (f/pointed-bytes bf (f/fget r "name"))]
                            (f/c-string bf o (min 1024 (long a))))]]
           {:name name :domain (f/fget r "domain") :single? single?
            :data (f/fget holder "data")}))))

(defn- named-data
  "The data pointer of the generic attribute `aname` on CustomData
  `cd-name` (3.5-4.x) or in the attribute storage with `domain` (5.0),
  as {:data ptr :single? bool}, or nil."
  [bf mesh attrs cd-name aname domain]
  (or (some #(when (and (= aname (:name %)) (= domain (:domain %))) %) attrs)
      (some #(when (= aname (:name %)) {:data (:data %) :single? false})
            (cd-layers bf (f/fget mesh cd-name)))))

(defn- struct-array
  "Pointer, stride and field offsets for a legacy struct array such as
  MVert or MPoly: {:ptr :stride :offsets {field offset}}, or nil."
  [bf ptr type-name fields]
  (when-let [lay (f/struct-layout bf type-name)]
    (when ptr
      {:ptr ptr :stride (:size lay)
       :fields (into {} (for [fl fields :let [fi (get-in lay [:by-name fl])] :when fi]
                          [fl fi]))})))

(defn- legacy-layer
  "The data pointer of the legacy CustomData layer of `type` (0 MVert,
  4 MFace, 25 MPoly, 26 MLoop) on `cd-name`, if the Mesh's own pointer
  field is missing."
  [bf mesh cd-name type]
  (some #(when (= type (:type %)) (:data %)) (cd-layers bf (f/fget mesh cd-name))))

(defn- field-ints
  "Read field `fl` (an int, short or char) of every element of struct
  array `sa`, `n` long."
  [bf mesh sa fl n what]
  (when-let [fi (get-in sa [:fields fl])]
    (read-small bf mesh (:ptr sa) n (:stride sa) (:offset fi) (:tlen fi) what)))

(defn positions
  "Vertex positions of `mesh` as a flat float array (x y z ...), from
  the 5.0 attribute storage, the `position` attribute (3.5-4.x) or the
  MVert array (2.4x-3.4)."
  [bf mesh attrs]
  (let [n (long (or (f/fget mesh "totvert") 0))]
    (if-let [{:keys [data]} (named-data bf mesh attrs "vdata" "position" 0)]
      (or (read-floats3 bf mesh data n 12 0 "position") (float-array 0))
      (let [ptr (or (f/fget mesh "mvert") (legacy-layer bf mesh "vdata" 0))
            sa (struct-array bf ptr "MVert" ["co"])]
        (or (when (and sa (get-in sa [:fields "co"]))
              (read-floats3 bf mesh ptr n (:stride sa) (get-in sa [:fields "co" :offset]) "MVert"))
            (float-array 0))))))

(defn- bools
  "A boolean attribute (one byte per element), as a boolean array, or
  nil when absent; a single value repeated for 5.0's single storage."
  [bf mesh attrs cd-name aname domain n]
  (when-let [{:keys [data single?]} (named-data bf mesh attrs cd-name aname domain)]
    (if single?
      (when-let [v (read-small bf mesh data 1 1 0 1 aname)]
        (boolean-array (repeat n (not (zero? (aget ^ints v 0))))))
      (when-let [^ints v (read-small bf mesh data n 1 0 1 aname)]
        (let [b (boolean-array n)]
          (dotimes [i n] (aset b i (not (zero? (aget v i)))))
          b)))))

(defn- ints-attr
  "An int attribute, or nil when absent."
  [bf mesh attrs cd-name aname domain n]
  (when-let [{:keys [data single?]} (named-data bf mesh attrs cd-name aname domain)]
    (if single?
      (when-let [v (read-ints bf mesh data 1 4 0 aname)]
        (int-array (repeat n (aget ^ints v 0))))
      (read-ints bf mesh data n 4 0 aname))))

(defn- negate
  "Smooth flags from `sharp_face` flags: their negation, or all smooth
  when the mesh has no such attribute."
  ^booleans [^booleans sharp np]
  (let [b (boolean-array np true)]
    (when sharp
      (dotimes [i (min (long np) (alength sharp))] (aset b i (not (aget sharp i)))))
    b))

(defn- polys-from-offsets
  "Faces from `poly_offset_indices` + `.corner_vert` (3.6 and later)."
  [bf mesh attrs]
  (let [np (long (or (f/fget mesh "totpoly") 0))
        nl (long (or (f/fget mesh "totloop") 0))
        offsets (read-ints bf mesh (f/fget mesh "poly_offset_indices") (inc np) 4 0
                           "face offsets")
        corners (ints-attr bf mesh attrs "ldata" ".corner_vert" 3 nl)
        mats (ints-attr bf mesh attrs "pdata" "material_index" 2 np)
        sharp (bools bf mesh attrs "pdata" "sharp_face" 2 np)]
    (when (and offsets corners)
      {:starts (java.util.Arrays/copyOf ^ints offsets (int np))
       :counts (let [^ints o offsets c (int-array np)]
                 (dotimes [i np] (aset c i (- (aget o (inc i)) (aget o i))))
                 c)
       :corners corners
       :mats (or mats (int-array np))
       :smooth (negate sharp np)})))

(defn- polys-from-mpoly
  "Faces from MPoly + MLoop (2.63-3.5), or MPoly with `.corner_vert`."
  [bf mesh attrs]
  (let [np (long (or (f/fget mesh "totpoly") 0))
        nl (long (or (f/fget mesh "totloop") 0))
        pptr (or (f/fget mesh "mpoly") (legacy-layer bf mesh "pdata" 25))
        lptr (or (f/fget mesh "mloop") (legacy-layer bf mesh "ldata" 26))
        mp (struct-array bf pptr "MPoly" ["loopstart" "totloop" "mat_nr" "flag"])
        ml (struct-array bf lptr "MLoop" ["v"])]
    (when (and mp (pos? np))
      (let [starts (field-ints bf mesh mp "loopstart" np "MPoly")
            counts (field-ints bf mesh mp "totloop" np "MPoly")
            corners (or (ints-attr bf mesh attrs "ldata" ".corner_vert" 3 nl)
                        (field-ints bf mesh ml "v" nl "MLoop"))
            mats (or (ints-attr bf mesh attrs "pdata" "material_index" 2 np)
                     (field-ints bf mesh mp "mat_nr" np "MPoly")
                     (int-array np))
            flags (field-ints bf mesh mp "flag" np "MPoly")
            sharp (bools bf mesh attrs "pdata" "sharp_face" 2 np)]
        (when (and starts counts corners)
          {:starts starts :counts counts :corners corners :mats mats
           :smooth (cond sharp (negate sharp np)
                         flags (let [^ints fl flags b (boolean-array np)]
                                 (dotimes [i np] (aset b i (boolean (odd? (aget fl i)))))
                                 b)
                         :else (boolean-array np))})))))

(defn- polys-from-mface
  "Faces from MFace (2.4x-2.62): triangles and quads, `v4` 0 for a
  triangle."
  [bf mesh]
  (let [nf (long (or (f/fget mesh "totface") 0))
        ptr (or (f/fget mesh "mface") (legacy-layer bf mesh "fdata" 4))
        mf (struct-array bf ptr "MFace" ["v1" "v2" "v3" "v4" "mat_nr" "flag"])]
    (when (and mf (pos? nf))
      (let [[v1 v2 v3 v4] (map #(field-ints bf mesh mf % nf "MFace") ["v1" "v2" "v3" "v4"])
            mats (or (field-ints bf mesh mf "mat_nr" nf "MFace") (int-array nf))
            flags (field-ints bf mesh mf "flag" nf "MFace")]
        (when (and v1 v2 v3 v4)
          (let [^ints v1 v1 ^ints v2 v2 ^ints v3 v3 ^ints v4 v4 ^ints flags flags
                counts (int-array nf)
                starts (int-array nf)
                corners (int-array (* 4 nf))
                smooth (boolean-array nf)
                used (loop [i 0 c 0]
                       (if (= i nf)
                         c
                         (let [quad? (not (zero? (aget v4 i)))]
                           (aset starts i (int c))
                           (aset counts i (int (if quad? 4 3)))
                           (aset corners c (aget v1 i))
                           (aset corners (+ c 1) (aget v2 i))
                           (aset corners (+ c 2) (aget v3 i))
                           (when quad? (aset corners (+ c 3) (aget v4 i)))
                           (when flags (aset smooth i (boolean (odd? (aget flags i)))))
                           (recur (inc i) (+ c (if quad? 4 3))))))]
            {:starts starts :counts counts :corners (java.util.Arrays/copyOf corners (int used))
             :mats mats :smooth smooth}))))))

(defn- check-polys
  "Every face must lie within the corner array and every corner name a
  vertex; a malformed file fails here, not later in an array index."
  [bf mesh {:keys [^ints starts ^ints counts ^ints corners] :as polys} nverts]
  (let [nc (alength corners)
        nverts (long nverts)]
    (dotimes [i (alength starts)]
      (let [s (aget starts i) n (aget counts i)]
        (when (or (neg? s) (neg? n) (> (+ s n) nc))
          (mesh-fail bf mesh (str "face " i " has corners " s ".." (+ s n)
                                  " of " nc)))))
    (dotimes [i nc]
      (let [v (aget corners i)]
        (when (or (neg? v) (>= v nverts))
          (mesh-fail bf mesh (str "corner " i " names vertex " v " of " nverts)))))
    polys))

(defn- floats-at
  "`n` groups of `k` floats at pointer `ptr`, `stride` bytes apart from
  `start`, flat; nil when the pointer dangles or its block is short
  (texture coordinates are optional, so they are dropped, not fatal)."
  [bf ptr n k stride start]
  (when-let [[off avail] (f/pointed-bytes bf ptr)]
    (let [n (long n) k (long k) stride (long stride) start (long start)]
      (when (and (>= n 0) (<= (+ (* (max 0 (dec n)) stride) start (* 4 k)) (long avail)))
        (let [^ByteBuffer buf (:buf bf)
              out (float-array (* n k))]
          (dotimes [i n]
            (dotimes [j k]
              (aset out (+ (* i k) j)
                    (.getFloat buf (int (+ (long off) start (* i stride) (* 4 j)))))))
          out)))))

(defn- uv-name?
  "Is `name` a user UV map's (not one of Blender's hidden `.` layers)?"
  [name]
  (and (string? name) (not (.startsWith ^String name "."))))

(defn uvs
  "Texture coordinates of the first UV map, two floats per face corner
  in the order of `corners`, or nil. They live in a float2 corner
  attribute (5.0 storage; `ldata` layer type 49 from 3.5), in MLoopUV
  structs (`ldata` type 16, 2.63-3.4) or in MTFace structs, four per
  face (`fdata` type 5, up to 2.62)."
  [bf mesh attrs {:keys [^ints starts ^ints counts ^ints corners]} from-mface?]
  (let [nc (alength corners)
        nl (long (or (f/fget mesh "totloop") 0))]
    (or
     (when-not from-mface?
       (or (some (fn [{:keys [name domain data single?]}]
                   (when (and (= 3 domain) (not single?) (uv-name? name)
                              (when-let [[_ avail] (f/pointed-bytes bf data)]
                                (= (long avail) (* 8 nl))))
                     (floats-at bf data nl 2 8 0)))
                 attrs)
           (some (fn [{:keys [type name data]}]
                   (case (long type)
                     49 (when (uv-name? name) (floats-at bf data nl 2 8 0))
                     16 (when-let [lay (f/struct-layout bf "MLoopUV")]
                          (when-let [fi (get-in lay [:by-name "uv"])]
                            (floats-at bf data nl 2 (:size lay) (:offset fi))))
                     nil))
                 (cd-layers bf (f/fget mesh "ldata")))))
     (when from-mface?
       (let [nf (alength starts)
             lay (f/struct-layout bf "MTFace")
             fi (get-in lay [:by-name "uv"])
             layer (some #(when (= 5 (:type %)) %) (cd-layers bf (f/fget mesh "fdata")))]
         (when (and lay fi layer)
           (when-let [^floats per-face (floats-at bf (:data layer) nf 8 (:size lay) (:offset fi))]
             (let [out (float-array (* 2 nc))]
               (dotimes [i nf]
                 (dotimes [k (aget counts i)]
                   (let [c (+ (aget starts i) k)]
                     (aset out (* 2 c) (aget per-face (+ (* 8 i) (* 2 k))))
                     (aset out (+ 1 (* 2 c)) (aget per-face (+ (* 8 i) (* 2 k) 1))))))
               out))))))))

(defn mesh-data
  "The base mesh of the Mesh struct `mesh`: {:name, :positions (flat
  floats, Blender coordinates), :starts :counts :corners (faces as runs
  of vertex indices), :mats (material slot per face), :smooth (per
  face), :uvs (two floats per corner, or nil)}. Faces come from the
  newest layout the file has."
  [bf mesh]
  (let [attrs (storage-attributes bf mesh)
        pos (positions bf mesh attrs)
        nverts (quot (alength ^floats pos) 3)
        loops (when (pos? (long (or (f/fget mesh "totpoly") 0)))
                (or (when (f/has-field? mesh "poly_offset_indices")
                      (polys-from-offsets bf mesh attrs))
                    (polys-from-mpoly bf mesh attrs)))
        polys (or loops
                  (polys-from-mface bf mesh)
                  {:starts (int-array 0) :counts (int-array 0) :corners (int-array 0)
                   :mats (int-array 0) :smooth (boolean-array 0)})
        polys (check-polys bf mesh polys nverts)]
    (assoc polys
           :name (f/id-name mesh)
           :positions pos
           :uvs (uvs bf mesh attrs polys (nil? loops)))))

(defn vertex
  "Vertex `i` of flat float array `pos` as a double array."
  ^doubles [^floats pos ^long i]
  (double-array [(aget pos (* 3 i)) (aget pos (+ 1 (* 3 i))) (aget pos (+ 2 (* 3 i)))]))

(defn newell-normal
  "The (unnormalised) Newell normal of the polygon through `pts`: its
  length is twice the area, its direction the side the corners wind
  counter-clockwise around."
  [pts]
  (let [n (count pts)]
    (loop [i 0 x 0.0 y 0.0 z 0.0]
      (if (= i n)
        [x y z]
        (let [^doubles a (nth pts i) ^doubles b (nth pts (mod (inc i) n))]
          (recur (inc i)
                 (+ x (* (- (aget a 1) (aget b 1)) (+ (aget a 2) (aget b 2))))
                 (+ y (* (- (aget a 2) (aget b 2)) (+ (aget a 0) (aget b 0))))
                 (+ z (* (- (aget a 0) (aget b 0)) (+ (aget a 1) (aget b 1))))))))))

(defn- cross2 ^double [[ax ay] [bx by] [cx cy]]
  (- (* (- (double bx) ax) (- (double cy) ay)) (* (- (double by) ay) (- (double cx) ax))))

(defn- inside?
  "Is 2-D point p inside or on triangle a b c (counter-clockwise)?"
  [p a b c]
  (and (>= (cross2 a b p) -1e-12) (>= (cross2 b c p) -1e-12) (>= (cross2 c a p) -1e-12)))

(defn- ring-2d
  "The corners `pts` projected onto the plane the polygon faces (the
  Newell normal's largest axis dropped), turned so they wind
  counter-clockwise."
  [pts]
  (let [[nx ny nz] (map #(Math/abs (double %)) (newell-normal pts))
        [u v] (cond (and (>= nx ny) (>= nx nz)) [1 2]
                    (>= ny nz) [2 0]
                    :else [0 1])
        p2 (mapv (fn [^doubles p] [(aget p u) (aget p v)]) pts)
        n (count pts)
        area (reduce + (map (fn [i] (let [[ax ay] (p2 i) [bx by] (p2 (mod (inc i) n))]
                                      (- (* (double ax) (double by)) (* (double bx) (double ay)))))
                            (range n)))]
    (if (neg? area) (mapv (fn [[a b]] [b a]) p2) p2)))

(defn- convex?
  "Does every corner of 2-D ring `p2` turn left (or go straight)?"
  [p2]
  (let [n (count p2)]
    (every? #(>= (cross2 (p2 %) (p2 (mod (inc %) n)) (p2 (mod (+ 2 %) n))) -1e-12)
            (range n))))

(defn- fan
  "Triangles fanning from the first of corners `ring`."
  [ring]
  (mapv (fn [i] [(ring 0) (ring i) (ring (inc i))]) (range 1 (dec (count ring)))))

(defn- ear-clip
  "Triangles of counter-clockwise 2-D ring `p2` by ear clipping: cut
  off a convex corner whose triangle holds no reflex corner, repeat.
  Fans what is left if no ear is found (a degenerate polygon)."
  [p2]
  (loop [ring (vec (range (count p2))) out []]
    (let [m (count ring)]
      (if (= m 3)
        (conj out ring)
        (let [turn (fn [k] (cross2 (p2 (ring (mod (dec k) m))) (p2 (ring k))
                                   (p2 (ring (mod (inc k) m)))))
              reflex (filterv #(<= (double (turn %)) 1e-12) (range m))
              ear (some (fn [k]
                          (let [a (ring (mod (dec k) m)) b (ring k) c (ring (mod (inc k) m))]
                            (when (and (> (double (turn k)) 1e-12)
                                       (not-any? #(let [r (ring %)]
                                                    (and (not= r a) (not= r b) (not= r c)
                                                         (inside? (p2 r) (p2 a) (p2 b) (p2 c))))
                                                 reflex))
                              k)))
                        (range m))]
          (if ear
            (recur (vec (concat (subvec ring 0 ear) (subvec ring (inc ear))))
                   (conj out [(ring (mod (dec ear) m)) (ring ear) (ring (mod (inc ear) m))]))
            (into out (fan ring))))))))

(defn triangulate
  "Triangles of a polygon with corners `pts` (3-D double arrays), as
  index triples into `pts` keeping the polygon's winding: convex
  polygons are fanned, concave ones of up to 256 corners ear-clipped
  in the plane they face (as Blender's polyfill does), bigger ones
  fanned to bound the time. Always n-2 triangles for n corners."
  [pts]
  (let [n (count pts)]
    (cond
      (< n 3) []
      (= n 3) [[0 1 2]]
      :else (let [p2 (ring-2d pts)]
              (if (or (> n 256) (convex? p2))
                (fan (vec (range n)))
                (ear-clip p2))))))

(defn face-normal!
  "Write into `out` the Newell normal of the face whose corners are
  `corners[s..s+n)`, vertices in flat `pos`; no allocation, for the
  mesh builder's inner loop."
  ^doubles [^floats pos ^ints corners s n ^doubles out]
  (let [s (int s) n (int n)]
   (loop [i (int 0) x 0.0 y 0.0 z 0.0]
    (if (= i n)
      (doto out (aset 0 x) (aset 1 y) (aset 2 z))
      (let [j (unchecked-inc-int i)
            a (unchecked-multiply-int 3 (aget corners (unchecked-add-int s i)))
            b (unchecked-multiply-int 3 (aget corners (unchecked-add-int s (if (= j n) (int 0) j))))
            ax (aget pos a) ay (aget pos (+ a 1)) az (aget pos (+ a 2))
            bx (aget pos b) by (aget pos (+ b 1)) bz (aget pos (+ b 2))]
        (recur j
               (+ x (* (- ay by) (+ az bz)))
               (+ y (* (- az bz) (+ ax bx)))
               (+ z (* (- ax bx) (+ ay by)))))))))

(defn- tri-dot
  "Dot product of normal `nrm` with the normal of triangle a b c
  (vertex indices into flat `pos`)."
  [^floats pos ^doubles nrm a b c]
  (let [a (* 3 (long a)) b (* 3 (long b)) c (* 3 (long c))
        ux (- (aget pos b) (aget pos a)) uy (- (aget pos (+ b 1)) (aget pos (+ a 1)))
        uz (- (aget pos (+ b 2)) (aget pos (+ a 2)))
        vx (- (aget pos c) (aget pos a)) vy (- (aget pos (+ c 1)) (aget pos (+ a 1)))
        vz (- (aget pos (+ c 2)) (aget pos (+ a 2)))]
    (+ (* (aget nrm 0) (- (* uy vz) (* uz vy)))
       (* (aget nrm 1) (- (* uz vx) (* ux vz)))
       (* (aget nrm 2) (- (* ux vy) (* uy vx))))))

(defn face-triangles
  "Triangles of face `f` of mesh data `md` as corner triples (0-based
  within the face). Triangles as they are; a quad is split along the
  diagonal that leaves both halves facing the face's way (right for
  concave quads too); bigger faces go to `triangulate`."
  [{:keys [^floats positions ^ints starts ^ints counts ^ints corners]} ^long f ^doubles nrm]
  (let [s (aget starts f) n (aget counts f)]
    (case n
      3 [[0 1 2]]
      4 (let [v (fn [^long k] (long (aget corners (+ s k))))]
          (if (and (pos? (tri-dot positions nrm (v 0) (v 1) (v 2)))
                   (pos? (tri-dot positions nrm (v 0) (v 2) (v 3))))
            [[0 1 2] [0 2 3]]
            [[1 2 3] [1 3 0]]))
      (if (< n 3)
        []
        (triangulate (mapv #(vertex positions (aget corners (+ s (long %)))) (range n)))))))

(defn triangle-count
  "How many triangles the faces of mesh data `md` make: n-2 per face of
  n >= 3 corners."
  [{:keys [^ints counts]}]
  (reduce + (map #(max 0 (- (long %) 2)) counts)))

(defn mirrored
  "Mesh data `mesh` (see `mesh-data`) and a mirrored copy of it: vertex
  i's copy is (reflect [x y z]) of it; with `merge?`, a vertex nearer
  than `tolerance` to its own copy is its own copy, moved half way to
  it, and a copied face whose corners are all such is left out. Each
  copied face keeps its first corner and runs through the others
  backwards; the copies keep their faces' material slots, smoothing and
  UVs."
  [{:keys [^floats positions ^ints starts ^ints counts ^ints corners ^ints mats
           ^booleans smooth ^floats uvs] :as mesh}
   reflect merge? tolerance]
  (let [n (quot (alength positions) 3)
        at (fn [i k] (double (aget positions (+ (* 3 (long i)) (long k)))))
        originals (mapv (fn [i] [(at i 0) (at i 1) (at i 2)]) (range n))
        copies (mapv #(mapv double (reflect %)) originals)
        own (mapv (fn [v c] (and merge? (< (reduce + (map #(let [d (- (double %1) (double %2))] (* d d)) v c))
                                           (* (double tolerance) (double tolerance)))))
                  originals copies)
        ;; where each vertex's copy is: itself, or the next new vertex
        [copy-of added] (reduce (fn [[m added] i]
                                  (if (own i)
                                    [(conj m i) added]
                                    [(conj m (+ n (count added))) (conj added i)]))
                                [[] []] (range n))
        ;; the faces copied, and the corners of each in its copy's order
        kept (filterv (fn [f] (let [s (aget starts (int f))]
                                (not-every? #(own (aget corners (+ s (long %)))) (range (aget counts (int f))))))
                      (range (alength counts)))
        order (fn [f] (let [s (aget starts (int f)) c (aget counts (int f))]
                        (cons s (map #(+ s (- c 1 (long %))) (range (dec c))))))
        copied (vec (mapcat order kept))
        kept-counts (map #(aget counts (int %)) kept)]
    (assoc mesh
           :positions (float-array (concat (mapcat (fn [v c o] (if o (map #(/ (+ (double %1) (double %2)) 2.0) v c) v))
                                                   originals copies own)
                                           (mapcat copies added)))
           :starts (int-array (concat starts (butlast (reductions + (alength corners) kept-counts))))
           :counts (int-array (concat counts kept-counts))
           :corners (int-array (concat corners (map #(copy-of (aget corners (int %))) copied)))
           :mats (int-array (concat mats (map #(aget mats (int %)) kept)))
           :smooth (boolean-array (concat smooth (map #(aget smooth (int %)) kept)))
           :uvs (when uvs
                  (float-array (concat uvs (mapcat #(vector (aget uvs (* 2 (long %)))
                                                            (aget uvs (+ 1 (* 2 (long %)))))
                                                   copied)))))))
