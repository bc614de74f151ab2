(ns cortex.blender.scene
  "The objects of a .blend file's scene as plain data: names, types,
  parents, world matrices rebuilt from each object's own transform
  fields, custom properties and material colours.

  Entry points: `scene-data` (a parsed file's scene as data),
  `current-scene`, `scene-objects`, `properties`."
  (:require [cortex.blender.file :as f]
            [cortex.blender.math :as m]
            [cortex.blender.mesh :as mesh]
            [cortex.blender.rigid-body :as physics]))

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

(defn- find-bone
  "The Bone named `name` in the tree of bones of armature `arm`
  (`bonebase`, then each bone's `childbase`), visiting each at most
  once."
  [bf arm name]
  (loop [todo (vec (f/list-seq bf (f/fget arm "bonebase") "Bone")) seen #{}]
    (when-let [b (peek todo)]
      (let [todo (pop todo)]
        (cond
          (seen (:offset b)) (recur todo seen)
          (= name (f/fget b "name")) b
          :else (recur (into todo (f/list-seq bf (f/fget b "childbase") "Bone"))
                       (conj seen (:offset b))))))))

(defn- bone-matrix
  "For an object parented to a bone (partype 7): the bone's pose matrix
  in its armature's frame, moved from the bone's head to its tail, as
  Blender's ob_parbone does; nil when the pose or bone is missing. The
  pose matrices are saved with the armature object's pose."
  [bf ob]
  (let [par (f/deref-ptr bf (f/fget ob "parent") "Object")
        name (f/fget ob "parsubstr")
        pose (f/deref-ptr bf (f/fget par "pose") "bPose")
        pchan (some #(when (= name (f/fget % "name")) %)
                    (f/list-seq bf (f/fget pose "chanbase") "bPoseChannel"))
        arm (f/deref-ptr bf (f/fget par "data") "bArmature")
        bone (when arm (find-bone bf arm name))]
    (when-let [pm (f/fget pchan "pose_mat")]
      (let [m (m/from-blender pm)
            len (double (or (f/fget bone "length") 0.0))
            y (mapv #(nth % 1) (subvec m 0 3))
            t (mapv + (m/translation m) (mapv #(* len (double %)) y))]
        (m/mat3->mat4 (m/mat4->mat3 m) t)))))

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
     :bone-matrix (when (= 7 (bit-and (long (or (f/fget ob "partype") 0)) 15))
                    (bone-matrix bf ob))
     :local (local-matrix ob)
     :parentinv (m/from-blender (f/fget ob "parentinv"))
     :stored-world (when obmat (m/from-blender obmat))
     :properties (properties bf ob)
     :materials (material-slots bf ob data)
     :color (or (f/fget ob "col") [1.0 1.0 1.0 1.0])
     :modifiers (count (f/list-seq bf (f/fget ob "modifiers")))
     :physics (physics/user-data bf ob)
     :mesh-ref (when (and (= type "MESH") data (= "Mesh" (:name (:layout data)))) data)}))

(defn- world-matrices
  "Each object's world matrix, by key: parent's world * parentinv *
  local, as Blender's solve_parenting does for object parents, with the
  bone's matrix after the parent's for bone parents (partype 7). A
  parent cycle or a parent missing from `infos` counts as no parent.
  Vertex parents (partype 5, 6) need the parent mesh evaluated; for
  them, and for a bone that cannot be found, the world matrix the file
  stores is used when it has one."
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
                                             bone-matrix]} (by-key q)
                                     pw (get done parent-key)]
                                 (assoc done q
                                        (cond
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

(defn scene-data
  "The scene of parsed file `bf` as data: {:scene name, :objects [...],
  :rigid-body-world settings}, each object with :name, :type, :parent
  (the parent's name, even when the parent is not in the scene),
  :parent-key (the parent's key when it is in the scene), :world (4x4
  rows, Blender coordinates), :mesh (mesh data or nil), :materials,
  :properties, :physics and more; :rigid-body-world is the scene's
  (see cortex.blender.rigid-body/rigid-body-world), nil when it has
  none. Objects are those of the current scene; a file whose scene
  lists none gives every object it holds."
  [bf]
  (let [sc (current-scene bf)
        obs (when sc (scene-objects bf sc))
        obs (if (seq obs)
              obs
              (keep #(f/block-ref bf %) (f/blocks-with-code bf "OB")))
        infos (mapv #(object-info bf %) obs)
        all (break-cycles (with-ancestors bf infos))
        worlds (world-matrices all)
        infos (vec (take (count infos) all))
        keys (set (map :key infos))
        names (into {} (map (juxt :key :name)) all)]
    {:scene (if sc (f/id-name sc) "Scene")
     :rigid-body-world (when sc (physics/rigid-body-world bf sc))
     :objects (mapv (fn [{:keys [parent-key mesh-ref] :as o}]
                      (-> o
                          (assoc :world (worlds (:key o))
                                 :parent-key (when (keys parent-key) parent-key)
                                 :parent (names parent-key)
                                 :mesh (when mesh-ref (mesh/mesh-data bf mesh-ref)))
                          (dissoc :mesh-ref)))
                    infos)}))
