;; Generated from org/blend-format.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender.file
  "Read the bytes of a .blend file into blocks and decode its structs
  with the file's own SDNA: no offset is written down here, every one is
  computed from the struct definitions the file carries.

  Entry points: `parse` (bytes to a parsed file), `blocks-with-code`,
  `block-ref`, `fget`/`fget-in` (a field by name), `deref-ptr`,
  `deref-array`, `list-seq` (Blender's linked lists), `id-name`,
  `has-field?`, `fail` (a named error, cortex.blender.bytes')."
  (:require [clojure.string :as str]
            [cortex.blender.bytes :as bytes :refer [decompress]])
  (:import [java.nio ByteBuffer ByteOrder]
           [java.util TreeMap Map$Entry]))

(set! *warn-on-reflection* true)

(def ^{:arglists '([source msg] [source msg data])
       :doc "Throw an ex-info whose message begins with the file's name
  (cortex.blender.bytes/fail)."}
  fail bytes/fail)

(defn parse-header
  "The file header: pointer size, byte order, version and the size of
  the header and of each block header.
  Before 5.0: `BLENDER` `_`|`-` (4|8-byte pointers) `v`|`V` (little|big
  endian) and three digits, with 20 or 24-byte block headers.
  5.0: `BLENDER17-01v0500`: header size, format 01 (8-byte pointers,
  32-byte block headers with 64-bit lengths), byte order, four digits."
  [source ^bytes b]
  (let [n (alength b)
        text (String. b 0 (int (min n 17)) "ISO-8859-1")]
    (when-not (str/starts-with? text "BLENDER")
      (fail source (if (zero? n) "empty file, not a .blend file"
                       "not a .blend file (no BLENDER header)")))
    (if-let [[_ hsize fmt endian version]
             (re-matches #"BLENDER(\d\d)-(\d\d)([vV])(\d{4})" text)]
      (do (when-not (and (= hsize "17") (= fmt "01"))
            (fail source (str "unknown .blend header format " (pr-str text))))
          {:header-size 17 :ptr-size 8 :little? (= endian "v")
           :version (Long/parseLong version) :bhead :large :bhead-size 32})
      (let [[_ ptr endian version] (re-matches #"BLENDER([_-])([vV])(\d{3}).*"
                                               (subs text 0 (min 12 (count text))))]
        (when-not version
          (fail source (str "bad .blend header " (pr-str (subs text 0 (min 12 (count text)))))))
        (let [ptr-size (if (= ptr "_") 4 8)]
          {:header-size 12 :ptr-size ptr-size :little? (= endian "v")
           :version (Long/parseLong version) :bhead :small
           :bhead-size (+ 16 ptr-size)})))))

(defn- code-string
  "A block code: four bytes, trailing NULs dropped (`OB\\0\\0` -> \"OB\")."
  [^ByteBuffer buf ^long pos]
  (let [sb (StringBuilder.)]
    (dotimes [i 4]
      (let [c (bit-and (.get buf (int (+ pos i))) 0xff)]
        (when-not (zero? c) (.append sb (char c)))))
    (str sb)))

(defrecord Block [code ^long offset ^long len ^long old ^long sdna ^long nstructs group])

(defn read-blocks
  "Every block of the file up to `ENDB`, as Blocks of :code, :offset (of
  the block's data), :len, :old (the pointer the block had in memory
  when saved), :sdna and :nstructs, the number of structs in it (:group
  is filled in later). Each
  length is checked against the bytes that are actually there; each
  step moves forward, so the walk ends within the file's size."
  [source header ^ByteBuffer buf]
  (let [limit (long (.limit buf))
        large? (= :large (:bhead header))
        ptr-size (long (:ptr-size header))
        bhead-size (long (:bhead-size header))]
    (loop [pos (long (:header-size header)), blocks (transient [])]
      (when (> (+ pos bhead-size) limit)
        (fail source (str "truncated: block header at byte " pos
                          " runs past the end (" limit " bytes); no ENDB block")))
      (let [code (code-string buf pos)
            p (int pos)
            len (if large? (.getLong buf (+ p 16)) (long (.getInt buf (+ p 4))))
            old (cond large? (.getLong buf (+ p 8))
                      (= ptr-size 8) (.getLong buf (+ p 8))
                      :else (bit-and (long (.getInt buf (+ p 8))) 0xFFFFFFFF))
            sdna (if large?
                   (bit-and (long (.getInt buf (+ p 4))) 0xFFFFFFFF)
                   (long (.getInt buf (int (+ p 8 ptr-size)))))
            cnt (if large? (.getLong buf (+ p 24)) (long (.getInt buf (int (+ p 12 ptr-size)))))
            start (+ pos bhead-size)]
        (when (or (neg? len) (> len (- limit start)))
          (fail source (str "block " (pr-str code) " at byte " pos " claims "
                            len " bytes but only " (- limit start) " remain")
                {:block code :offset pos}))
        (if (= code "ENDB")
          (persistent! blocks)
          (recur (+ start len)
                 (conj! blocks (->Block code start len old sdna cnt nil))))))))

(defn- align4
  "Round byte offset `p` up to a multiple of 4 counted from `base`."
  ^long [^long base ^long p]
  (+ base (bit-and (+ (- p base) 3) -4)))

(defn parse-sdna
  "The struct definitions in the DNA1 block: names, types, type
  lengths and structs (type index plus [type name] index pairs).
  Sections are `SDNA` then `NAME`, `TYPE`, `TLEN`, `STRC`, each
  4-byte aligned; every count is checked against the block's bytes."
  [source ^ByteBuffer buf {:keys [^long offset ^long len]}]
  (let [end (+ offset len)
        need (fn [^long p ^long k what]
               (when (or (neg? k) (> (+ p k) end))
                 (fail source (str "DNA1 block cut short reading " what))))
        tag (fn [^long p t]
              (need p 4 t)
              (when-not (= (code-string buf p) t)
                (fail source (str "DNA1 block lacks its " t " section"))))
        int-at (fn ^long [^long p what] (need p 4 what) (.getInt buf (int p)))
        short-at (fn ^long [^long p] (long (.getShort buf (int p))))
        strings (fn [^long p ^long n what]
                  (when (or (neg? n) (> n (- end p)))
                    (fail source (str "DNA1 block claims " n " " what)))
                  (loop [p p, i 0, out (transient [])]
                    (if (= i n)
                      [(persistent! out) p]
                      (let [q (loop [q (long p)]
                                (cond (>= q end) (fail source (str "DNA1 block cut short reading " what))
                                      (zero? (.get buf (int q))) q
                                      :else (recur (inc q))))
                            bs (byte-array (- (long q) (long p)))]
                        (.get (.duplicate buf) (int p) bs)
                        (recur (inc (long q)) (inc i) (conj! out (String. bs "UTF-8")))))))
        _ (tag offset "SDNA")
        _ (tag (+ offset 4) "NAME")
        [names p] (strings (+ offset 12) (int-at (+ offset 8) "names") "names")
        p (align4 offset p)
        _ (tag p "TYPE")
        [types p] (strings (+ p 8) (int-at (+ p 4) "types") "types")
        p (align4 offset p)
        _ (tag p "TLEN")
        ntypes (count types)
        _ (need (+ p 4) (* 2 ntypes) "type lengths")
        tlens (mapv #(short-at (+ p 4 (* 2 %))) (range ntypes))
        p (align4 offset (+ p 4 (* 2 ntypes)))
        _ (tag p "STRC")
        nstructs (int-at (+ p 4) "structs")
        _ (when (or (neg? nstructs) (> nstructs (quot (- end p) 4)))
            (fail source (str "DNA1 block claims " nstructs " structs")))
        structs (loop [q (+ p 8), i 0, out (transient [])]
                  (if (= i nstructs)
                    (persistent! out)
                    (do (need q 4 "struct header")
                        (let [t (short-at q)
                              nf (short-at (+ q 2))]
                          (need (+ q 4) (* 4 nf) "struct fields")
                          (when-not (< -1 t ntypes)
                            (fail source (str "struct " i " has bad type index " t)))
                          (let [fields (mapv (fn [k]
                                               (let [ft (short-at (+ q 4 (* 4 k)))
                                                     fnm (short-at (+ q 6 (* 4 k)))]
                                                 (when-not (and (< -1 ft ntypes)
                                                                (< -1 fnm (count names)))
                                                   (fail source (str "struct " (types t)
                                                                     " has a bad field")))
                                                 [ft fnm]))
                                             (range nf))]
                            (recur (+ q 4 (* 4 (long nf))) (inc i)
                                   (conj! out {:type t :fields fields})))))))]
    {:names names :types types :tlens tlens :structs structs}))

(defn parse-name
  "What a field name says: `*next` is a pointer, `mat[4][4]` an array
  4 by 4, `(*func)()` a function pointer; the bare name is `next`,
  `mat`, `func`."
  [s]
  (let [ptr (count (re-find #"^\(?\*+" s))
        func? (str/starts-with? s "(*")
        dims (mapv #(Long/parseLong %) (map second (re-seq #"\[(\d+)\]" s)))
        base (-> s (str/replace #"\[.*$" "") (str/replace #"[*()]" ""))]
    {:base base :ptr? (or (pos? ptr) func?) :func? func? :dims dims
     :n (reduce * 1 dims)}))

(declare field-reader)

(defn- struct-layout*
  "Lay out one SDNA struct: its name, size and fields in order, each
  with :name, :type, :offset, :size, pointer/array facts and :read, a
  function that decodes the field from a struct view. Offsets are the
  sums of the sizes before, as makesdna lays them out (it demands
  explicit padding, so there is none to guess)."
  [{:keys [types tlens]} parsed struct-of-type ptr-size {:keys [type fields]}]
  (let [fs (loop [[[ft fnm] & more] fields, off 0, out []]
             (if (nil? ft)
               out
               (let [{:keys [ptr? ^long n] :as pn} @(parsed fnm)
                     size (if ptr? (* (long ptr-size) n) (* (long (tlens ft)) n))
                     f (assoc pn :name (:base pn) :type (types ft)
                              :struct (when-not ptr? (struct-of-type ft))
                              :tlen (tlens ft)
                              :offset off :size size)
                     f (assoc f :read (field-reader f))]
                 (recur more (+ off (long size)) (conj out f)))))]
    {:name (types type)
     :size (tlens type)
     :fields fs
     :by-name (into {} (map (juxt :name identity)) (reverse fs))}))

(defn layouts
  "The layout of every struct of the SDNA, each computed when first
  asked for (a file defines around a thousand structs; a load needs a
  few dozen)."
  [{:keys [names structs] :as sdna} ptr-size]
  (let [parsed (mapv #(delay (parse-name %)) names)
        struct-of-type (into {} (map-indexed (fn [i s] [(:type s) i]) structs))]
    (mapv #(delay (struct-layout* sdna parsed struct-of-type ptr-size %)) structs)))

(defn layout
  "The layout of struct number `i` of the file's SDNA, or nil."
  [bf i]
  (some-> (get (:layouts bf) i) deref))

(defn- ptr-map
  "A sorted map from old pointer to block, for floor look-ups."
  ^TreeMap [blocks]
  (let [m (TreeMap.)]
    (doseq [b blocks :when (not= 0 (:old b))]
      (.put m (:old b) b))
    m))

(defn- with-groups
  "Tag each block with :group, the index of the ID block it belongs to:
  an ID block (`OB`, `ME`, ...) starts a group and the `DATA` blocks
  after it are its data. Blender reads pointers inside an ID's data
  against that ID's blocks only, and since 5.0 old pointers are only
  unique within such a group."
  [blocks]
  (loop [[b & more] blocks, g -1, i 0, out (transient [])]
    (if (nil? b)
      (persistent! out)
      (let [g (if (= "DATA" (:code b)) g i)]
        (recur more g (inc i) (conj! out (assoc b :group g)))))))

(def ^:private catalogues
  "Catalogues seen, by pointer size, byte order and hash of the DNA1
  bytes. A plain def, not defonce: reloading this namespace must drop
  layouts whose readers were compiled against the old classes."
  (atom {}))

(defn- catalogue
  "The SDNA of DNA1 block `dna` with its struct layouts and an index of
  structs by name. Files saved by one Blender version carry the same
  catalogue, so these are kept, keyed by the block's exact bytes, and
  a file with a catalogue seen before skips parsing and laying it out.
  At most 32 catalogues are kept."
  [source ^ByteBuffer buf {:keys [^long offset ^long len] :as dna} ptr-size]
  (let [bs (byte-array len)
        _ (.get (.duplicate buf) (int offset) bs)
        k [ptr-size (str (.order buf)) (java.util.Arrays/hashCode bs)]
        hit (some #(when (java.util.Arrays/equals ^bytes (:bytes %) bs) %) (get @catalogues k))]
    (or hit
        (let [sdna (parse-sdna source buf dna)
              entry {:bytes bs
                     :sdna sdna
                     :layouts (layouts sdna ptr-size)
                     :struct-index (into {} (map-indexed (fn [i s] [((:types sdna) (:type s)) i])
                                                         (:structs sdna)))}]
          (swap! catalogues (fn [c] (update (if (>= (count c) 32) {} c) k conj entry)))
          entry))))

(defn parse
  "Parse the bytes of a .blend file: header, blocks, SDNA, struct
  layouts and indexes of blocks by old pointer. `source` names the
  file in every error."
  [source ^bytes raw]
  (let [bytes (decompress source raw)
        header (parse-header source bytes)
        buf (.order (ByteBuffer/wrap bytes)
                    (if (:little? header) ByteOrder/LITTLE_ENDIAN ByteOrder/BIG_ENDIAN))
        blocks (with-groups (read-blocks source header buf))
        dna (or (some #(when (= (:code %) "DNA1") %) blocks)
                (fail source "no DNA1 block (struct definitions) in the file"))
        {:keys [sdna layouts struct-index]} (catalogue source buf dna (:ptr-size header))
        olds (remove zero? (map :old blocks))]
    (assoc header
           :source (str source)
           :buf buf
           :size (alength bytes)
           :blocks blocks
           :sdna sdna
           :layouts layouts
           :struct-index struct-index
           :ids (ptr-map (remove #(= "DATA" (:code %)) blocks))
           :groups (into {} (for [[g bs] (group-by :group blocks)] [g (delay (ptr-map bs))]))
           :all (delay (when (= (count olds) (count (distinct olds))) (ptr-map blocks))))))

(defrecord Ptr [^long addr group])

(defrecord Ref [bf ^ByteBuffer buf layout ^long offset ^long end group])

(defn struct-layout
  "The layout of struct `type-name`, or nil when this file has none."
  [bf type-name]
  (when-let [i ((:struct-index bf) type-name)]
    (layout bf i)))

(defn ref-at
  "A view of struct `layout` at byte `offset` of a block of `group`,
  which must end by `end` (the end of that block), or nil when it does
  not fit."
  [bf layout offset end group]
  (when (and layout (<= (+ (long offset) (long (:size layout))) (long end)) (>= (long offset) 0))
    (->Ref bf (:buf bf) layout offset end group)))

(defn- lookup
  "The block of sorted map `m` holding address `addr`, and the offset
  of that byte in the buffer."
  [^TreeMap m ^long addr]
  (when m
    (when-let [^Map$Entry e (.floorEntry m addr)]
      (let [b (.getValue e)
            d (- addr (long (:old b)))]
        (when (and (>= d 0) (< d (max 1 (long (:len b)))))
          [b (+ (long (:offset b)) d)])))))

(defn block-of
  "The block pointer `ptr` points into, with the buffer offset of the
  pointed-at byte, or nil for NULL or a pointer into no block. Looks in
  the pointer's own ID group, then among ID blocks, then (when old
  pointers are unique in the file) anywhere."
  [bf ptr]
  (when ptr
    (let [addr (long (:addr ptr))]
      (or (lookup (some-> (get (:groups bf) (:group ptr)) deref) addr)
          (lookup (:ids bf) addr)
          (lookup @(:all bf) addr)))))

(defn block-ref
  "A view of the `i`th struct of a block, typed by the block's SDNA
  index, or nil when it does not fit."
  ([bf block] (block-ref bf block 0))
  ([bf {:keys [sdna ^long offset ^long len group]} ^long i]
   (let [lay (layout bf sdna)]
     (when lay
       (ref-at bf lay (+ offset (* i (long (:size lay)))) (+ offset len) group)))))

(defn deref-ptr
  "A view of the struct pointer `ptr` points at, typed as `type-name`
  or, without one, by the SDNA index of the block it lands in; nil for
  NULL, dangling pointers and structs that do not fit in their block."
  ([bf ptr] (deref-ptr bf ptr nil))
  ([bf ptr type-name]
   (when-let [[b off] (block-of bf ptr)]
     (let [lay (if type-name
                 (struct-layout bf type-name)
                 (layout bf (:sdna b)))]
       (ref-at bf lay off (+ (long (:offset b)) (long (:len b))) (:group b))))))

(defn pointed-bytes
  "[offset available group] for the bytes pointer `ptr` points at:
  where they start in the buffer, how many the block holds from there
  on, and the block's ID group (for pointers stored there)."
  [bf ptr]
  (when-let [[b off] (block-of bf ptr)]
    [off (- (+ (long (:offset b)) (long (:len b))) (long off)) (:group b)]))

(defn deref-array
  "Views of the first `n` structs of type `type-name` in the array
  pointer `ptr` points at: no more than the pointed-at block holds,
  whatever `n` (a count read from the file) says. Empty for NULL,
  dangling pointers and unknown types."
  [bf ptr type-name n]
  (let [lay (struct-layout bf type-name)]
    (if-let [[off avail g] (and lay (pos? (long n)) (pointed-bytes bf ptr))]
      (let [size (long (:size lay))
            end (+ (long off) (long avail))]
        (vec (keep #(ref-at bf lay (+ (long off) (* (long %) size)) end g)
                   (range (min (long n) (quot (long avail) (max 1 size)))))))
      [])))

(defn read-ptr
  "The pointer stored at `off` in a block of `group`, or nil for NULL.
  4-byte pointers are read unsigned."
  [bf ^long off group]
  (let [^ByteBuffer buf (:buf bf)
        addr (if (= 8 (:ptr-size bf))
               (.getLong buf (int off))
               (bit-and (long (.getInt buf (int off))) 0xffffffff))]
    (when-not (zero? addr) (->Ptr addr group))))

(defn c-string
  "The NUL-terminated string in the `n` bytes at `off`, read as UTF-8."
  [bf ^long off ^long n]
  (let [^ByteBuffer buf (:buf bf)
        len (loop [i 0]
              (if (or (>= i n) (zero? (.get buf (int (+ off i))))) i (recur (inc i))))
        bs (byte-array len)]
    (.get (.duplicate buf) (int off) bs)
    (String. bs "UTF-8")))

(defn- shape
  "Group flat values `xs` into nested vectors by array dims."
  [xs dims]
  (if (<= (count dims) 1)
    (vec xs)
    (mapv #(shape % (rest dims))
          (partition (reduce * 1 (rest dims)) xs))))

(defn field-info
  "The layout entry of field `fname` of the struct `r` views, or nil."
  [^Ref r fname]
  (get (:by-name (.layout r)) fname))

(defn has-field?
  "Does the struct `r` views have field `fname` in this file's SDNA?"
  [r fname]
  (some? (field-info r fname)))

(defn- prim-reader
  "A function reading one value of SDNA primitive `t` (`size` bytes) at
  a buffer offset."
  [t ^long size]
  (case t
    ("char" "int8_t") (fn [^ByteBuffer b ^long o] (long (.get b (int o))))
    ("uchar" "uint8_t") (fn [^ByteBuffer b ^long o] (bit-and (long (.get b (int o))) 0xff))
    "bool" (fn [^ByteBuffer b ^long o] (not (zero? (.get b (int o)))))
    ("short" "int16_t") (fn [^ByteBuffer b ^long o] (long (.getShort b (int o))))
    ("ushort" "uint16_t") (fn [^ByteBuffer b ^long o] (bit-and (long (.getShort b (int o))) 0xffff))
    ("int" "int32_t") (fn [^ByteBuffer b ^long o] (long (.getInt b (int o))))
    ("uint" "uint32_t") (fn [^ByteBuffer b ^long o] (bit-and (long (.getInt b (int o))) 0xffffffff))
    "float" (fn [^ByteBuffer b ^long o] (.getFloat b (int o)))
    "double" (fn [^ByteBuffer b ^long o] (.getDouble b (int o)))
    ("int64_t" "uint64_t") (fn [^ByteBuffer b ^long o] (.getLong b (int o)))
    ;; a type this reader does not name: an integer of its size
    (case size
      1 (fn [^ByteBuffer b ^long o] (long (.get b (int o))))
      2 (fn [^ByteBuffer b ^long o] (long (.getShort b (int o))))
      4 (fn [^ByteBuffer b ^long o] (long (.getInt b (int o))))
      8 (fn [^ByteBuffer b ^long o] (.getLong b (int o)))
      (fn [_ _] nil))))

(defn field-reader
  "The function that decodes field `f` from a struct view: numbers,
  strings (char arrays), vectors (other arrays), Ptrs (pointers; nil
  for NULL) or views of embedded structs. Made once per field of a
  catalogue, so reading a field is a map look-up and a call."
  [{:keys [ptr? dims n type tlen struct offset]}]
  (let [n (long n) tlen (long tlen) offset (long offset)
        prim (when-not (or ptr? struct) (prim-reader type tlen))]
    (cond
      (and ptr? (empty? dims))
      (fn [^Ref r] (read-ptr (.bf r) (+ (.offset r) offset) (.group r)))

      ptr?
      (fn [^Ref r]
        (let [bf (.bf r) ps (long (:ptr-size bf))]
          (shape (map #(read-ptr bf (+ (.offset r) offset (* (long %) ps)) (.group r)) (range n))
                 dims)))

      struct
      (fn [^Ref r]
        (let [lay (layout (.bf r) struct)
              off (+ (.offset r) offset)]
          (if (empty? dims)
            (->Ref (.bf r) (.buf r) lay off (.end r) (.group r))
            (shape (map #(->Ref (.bf r) (.buf r) lay (+ off (* (long %) tlen)) (.end r) (.group r))
                        (range n))
                   dims))))

      (and (= type "char") (= 1 (count dims)))
      (fn [^Ref r] (c-string (.bf r) (+ (.offset r) offset) n))

      (empty? dims)
      (fn [^Ref r] (prim (.buf r) (+ (.offset r) offset)))

      :else
      (fn [^Ref r]
        (let [off (+ (.offset r) offset)]
          (shape (map #(prim (.buf r) (+ off (* (long %) tlen))) (range n)) dims))))))

(defn fget
  "The value of field `fname` of the struct `r` views, decoded by the
  SDNA (see `field-reader`); nil when the struct has no such field in
  this file."
  [^Ref r fname]
  (when r
    (when-let [fi (get (:by-name (.layout r)) fname)]
      ((:read fi) r))))

(defn fget-in
  "Follow a path of field names through embedded structs."
  [r path]
  (reduce (fn [r k] (when r (fget r k))) r path))

(defn field-offset
  "The absolute byte offset of field `fname` of `r`, or nil."
  [^Ref r fname]
  (when-let [fi (field-info r fname)]
    (+ (.offset r) (long (:offset fi)))))

(defn list-seq
  "The structs of a ListBase (`first`, then each one's `next`: the
  pointer every element starts with, its own or that of the struct it
  begins with, as a Mirror modifier's struct begins with ModifierData),
  typed by their blocks or as `type-name`. Stops at NULL, at a dangling
  pointer and at a link already seen, so cycles end; never longer than
  the file has blocks."
  ([bf listbase] (list-seq bf listbase nil))
  ([bf listbase type-name]
   (let [limit (count (:blocks bf))]
     (loop [ptr (fget listbase "first"), seen #{}, out []]
       (let [r (deref-ptr bf ptr type-name)]
         (if (or (nil? r) (seen (.offset ^Ref r)) (>= (count out) limit))
           out
           (recur (read-ptr bf (.offset ^Ref r) (.group ^Ref r)) (conj seen (.offset ^Ref r)) (conj out r))))))))

(defn blocks-with-code
  "The blocks whose code is `code` (\"OB\", \"ME\", \"SC\", ...)."
  [bf code]
  (filter #(= code (:code %)) (:blocks bf)))

(defn id-name
  "An ID's name without its two-letter type prefix (`OBCube` -> `Cube`)."
  [r]
  (let [n (or (fget-in r ["id" "name"]) "")]
    (if (>= (count n) 2) (subs n 2) n)))
