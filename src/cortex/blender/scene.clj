;; Generated from org/blender-scene.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender.scene
  "The objects of a .blend file's scene as plain data: names, types,
  parents, world matrices rebuilt from each object's own transform
  fields, custom properties and material colours.

  Entry points: `scene-data` (a parsed file's scene as data, the saved
  scene or one chosen by name), `scene-list` (a file's scenes),
  `armature-poses` (bones posed as Blender poses them),
  `current-scene`, `scene-objects`, `properties`."
  (:require [clojure.string :as str]
            [cortex.blender.file :as f]
            [cortex.blender.math :as m]
            [cortex.blender.mesh :as mesh]
            [cortex.blender.rigid-body :as physics]
            [cortex.sense :as sense]))

(set! *warn-on-reflection* true)

(def object-types
  "Blender's object type codes, named as Blender's Python API names
  them (`Object.type`)."
  {0 "EMPTY" 1 "MESH" 2 "CURVE" 3 "SURFACE" 4 "FONT" 5 "META" 10 "LIGHT"
   11 "CAMERA" 12 "SPEAKER" 13 "LIGHT_PROBE" 22 "LATTICE" 25 "ARMATURE"
   26 "GPENCIL" 27 "CURVES" 28 "POINTCLOUD" 29 "VOLUME" 30 "GREASEPENCIL"})

(def rotation-modes
  "Blender's `rotmode` codes as its Python API names them."
  {0 "QUATERNION" -1 "AXIS_ANGLE" 1 "XYZ" 2 "XZY" 3 "YXZ" 4 "YZX" 5 "ZXY" 6 "ZYX"})

(defn- field-any
  "The first of fields `names` the struct has (file names change:
  `size` is `scale` in newer sources but stays `size` in files)."
  [r names]
  (some #(when (f/has-field? r %) (f/fget r %)) names))

(defn- rotation-matrix
  "An object's rotation as Blender's BKE_object_rot_to_mat3 builds it:
  delta rotation times rotation, each in the object's rotation mode
  (Euler orders 1..6, quaternion 0, axis-angle -1). Files from before
  rotation modes (2.4x) hold Euler XYZ `rot` plus `drot`."
  [ob]
  (let [mode (f/fget ob "rotmode")
        rot (or (f/fget ob "rot") [0 0 0])
        drot (or (f/fget ob "drot") [0 0 0])]
    (cond
      (nil? mode) (m/euler->mat3 (mapv + rot drot) 1)
      (pos? (long mode)) (m/mat-mul (m/euler->mat3 drot mode) (m/euler->mat3 rot mode))
      (= -1 (long mode)) (m/mat-mul (m/axis-angle->mat3 (or (f/fget ob "drotAxis") [0 1 0])
                                                        (or (f/fget ob "drotAngle") 0.0))
                                    (m/axis-angle->mat3 (or (f/fget ob "rotAxis") [0 1 0])
                                                        (or (f/fget ob "rotAngle") 0.0)))
      (zero? (long mode)) (m/mat-mul (m/quat->mat3 (or (f/fget ob "dquat") [1 0 0 0]))
                                     (m/quat->mat3 (or (f/fget ob "quat") [1 0 0 0])))
      :else (m/euler->mat3 rot 1))))

(defn- scale-vector
  "An object's scale with its delta: `size * dscale` (2.5x+), or
  `size + dsize` in files that only have `dsize`."
  [ob]
  (let [s (or (field-any ob ["size" "scale"]) [1 1 1])]
    (cond
      (f/has-field? ob "dscale") (mapv * s (f/fget ob "dscale"))
      (f/has-field? ob "dsize") (mapv + s (f/fget ob "dsize"))
      :else s)))

(defn- local-matrix
  "An object's matrix relative to its parent's (before `parentinv`),
  as BKE_object_to_mat4: rotation * scale, translated by loc + dloc."
  [ob]
  (let [loc (or (f/fget ob "loc") [0 0 0])
        dloc (or (f/fget ob "dloc") [0 0 0])]
    (m/mat3->mat4 (m/mat-mul (rotation-matrix ob) (m/scale->mat3 (scale-vector ob)))
                  (mapv + loc dloc))))

(def ^:private idp
  {0 :string 1 :int 2 :float 5 :array 6 :group 7 :id 8 :double 9 :idparray 10 :bool})

(declare idprop-value)

(defn- idprop-children
  "The IDProperty children of group `p`, walking its ListBase."
  [bf p]
  (f/list-seq bf (f/fget-in p ["data" "group"]) "IDProperty"))

(defn- idprop-array
  "The elements of IDP_ARRAY `p`: `len` values of its subtype."
  [bf p depth]
  (let [n (long (or (f/fget p "len") 0))
        sub (idp (f/fget p "subtype"))
        ptr (f/fget-in p ["data" "pointer"])
        [off avail] (f/pointed-bytes bf ptr)
        buf ^java.nio.ByteBuffer (:buf bf)
        width (case sub (:int :float) 4 :double 8 :bool 1 nil)]
    (cond
      (or (nil? off) (zero? n)) []
      width (do (when (or (neg? n) (> (* n (long width)) (long avail)))
                  (f/fail (:source bf) (str "property " (pr-str (f/fget p "name"))
                                            " claims " n " elements, its block has "
                                            avail " bytes")))
                (mapv (fn [i]
                        (let [o (int (+ (long off) (* (long i) (long width))))]
                          (case sub
                            :int (.getInt buf o)
                            :float (.getFloat buf o)
                            :double (.getDouble buf o)
                            :bool (not (zero? (.get buf o))))))
                      (range n)))
      (= sub :group) (mapv #(idprop-value bf % (inc (long depth)))
                           (f/deref-array bf ptr "IDProperty" n))
      :else [])))

(defn- idprop-value
  "The value of IDProperty `p` as Clojure data: strings, longs (int),
  floats, doubles, booleans, vectors (arrays), maps from name to value
  (groups), ID names (ID pointers). Nesting deeper than 64 is cut off,
  so a malicious file cannot recurse without end."
  [bf p depth]
  (when (< (long depth) 64)
    (let [type (idp (f/fget p "type"))
          data (f/fget p "data")
          val-off (f/field-offset data "val")
          buf ^java.nio.ByteBuffer (:buf bf)]
      (case type
        :string (let [[off avail] (f/pointed-bytes bf (f/fget data "pointer"))
                      n (min (long (or (f/fget p "len") 0)) (long (or avail 0)))]
                  (if off (f/c-string bf off (max 0 n)) ""))
        :int (f/fget data "val")
        :bool (not (zero? (long (f/fget data "val"))))
        :float (.getFloat buf (int val-off))
        :double (.getDouble buf (int val-off))
        :array (idprop-array bf p depth)
        :group (into {} (for [c (idprop-children bf p)
                              :let [v (idprop-value bf c (inc (long depth)))]
                              :when (some? v)]
                          [(f/fget c "name") v]))
        :idparray (vec (keep #(idprop-value bf % (inc (long depth)))
                             (f/deref-array bf (f/fget data "pointer") "IDProperty"
                                            (long (or (f/fget p "len") 0)))))
        :id (some-> (f/deref-ptr bf (f/fget data "pointer")) f/id-name)
        nil))))

(defn properties
  "The custom properties of ID struct `id-ref` as a map from name to
  value; Blender's own bookkeeping group `_RNA_UI` (2.x) is left out."
  [bf id-ref]
  (let [p (f/deref-ptr bf (f/fget-in id-ref ["id" "properties"]) "IDProperty")]
    (if (and p (= :group (idp (f/fget p "type"))))
      (dissoc (idprop-value bf p 0) "_RNA_UI")
      {})))

(defn- pointer-array
  "`n` pointers stored at pointer `ptr` (a `**mat` array)."
  [bf ptr n]
  (when-let [[off avail g] (f/pointed-bytes bf ptr)]
    (let [ps (long (:ptr-size bf))]
      (mapv #(f/read-ptr bf (+ (long off) (* ps (long %))) g)
            (range (min (long n) (quot (long avail) ps)))))))

(defn- material-color
  "A material's colour [r g b a]: its diffuse colour (2.4x-2.7x), its
  viewport display colour (2.8+, same fields)."
  [ma]
  [(or (f/fget ma "r") 0.8) (or (f/fget ma "g") 0.8) (or (f/fget ma "b") 0.8)
   (or (field-any ma ["a" "alpha"]) 1.0)])

(defn- material-slots
  "For each material slot of object `ob` with data `data`, the
  material's name and colour, or nil for an empty slot. A slot's
  material comes from the object when its `matbits` bit says so, else
  from the object data, as Blender's BKE_object_material_get does."
  [bf ob data]
  (let [n (long (or (f/fget ob "totcol") 0))
        n (min n 1024)
        ob-mats (pointer-array bf (f/fget ob "mat") n)
        bits (when-let [[off avail] (f/pointed-bytes bf (f/fget ob "matbits"))]
               (mapv #(.get ^java.nio.ByteBuffer (:buf bf) (int (+ (long off) (long %))))
                     (range (min n (long avail)))))
        dn (long (or (f/fget data "totcol") 0))
        data-mats (pointer-array bf (f/fget data "mat") (min dn 1024))]
    (vec (for [i (range (max n (min dn 1024)))
               :let [p (if (and (pos? (long (get bits i 0))) (get ob-mats i))
                         (get ob-mats i)
                         (get data-mats i))
                     ma (f/deref-ptr bf p "Material")]]
           (when ma {:name (f/id-name ma) :color (material-color ma)})))))

(def camera-types
  "Blender's camera `type` codes."
  {0 :perspective 1 :orthographic 2 :panoramic})

(def sensor-fits
  "Blender's camera `sensor_fit` codes."
  {0 :auto 1 :horizontal 2 :vertical})

(defn camera-data
  "What the reader keeps of Camera struct `cam`: {:type (:perspective,
  :orthographic, :panoramic) :lens :sensor-width :sensor-height
  :sensor-fit (:auto, :horizontal, :vertical) :clip-start :clip-end
  :ortho-scale :shift-x :shift-y}, numbers as doubles, lengths in
  millimetres (lens, sensor) or Blender units."
  [cam]
  (let [number (fn [names default]
                 (double (or (field-any cam names) default)))]
    {:type (camera-types (f/fget cam "type") :unknown)
     :lens (number ["lens"] 50.0)
     :sensor-width (number ["sensor_x"] 36.0)
     :sensor-height (number ["sensor_y"] 24.0)
     :sensor-fit (sensor-fits (f/fget cam "sensor_fit") :auto)
     :clip-start (number ["clipsta" "clip_start"] 0.1)
     :clip-end (number ["clipend" "clip_end"] 100.0)
     :ortho-scale (number ["ortho_scale"] 7.0)
     :shift-x (number ["shiftx" "shift_x"] 0.0)
     :shift-y (number ["shifty" "shift_y"] 0.0)}))

(defn- file-global
  "The FileGlobal struct of the `GLOB` block, or nil."
  [bf]
  (some->> (f/blocks-with-code bf "GLOB") first (f/block-ref bf)))

(defn current-scene
  "The scene the file was saved showing (`FileGlobal.curscene`), else
  the first scene."
  [bf]
  (or (f/deref-ptr bf (f/fget (file-global bf) "curscene") "Scene")
      (some->> (f/blocks-with-code bf "SC") first (f/block-ref bf))))

(defn- collection-objects
  "Object pointers of collection `c` and its children, depth first,
  each collection visited once."
  [bf c]
  (loop [stack [c] seen #{} out []]
    (if-let [c (peek stack)]
      (let [stack (pop stack)
            k (.offset ^cortex.blender.file.Ref c)]
        (if (seen k)
          (recur stack seen out)
          (let [obs (keep #(f/deref-ptr bf (f/fget % "ob") "Object")
                          (f/list-seq bf (f/fget c "gobject") "CollectionObject"))
                kids (keep #(f/deref-ptr bf (f/fget % "collection") "Collection")
                           (f/list-seq bf (f/fget c "children") "CollectionChild"))]
            (recur (into stack (reverse kids)) (conj seen k) (into out obs)))))
      out)))

(defn scene-objects
  "The Object structs of scene `sc`: its master collection's tree
  (2.8+) or its `base` list (before 2.8), in order, without repeats."
  [bf sc]
  (let [from-collections (when-let [mc (f/deref-ptr bf (f/fget sc "master_collection") "Collection")]
                           (collection-objects bf mc))
        from-bases (keep #(f/deref-ptr bf (f/fget % "object") "Object")
                         (f/list-seq bf (f/fget sc "base") "Base"))
        all (concat from-collections from-bases)]
    (first (reduce (fn [[out seen] r]
                     (if (seen (:offset r)) [out seen] [(conj out r) (conj seen (:offset r))]))
                   [[] #{}] all))))

(def ^:private bone-bits
  "Bits of a Bone's `flag` (eBone_Flag) that change how its pose is
  computed."
  {:connected 4 :hinge 9 :no-scale 15 :no-local-location 22 :relative-parenting 23})

(defn- bones
  "Every Bone of armature `arm` (`bonebase`, then each bone's
  `childbase`), each with the name of its parent bone, parents first,
  each visited once."
  [bf arm]
  (loop [todo (mapv #(vector % nil) (f/list-seq bf (f/fget arm "bonebase") "Bone"))
         seen #{} out []]
    (if-let [[b parent] (first todo)]
      (if (seen (:offset b))
        (recur (subvec todo 1) seen out)
        (let [kids (mapv #(vector % (f/fget b "name"))
                         (f/list-seq bf (f/fget b "childbase") "Bone"))]
          (recur (into (subvec todo 1) kids) (conj seen (:offset b))
                 (conj out [b parent]))))
      out)))

(defn- channel-matrix
  "A pose channel's own matrix, as Blender's BKE_pchan_to_mat4:
  rotation (its rotation mode: Euler 1..6, quaternion 0, axis-angle
  -1) times scale, translated by its location unless the bone is
  connected to its parent."
  [pchan connected?]
  (let [mode (long (or (f/fget pchan "rotmode") 0))
        rot (cond
              (pos? mode) (m/euler->mat3 (or (f/fget pchan "eul") [0 0 0]) mode)
              (= -1 mode) (m/axis-angle->mat3 (or (f/fget pchan "rotAxis") [0 1 0])
                                              (or (f/fget pchan "rotAngle") 0.0))
              :else (m/quat->mat3 (or (f/fget pchan "quat") [1 0 0 0])))
        size (or (field-any pchan ["size" "scale"]) [1 1 1])]
    (m/mat3->mat4 (m/mat-mul rot (m/scale->mat3 size))
                  (if connected? [0 0 0] (or (f/fget pchan "loc") [0 0 0])))))

(defn- driven-bones
  "The names of the bones that drivers of armature object `par` drive
  (F-Curves of its animation data whose path is pose.bones[\"name\"]...)."
  [bf par]
  (let [adt (f/deref-ptr bf (f/fget par "adt") "AnimData")]
    (set (for [fc (f/list-seq bf (f/fget adt "drivers") "FCurve")
               :let [[off n] (f/pointed-bytes bf (f/fget fc "rna_path"))
                     path (when off (f/c-string bf off (min 4096 (long n))))
                     [_ bone] (when path (re-find #"pose\.bones\[\"([^\"]*)\"\]" path))]
               :when bone]
           bone))))

(defn armature-poses
  "The pose of every bone of armature object `par`, computed as Blender
  computes it for bones without constraints or drivers (see above):
  {:poses {bone-name {:matrix 4x4 (armature frame) :length :relative?}}
  :warnings [...]}. A bone with constraints, drivers or an inheritance
  mode other than the full one, and the bones under it, keep the pose
  matrix the file saved, with a warning naming the bone."
  [bf par]
  (let [arm (f/deref-ptr bf (f/fget par "data") "bArmature")
        pose (f/deref-ptr bf (f/fget par "pose") "bPose")
        chans (into {} (map (juxt #(f/fget % "name") identity))
                    (f/list-seq bf (f/fget pose "chanbase") "bPoseChannel"))
        rest? (bit-test (long (or (f/fget arm "flag") 0)) 0)
        driven (driven-bones bf par)
        arm-name (f/id-name par)]
    (reduce
     (fn [{:keys [poses] :as acc} [b parent]]
       (let [name (f/fget b "name")
             flag (long (or (f/fget b "flag") 0))
             bit #(bit-test flag (long (bone-bits %)))
             pchan (chans name)
             parent-pose (get poses parent)
             saved (some-> (f/fget pchan "pose_mat") m/from-blender)
             why (cond
                   rest? nil
                   (seq (f/list-seq bf (f/fget pchan "constraints"))) "has constraints"
                   (driven name) "has drivers"
                   (or (bit :hinge) (bit :no-local-location)
                       (pos? (long (or (f/fget b "inherit_scale_mode") 0)))
                       (and (not (f/has-field? b "inherit_scale_mode")) (bit :no-scale)))
                   "does not inherit its parent's full transform")
             chan (if (or rest? (nil? pchan)) (m/identity-matrix 4) (channel-matrix pchan (bit :connected)))
             offset (if parent-pose
                      (let [head (or (f/fget b "head") [0 0 0])
                            plen (double (:length parent-pose))]
                        (m/mat3->mat4 (m/mat4->mat3 (m/from-blender (f/fget b "bone_mat")))
                                      (update (vec head) 1 #(+ (double %) plen))))
                      (m/from-blender (f/fget b "arm_mat")))
             computed (m/mat-mul (if parent-pose (m/mat-mul (:matrix parent-pose) offset) offset)
                                 chan)
             use-saved? (and why saved)]
         (-> acc
             (assoc-in [:poses name]
                       {:matrix (if use-saved? saved computed)
                        :chan chan
                        :saved? (boolean use-saved?)
                        :relative? (bit :relative-parenting)
                        :length (double (or (f/fget b "length") 0.0))})
             (cond-> use-saved?
               (update :warnings conj
                       (str "bone " (pr-str name) " of armature " (pr-str arm-name) " " why
                            ": cortex does not evaluate that and uses the pose saved in the"
                            " file for it, which may be stale"))))))
     {:poses {} :warnings []}
     (if arm (bones bf arm) []))))

(def ^:private shapeless-modifiers
  "Kinds of modifier that leave a mesh's vertices where they are."
  #{"Collision" "Triangulate" "ParticleSystem" "NormalEdit" "WeightedNormal"
    "UVProject" "UVWarp" "WeightVGEdit" "WeightVGMix" "WeightVGProximity"})

(defn- mirror-settings
  "A Mirror modifier's settings from its struct `md`: :axes (x y z,
  each mirrored or not), :merge?, :tolerance (how near a vertex and its
  copy merge), :bisect? (whether it cuts the mesh at the plane first)
  and :object-key (the object across whose axes it mirrors, or nil for
  the object's own). Bits of its flag as DNA_modifier_types.h has them."
  [bf md]
  (let [flag (long (or (f/fget md "flag") 0))
        bit? #(pos? (bit-and flag (long %)))]
    {:axes (mapv bit? [8 16 32])
     :merge? (not (bit? 128))
     :tolerance (double (or (f/fget md "tolerance") 0.001))
     :bisect? (boolean (some bit? [256 512 1024]))
     :object-key (:offset (f/deref-ptr bf (f/fget md "mirror_ob") "Object"))}))

(defn modifiers
  "The modifiers of Object struct `ob`, in their order: {:name, :kind
  (its struct's name less ModifierData), :viewport? (shown in the
  viewport), :reshapes? (whether it can move the mesh's vertices)},
  and a Mirror's :mirror settings (see `mirror-settings`)."
  [bf ob]
  (vec (for [md (f/list-seq bf (f/fget ob "modifiers"))
             :let [kind (str/replace (str (:name (:layout md))) #"ModifierData$" "")]]
         (cond-> {:name (str (f/fget-in md ["modifier" "name"]))
                  :kind kind
                  :viewport? (odd? (long (or (f/fget-in md ["modifier" "mode"]) 0)))
                  ;; an Armature modifier without its armature does nothing
                  :reshapes? (not (or (shapeless-modifiers kind)
                                      (and (= kind "Armature") (nil? (f/fget md "object")))))}
           (= kind "Mirror") (assoc :mirror (mirror-settings bf md))))))


(defn unapplied
  "The modifiers of object `o` (as scene-data gives it) that Blender
  shows and that can reshape its mesh, which the reader did not apply
  (see `with-mirrors`), and the shape keys in use, which it does not
  apply either: [{:name :kind}], with :why for a Mirror and a shape key
  (kind \"ShapeKey\"), empty for an object that is no mesh."
  [{:keys [type modifiers shape-keys]}]
  (if (= type "MESH")
    (into (vec (for [m modifiers
                     :when (and (:viewport? m) (:reshapes? m) (not (:applied? m)))]
                 (select-keys m [:name :kind :why])))
          (for [{:keys [name value]} shape-keys]
            {:name name :kind "ShapeKey" :why (format "at %.2f" (double value))}))
    []))

(defn- shape-keys
  "The shape keys of Mesh struct `mesh` that change what Blender shows:
  [{:name :value}] for each key after the first (the basis) whose value
  is not 0 and that is not muted (KEYBLOCK_MUTE)."
  [bf mesh]
  (let [key (f/deref-ptr bf (f/fget mesh "key") "Key")]
    (vec (for [kb (rest (f/list-seq bf (f/fget key "block") "KeyBlock"))
               :let [v (double (or (f/fget kb "curval") 0.0))]
               :when (and (not (zero? v)) (even? (long (or (f/fget kb "flag") 0))))]
           {:name (str (f/fget kb "name")) :value v}))))


(def ^:dynamic *mirror-budget*
  "The most vertices Mirror modifiers may make of one mesh: each axis
  doubles it, so a stack of them (a damaged file may hold dozens) would
  otherwise outgrow memory; Blender itself stalls long before."
  4000000)

(defn- with-mirrors
  "Object `o` with its `mesh` mirrored by each Mirror modifier Blender
  shows, in order, each marked :applied?; `worlds` gives objects' world
  matrices by key. A Mirror that bisects, whose mirror object's frame
  is not known here (no world matrix, or none that inverts), or that
  would make more than `*mirror-budget*` vertices, is left unapplied."
  [o mesh worlds]
  (let [world (worlds (:key o))
        inverse (some-> world m/affine-inverse)
        step (fn [[mesh done] {:keys [viewport? mirror] :as md}]
               (let [{:keys [axes merge? tolerance bisect? object-key]} mirror
                     ;; into the frame mirrored across, and back
                     to (when (and inverse object-key (worlds object-key))
                          (m/mat-mul inverse (worlds object-key)))
                     back (when to (m/affine-inverse to))
                     n (when mesh (quot (alength ^floats (:positions mesh)) 3))
                     too-many? (and n (> (* n (long (Math/pow 2 (count (filter true? axes)))))
                                         (long *mirror-budget*)))
                     ;; why a Mirror Blender shows is left as it is
                     why (cond (not (and mesh viewport? mirror)) nil
                               bisect? "it bisects"
                               too-many? (str "it would make more than " *mirror-budget* " vertices")
                               (and object-key (not back)) "its mirror object's frame is not known here")]
                 (if (and mesh viewport? mirror world (nil? why))
                   [(reduce (fn [mesh k]
                              (let [flip (fn [p] (update (vec p) k -))
                                    reflect (if to
                                              #(vec (take 3 (m/mat-vec to (flip (m/mat-vec back (conj (vec %) 1.0))))))
                                              flip)]
                                (mesh/mirrored mesh reflect merge? tolerance)))
                            mesh (filter #(nth axes %) [0 1 2]))
                    (conj done (assoc md :applied? true))]
                   [mesh (conj done (cond-> md why (assoc :why why)))])))
        [mesh mods] (reduce step [mesh []] (:modifiers o))]
    (assoc o :mesh mesh :modifiers mods)))

(defn- constraint-warning
  [{:keys [name constrained? stored-world]}]
  (when constrained?
    (str "object " (pr-str name) " has constraints, which the reader does not evaluate: "
         (if stored-world
           "it is placed by the world matrix the file saved, where Blender last drew it"
           (str "the file keeps no world matrix (Blender 4.5 on), so it is placed by its own location,"
                " rotation and scale; apply them in Blender (Object > Apply > Visual Transform)"
                " to place it as Blender shows")))))

(defn- modifier-warning
  [{:keys [name] :as o}]
  (when-let [ms (seq (unapplied o))]
    (str "object " (pr-str name) " has modifiers or shape keys the reader does not apply ("
         (sense/modifiers-text ms)
         "): it loads as Blender draws it with them off;"
         " apply them in Blender (Object > Convert > Mesh) to load what Blender shows")))

(defn- bone-matrix
  "For an object parented to a bone (partype 7): the bone's pose in its
  armature's frame (see `armature-poses`), moved from the bone's head
  to its tail, as Blender's ob_parbone does (or the bare channel matrix
  for a bone with relative parenting). {:matrix m :warnings [...]};
  :matrix is nil when the armature has no such bone."
  [bf ob]
  (let [par (f/deref-ptr bf (f/fget ob "parent") "Object")
        name (f/fget ob "parsubstr")
        {:keys [poses warnings]} (armature-poses bf par)]
    {:warnings warnings
     :matrix (when-let [{:keys [matrix length relative? chan]} (get poses name)]
               (if relative?
                 chan
                 (let [y (mapv #(nth % 1) (subvec matrix 0 3))
                       t (mapv + (m/translation matrix) (mapv #(* (double length) (double %)) y))]
                   (m/mat3->mat4 (m/mat4->mat3 matrix) t))))}))

(defn- object-info
  "What the reader keeps of the Object struct `ob`. Objects are known by
  :key, the byte offset of their struct in the file (old pointers are
  not unique in 5.0 files)."
  [bf ob]
  (let [type (object-types (f/fget ob "type") "UNKNOWN")
        data (f/deref-ptr bf (f/fget ob "data"))
        obmat (f/fget ob "obmat")]
    {:key (:offset ob)
     :name (f/id-name ob)
     :type type
     :rotation-mode (rotation-modes (f/fget ob "rotmode") "XYZ")
     :parent-key (:offset (f/deref-ptr bf (f/fget ob "parent") "Object"))
     :partype (bit-and (long (or (f/fget ob "partype") 0)) 15)
     :bone (when (= 7 (bit-and (long (or (f/fget ob "partype") 0)) 15))
             (bone-matrix bf ob))
     :local (local-matrix ob)
     :parentinv (m/from-blender (f/fget ob "parentinv"))
     :stored-world (when obmat (m/from-blender obmat))
     :properties (properties bf ob)
     :materials (material-slots bf ob data)
     :color (or (f/fget ob "col") [1.0 1.0 1.0 1.0])
     :modifiers (modifiers bf ob)
     :physics (physics/user-data bf ob)
     :camera (when (and (= type "CAMERA") data (= "Camera" (:name (:layout data))))
               (camera-data data))
     :shape-keys (if (and (= type "MESH") data (= "Mesh" (:name (:layout data)))) (shape-keys bf data) [])
     :constrained? (boolean (seq (f/list-seq bf (f/fget ob "constraints"))))
     :mesh-ref (when (and (= type "MESH") data (= "Mesh" (:name (:layout data)))) data)}))

(defn- world-matrices
  "Each object's world matrix, by key: parent's world * parentinv *
  local, as Blender's solve_parenting does for object parents, with the
  bone's matrix after the parent's for bone parents (partype 7). A
  parent cycle or a parent missing from `infos` counts as no parent.
  Vertex parents (partype 5, 6) need the parent mesh evaluated, and
  an object's constraints (see `object-info`'s :constrained?) their
  targets; for them, and for a bone that cannot be found, the world
  matrix the file stores is used when it has one."
  [infos]
  (let [by-key (into {} (map (juxt :key identity)) infos)]
    (loop [todo (map :key infos) done {}]
      (if-let [k (first todo)]
        (if (done k)
          (recur (rest todo) done)
          ;; walk up to the first ancestor already done, guarding cycles
          (let [chain (loop [q k chain [] seen #{}]
                        (if (or (nil? q) (done q) (seen q) (nil? (by-key q)))
                          chain
                          (recur (:parent-key (by-key q)) (conj chain q) (conj seen q))))
                done (reduce (fn [done q]
                               (let [{:keys [parent-key partype local parentinv stored-world
                                             bone constrained?]} (by-key q)
                                     bone-matrix (:matrix bone)
                                     pw (get done parent-key)]
                                 (assoc done q
                                        (cond
                                          (and constrained? stored-world) stored-world
                                          (and pw bone-matrix)
                                          (m/mat-mul (m/mat-mul (m/mat-mul pw bone-matrix) parentinv) local)
                                          (and (#{5 6 7} partype) stored-world) stored-world
                                          pw (m/mat-mul (m/mat-mul pw parentinv) local)
                                          :else local))))
                             done (reverse chain))]
            (recur (rest todo) done)))
        done))))

(defn- with-ancestors
  "`infos` plus the info of every ancestor they have outside it, so a
  child's world matrix includes parents that are not in the scene. At
  most as many rounds as the file has objects."
  [bf infos]
  (let [by-offset (into {} (for [b (f/blocks-with-code bf "OB")
                                 :let [r (f/block-ref bf b)] :when r]
                             [(:offset r) r]))]
    (loop [infos infos rounds (count by-offset)]
      (let [have (set (map :key infos))
            missing (distinct (remove #(or (nil? %) (have %)) (map :parent-key infos)))
            extra (keep #(some->> (by-offset %) (object-info bf)) missing)]
        (if (or (empty? extra) (neg? (long rounds)))
          infos
          (recur (into infos extra) (dec (long rounds))))))))

(defn- break-cycles
  "`infos` with parent links that close a cycle removed: walking up from
  each object in turn, a walk that comes back to the object cuts the
  object's own parent link. Each walk is at most as long as `infos`."
  [infos]
  (let [parent (into {} (map (juxt :key :parent-key)) infos)
        parent (reduce (fn [parent k]
                         (loop [q (parent k) steps 0]
                           (cond
                             (or (nil? q) (> steps (count parent))) parent
                             (= q k) (assoc parent k nil)
                             :else (recur (parent q) (inc steps)))))
                       parent (map :key infos))]
    (mapv #(assoc % :parent-key (parent (:key %))) infos)))

(defn scene-structs
  "Every Scene struct of parsed file `bf`, in file order."
  [bf]
  (keep #(f/block-ref bf %) (f/blocks-with-code bf "SC")))

(defn scene-list
  "The scenes of parsed file `bf`: for each, {:name :objects (how many
  objects it holds) :meshes (how many of them are meshes) :current?
  (whether the file was saved showing it)}."
  [bf]
  (let [cur (current-scene bf)]
    (mapv (fn [sc]
            (let [obs (scene-objects bf sc)]
              {:name (f/id-name sc)
               :objects (count obs)
               :meshes (count (filter #(= 1 (f/fget % "type")) obs))
               :current? (= (:offset sc) (:offset cur))}))
          (scene-structs bf))))

(defn- choose-scene
  "The Scene struct `opts` asks for (:scene, a name), else the current
  one; an error listing the scenes when no scene has that name. With a
  warning when the scene has no mesh objects and others have."
  [bf {:keys [scene]}]
  (let [all (scene-structs bf)
        sc (if scene
             (or (some #(when (= scene (f/id-name %)) %) all)
                 (f/fail (:source bf) (str "no scene named " (pr-str scene) "; the file has "
                                           (pr-str (mapv f/id-name all)))))
             (current-scene bf))
        listed (when sc (scene-list bf))
        mine (some #(when (= (f/id-name sc) (:name %)) %) listed)
        others (filter #(and (pos? (long (:meshes %))) (not= (:name %) (:name mine))) listed)]
    [sc (when (and mine (zero? (long (:meshes mine))) (seq others))
          [(str "scene " (pr-str (:name mine)) " has no mesh objects; "
                (str/join ", " (map #(str "scene " (pr-str (:name %)) " has " (:meshes %)) others))
                ": choose one with (load-blender-model path {:scene "
                (pr-str (:name (first others))) "})")])]))

(defn scene-data
  "The scene of parsed file `bf` as data: {:scene name, :objects [...],
  :rigid-body-world settings, :warnings [...]}, each object with :name,
  :type, :parent (the parent's name, even when the parent is not in
  the scene), :parent-key (the parent's key when it is in the scene),
  :world (4x4 rows, Blender coordinates), :mesh (mesh data or nil),
  :materials, :properties, :physics and more; :rigid-body-world is the
  scene's (see cortex.blender.rigid-body/rigid-body-world), nil when it
  has none. The scene is the one `opts` names ({:scene \"Game\"}), else
  the one the file was saved showing; a saved scene that lists no
  objects gives every object the file holds (files that predate
  scenes' object lists). :warnings says what the reader could not do
  as Blender would (bones whose saved pose is used, modifiers not
  applied) and when the scene has no meshes but another has."
  ([bf] (scene-data bf {}))
  ([bf opts]
   (let [[sc scene-warnings] (choose-scene bf opts)
         obs (when sc (scene-objects bf sc))
         obs (if (or (seq obs) (:scene opts))
               obs
               (keep #(f/block-ref bf %) (f/blocks-with-code bf "OB")))
         infos (mapv #(object-info bf %) obs)
         all (break-cycles (with-ancestors bf infos))
         worlds (world-matrices all)
         infos (vec (take (count infos) all))
         keys (set (map :key infos))
         names (into {} (map (juxt :key :name)) all)
         objects (mapv (fn [{:keys [parent-key mesh-ref] :as o}]
                         (-> o
                             (assoc :world (worlds (:key o))
                                    :bone-matrix (:matrix (:bone o))
                                    :parent-key (when (keys parent-key) parent-key)
                                    :parent (names parent-key))
                             (with-mirrors (when mesh-ref (mesh/mesh-data bf mesh-ref)) worlds)
                             (dissoc :mesh-ref :bone)))
                       infos)]
     {:scene (if sc (f/id-name sc) "Scene")
      :rigid-body-world (when sc (physics/rigid-body-world bf sc))
      :warnings (vec (distinct (concat scene-warnings (mapcat (comp :warnings :bone) all)
                                       (keep constraint-warning objects)
                                       (keep modifier-warning objects))))
      :objects objects})))
