;; Generated from org/blend-format.org by lein tangle: edit the chapter, not this file.
(ns cortex.blend-format-test
  (:require [clojure.test :refer [deftest is testing]]
            [cortex.blender.bytes :as bytes]
            [cortex.blender.file :as file])
  (:import [clojure.lang ExceptionInfo]
           [java.io ByteArrayOutputStream]
           [java.nio ByteBuffer ByteOrder]
           [java.nio.file Files Paths]
           [java.util Arrays]
           [java.util.zip GZIPOutputStream]))

(set! *warn-on-reflection* true)

(defn- slurp-bytes
  "The bytes of the file at `path`."
  ^bytes [^String path]
  (Files/readAllBytes (Paths/get path (make-array String 0))))

(defn- error
  "The ex-info that (f) throws, or nil when it throws none."
  [f]
  (try (f) nil (catch ExceptionInfo e e)))

(defn- header [^String text]
  (file/parse-header "h.blend" (.getBytes text "ISO-8859-1")))

(deftest headers
  (is (= {:header-size 12 :ptr-size 4 :little? true :version 279 :bhead :small :bhead-size 20}
         (header "BLENDER_v279")))
  (is (= {:header-size 12 :ptr-size 8 :little? true :version 279 :bhead :small :bhead-size 24}
         (header "BLENDER-v279")))
  (is (= {:header-size 12 :ptr-size 4 :little? false :version 260 :bhead :small :bhead-size 20}
         (header "BLENDER_V260")))
  (is (= {:header-size 12 :ptr-size 8 :little? false :version 250 :bhead :small :bhead-size 24}
         (header "BLENDER-V250")))
  (is (= {:header-size 17 :ptr-size 8 :little? true :version 500 :bhead :large :bhead-size 32}
         (header "BLENDER17-01v0500")))
  (testing "the fixtures' headers"
    (doseq [[v version size] [["b34" 304 12] ["b45" 405 12] ["b50" 500 17]]]
      (let [h (file/parse-header v (slurp-bytes (str "test/fixtures/blend/" v "/transforms.blend")))]
        (is (= [version size 8 true] ((juxt :version :header-size :ptr-size :little?) h))))))
  (testing "what is not a header"
    (doseq [[text msg] [["" "h.blend: empty file, not a .blend file"]
                        ["PK\u0003\u0004 a zip file" "h.blend: not a .blend file (no BLENDER header)"]
                        ["BLENDER_v2" "h.blend: bad .blend header \"BLENDER_v2\""]
                        ["BLENDER*v279" "h.blend: bad .blend header \"BLENDER*v279\""]
                        ["BLENDER17-02v0500" "h.blend: unknown .blend header format \"BLENDER17-02v0500\""]]]
      (let [e (error #(header text))]
        (is (= msg (ex-message e)))
        (is (= "h.blend" (:file (ex-data e))))))))

(deftest field-names
  (is (= {:base "next" :ptr? true :func? false :dims [] :n 1} (file/parse-name "*next")))
  (is (= {:base "mat" :ptr? false :func? false :dims [4 4] :n 16} (file/parse-name "mat[4][4]")))
  (is (= {:base "func" :ptr? true :func? true :dims [] :n 1} (file/parse-name "(*func)()")))
  (is (= {:base "mtex" :ptr? true :func? false :dims [18] :n 18} (file/parse-name "*mtex[18]"))))

(def ^:private tiny-sdna
  "The catalogue of the file made by hand: field names, type names and
  structs (type, then [type name] of each field)."
  {:names ["*next" "*prev" "name[8]" "*first" "*last" "id" "loc[3]" "flag" "pad" "count"
           "*other" "things"]
   :types ["void" "char" "short" "int" "float" "ID" "ListBase" "Thing" "World"]
   :structs [["ID" [["char" "name[8]"]]]
             ["ListBase" [["void" "*first"] ["void" "*last"]]]
             ["Thing" [["Thing" "*next"] ["Thing" "*prev"] ["ID" "id"] ["float" "loc[3]"]
                       ["short" "flag"] ["short" "pad"] ["int" "count"] ["Thing" "*other"]]]
             ["World" [["ID" "id"] ["ListBase" "things"]]]]})

(defn- tlens
  "The size of each type of `tiny-sdna` with pointers of `ps` bytes."
  [ps]
  (let [ps (long ps)]
    {"void" 0 "char" 1 "short" 2 "int" 4 "float" 4 "ID" 8 "ListBase" (* 2 ps)
     "Thing" (+ (* 3 ps) 28) "World" (+ 8 (* 2 ps))}))

(defn- ascii! [^ByteBuffer b ^String s]
  (.put b (.getBytes s "ISO-8859-1")))

(defn- pad! [^ByteBuffer b n]
  (while (pos? (mod (.position b) (long n))) (.put b (byte 0))))

(defn- ptr! [^ByteBuffer b ps addr]
  (if (= 8 ps) (.putLong b (long addr)) (.putInt b (unchecked-int (long addr)))))

(defn- dna1
  "The bytes of the DNA1 block of `tiny-sdna`, in byte order `order`."
  ^bytes [^ByteOrder order ps]
  (let [b (.order (ByteBuffer/allocate 1024) order)
        {:keys [names types structs]} tiny-sdna
        type-index (zipmap types (range))
        name-index (zipmap names (range))
        c-strings! (fn [ss] (doseq [^String s ss] (ascii! b s) (.put b (byte 0))))]
    (ascii! b "SDNA")
    (ascii! b "NAME") (.putInt b (count names)) (c-strings! names) (pad! b 4)
    (ascii! b "TYPE") (.putInt b (count types)) (c-strings! types) (pad! b 4)
    (ascii! b "TLEN") (doseq [t types] (.putShort b (short ((tlens ps) t)))) (pad! b 4)
    (ascii! b "STRC") (.putInt b (count structs))
    (doseq [[t fields] structs]
      (.putShort b (short (type-index t)))
      (.putShort b (short (count fields)))
      (doseq [[ft fname] fields]
        (.putShort b (short (type-index ft)))
        (.putShort b (short (name-index fname)))))
    (Arrays/copyOf (.array b) (.position b))))

(defn tiny-blend
  "The file made by hand, with pointers of `ptr-size` bytes, little or
  big endian, or in Blender 5.0's layout (`v5?`, 8-byte pointers)."
  ^bytes [{:keys [ptr-size little? v5?]}]
  (let [ps (if v5? 8 ptr-size)
        order (if little? ByteOrder/LITTLE_ENDIAN ByteOrder/BIG_ENDIAN)
        b (.order (ByteBuffer/allocate 4096) order)
        thing (long ((tlens ps) "Thing"))
        t1 0x2000
        t2 (+ t1 thing)
        block! (fn [code sdna old ^bytes data n]
                 (ascii! b code)
                 (if v5?
                   (do (.putInt b (int sdna)) (.putLong b old) (.putLong b (alength data)) (.putLong b n))
                   (do (.putInt b (alength data)) (ptr! b ps old) (.putInt b (int sdna)) (.putInt b (int n))))
                 (.put b data))
        data (fn [f] (let [d (.order (ByteBuffer/allocate 256) order)]
                       (f d)
                       (Arrays/copyOf (.array d) (.position d))))
        name! (fn [^ByteBuffer d ^String s] (ascii! d s) (dotimes [_ (- 8 (count s))] (.put d (byte 0))))
        thing! (fn [^ByteBuffer d next prev nm [x y z] flag cnt other]
                 (ptr! d ps next) (ptr! d ps prev) (name! d nm)
                 (.putFloat d x) (.putFloat d y) (.putFloat d z)
                 (.putShort d (short flag)) (.putShort d (short 0)) (.putInt d (int cnt))
                 (ptr! d ps other))]
    (ascii! b (if v5?
                (str "BLENDER17-01" (if little? "v" "V") "0500")
                (str "BLENDER" (if (= 4 ps) "_" "-") (if little? "v" "V") "279")))
    (block! "WO\u0000\u0000" 3 0x1000 (data #(do (name! % "WOworld") (ptr! % ps t1) (ptr! % ps t2))) 1)
    (block! "DATA" 2 t1 (data #(do (thing! % t2 0 "THone" [1.5 -2.0 3.25] -2 70000 t2)
                                  (thing! % 0 t1 "THtwo" [0.0 0.5 -1.0] 7 -1 t1)))
            2)
    (block! "DNA1" 0 0x3000 (dna1 order ps) 1)
    (block! "ENDB" 0 0 (byte-array 0) 0)
    (Arrays/copyOf (.array b) (.position b))))

(def ^:private layouts
  "The five ways to write the file made by hand."
  [{:ptr-size 4 :little? true} {:ptr-size 4 :little? false}
   {:ptr-size 8 :little? true} {:ptr-size 8 :little? false}
   {:v5? true :little? true}])

(deftest a-file-made-by-hand
  (doseq [{:keys [v5? little?] :as l} layouts
          :let [ps (if v5? 8 (:ptr-size l))
                bs (tiny-blend l)
                bf (file/parse "tiny.blend" bs)
                hs (if v5? 17 12)
                bh (if v5? 32 (+ 16 ps))]]
    (testing (pr-str l)
      (is (= [ps little? (if v5? 500 279) bh] ((juxt :ptr-size :little? :version :bhead-size) bf)))
      (testing "blocks: code, where the data starts, length, old address, struct, count"
        (is (= [["WO" (+ hs bh) (+ 8 (* 2 ps)) 0x1000 3 1]
                ["DATA" (+ hs bh (+ 8 (* 2 ps)) bh) (* 2 (+ 28 (* 3 ps))) 0x2000 2 2]]
               (mapv (juxt :code :offset :len :old :sdna :nstructs) (take 2 (:blocks bf)))))
        (is (= ["WO" "DATA" "DNA1"] (mapv :code (:blocks bf))))
        (is (= (alength bs) (+ (long (:offset (last (:blocks bf)))) (long (:len (last (:blocks bf)))) bh))))
      (testing "the catalogue"
        (let [sdna (:sdna bf)]
          (is (= (:names tiny-sdna) (:names sdna)))
          (is (= (:types tiny-sdna) (:types sdna)))
          (is (= [0 1 2 4 4 8 (* 2 ps) (+ 28 (* 3 ps)) (+ 8 (* 2 ps))] (:tlens sdna)))
          (is (= [{:type 5 :fields [[1 2]]}
                  {:type 6 :fields [[0 3] [0 4]]}
                  {:type 7 :fields [[7 0] [7 1] [5 5] [4 6] [2 7] [2 8] [3 9] [7 10]]}
                  {:type 8 :fields [[5 5] [6 11]]}]
                 (:structs sdna)))))
      (testing "layouts: each field's offset and size"
        (let [lay (file/struct-layout bf "Thing")]
          (is (= (+ 28 (* 3 ps)) (:size lay)))
          (is (= [["next" 0 ps] ["prev" ps ps] ["id" (* 2 ps) 8] ["loc" (+ 8 (* 2 ps)) 12]
                  ["flag" (+ 20 (* 2 ps)) 2] ["pad" (+ 22 (* 2 ps)) 2] ["count" (+ 24 (* 2 ps)) 4]
                  ["other" (+ 28 (* 2 ps)) ps]]
                 (mapv (juxt :name :offset :size) (:fields lay)))))
        (is (nil? (file/struct-layout bf "Object"))))
      (testing "fields read by name, pointers followed"
        (let [world (file/block-ref bf (first (:blocks bf)))
              [one two :as things] (file/list-seq bf (file/fget world "things"))]
          (is (= "world" (file/id-name world)))
          (is (= ["one" "two"] (mapv file/id-name things)))
          (is (= [[1.5 -2.0 3.25] -2 70000] ((juxt #(file/fget % "loc") #(file/fget % "flag")
                                                    #(file/fget % "count"))
                                              one)))
          (is (= [[0.0 0.5 -1.0] 7 -1] ((juxt #(file/fget % "loc") #(file/fget % "flag")
                                               #(file/fget % "count"))
                                         two)))
          (is (= "THone" (file/fget-in one ["id" "name"])))
          (is (= 0x2000 (:addr (file/fget two "prev")) (:addr (file/fget two "other"))))
          (is (= (+ 0x2000 28 (* 3 ps)) (:addr (file/fget one "next")) (:addr (file/fget one "other"))))
          (is (= "two" (file/id-name (file/deref-ptr bf (file/fget one "other") "Thing"))))
          (is (= "one" (file/id-name (file/deref-ptr bf (file/fget two "other")))))
          (is (nil? (file/fget two "next")))
          (is (file/has-field? one "loc"))
          (is (not (file/has-field? one "rot")))
          (is (nil? (file/fget one "rot")))
          (is (= (+ (long (:offset (second (:blocks bf)))) 8 (* 2 ps))
                 (file/field-offset one "loc")))
          (is (= 2 (count (file/deref-array bf (file/fget-in world ["things" "first"]) "Thing" 1000)))))))))

(defn- parse-error
  "The message of the error parsing `bs` gives, checking that the error
  names the file."
  [^bytes bs]
  (let [e (error #(file/parse "tiny.blend" bs))]
    (is (= "tiny.blend" (:file (ex-data e))))
    (ex-message e)))

(defn- patched
  "A copy of `bs` with the ASCII text `s` written over it at `at`."
  ^bytes [^bytes bs at ^String s]
  (let [c (aclone bs)]
    (System/arraycopy (.getBytes s "ISO-8859-1") 0 c (int at) (count s))
    c))

(deftest damage-is-named
  (let [bs (tiny-blend {:ptr-size 4 :little? true})
        n (alength bs)
        cut #(Arrays/copyOf bs (int %))
        dna-at (+ 148 20)]
    (is (= "DNA1" (String. bs 148 4 "ISO-8859-1")))
    (is (= "tiny.blend: bad .blend header \"BLENDER_v27\"" (parse-error (cut 11))))
    (is (= "tiny.blend: truncated: block header at byte 12 runs past the end (30 bytes); no ENDB block"
           (parse-error (cut 30))))
    (is (= "tiny.blend: block \"WO\" at byte 12 claims 16 bytes but only 5 remain"
           (parse-error (cut 37))))
    (is (= "tiny.blend: block \"DATA\" at byte 48 claims 80 bytes but only 12 remain"
           (parse-error (cut 80))))
    (is (= (str "tiny.blend: truncated: block header at byte " (- n 20) " runs past the end ("
                (- n 20) " bytes); no ENDB block")
           (parse-error (cut (- n 20)))))
    (is (= "tiny.blend: no DNA1 block (struct definitions) in the file"
           (parse-error (patched bs 148 "DNA2"))))
    (is (= "tiny.blend: DNA1 block lacks its NAME section"
           (parse-error (patched bs (+ dna-at 4) "NAMX"))))
    (is (= "tiny.blend: DNA1 block lacks its TLEN section"
           (parse-error (patched bs (.indexOf (String. bs "ISO-8859-1") "TLEN") "TLEX"))))
    (testing "counts the block cannot hold"
      (let [huge (aclone bs)]
        (.putInt (.order (ByteBuffer/wrap huge) ByteOrder/LITTLE_ENDIAN) (int (+ dna-at 8)) 1000000)
        (is (= "tiny.blend: DNA1 block claims 1000000 names" (parse-error huge))))
      (let [big (aclone bs)]
        (.putInt (.order (ByteBuffer/wrap big) ByteOrder/LITTLE_ENDIAN) (int 52) Integer/MAX_VALUE)
        (is (= (str "tiny.blend: block \"DATA\" at byte 48 claims 2147483647 bytes but only "
                    (- n 68) " remain")
               (parse-error big)))))))

(def ^:private fixture-facts
  {"b34" {:blocks 557 :names 4976 :types 931 :structs 806 :object 1456 :id 192 :name 66 :loc 584}
   "b45" {:blocks 668 :names 5269 :types 1095 :structs 957 :object 1168 :id 224 :name 66 :loc 600}
   "b50" {:blocks 1131 :names 5223 :types 1109 :structs 970 :object 1296 :id 408 :name 258 :loc 744}})

(defn- light
  "The Object struct of `bf` named Light."
  [bf]
  (some #(when (= "Light" (file/id-name %)) %)
        (keep #(file/block-ref bf %) (file/blocks-with-code bf "OB"))))

(deftest catalogues-of-real-files
  (doseq [[v facts] fixture-facts
          :let [path (str "test/fixtures/blend/" v "/transforms.blend")
                bf (file/parse path (slurp-bytes path))
                object (file/struct-layout bf "Object")
                loc (get-in object [:by-name "loc"])
                ob (light bf)]]
    (testing v
      (is (= facts {:blocks (count (:blocks bf))
                    :names (count (:names (:sdna bf)))
                    :types (count (:types (:sdna bf)))
                    :structs (count (:structs (:sdna bf)))
                    :object (:size object)
                    :id (:size (file/struct-layout bf "ID"))
                    :name (get-in (file/struct-layout bf "ID") [:by-name "name" :n])
                    :loc (:offset loc)}))
      (is (= ["float" [3] 12] ((juxt :type :dims :size) loc)))
      (is (= (:size object) (reduce + (map :size (:fields object)))))
      (is (= 23 (count (file/blocks-with-code bf "OB"))))
      (is (= [4.0 1.0 6.0] (file/fget ob "loc")))
      (is (= 10 (file/fget ob "type"))))))

(defn- gzip
  "`bs` gzipped."
  ^bytes [^bytes bs]
  (let [out (ByteArrayOutputStream.)]
    (with-open [z (GZIPOutputStream. out)] (.write z bs))
    (.toByteArray out)))

(deftest compressed-files
  (doseq [[v frames size] [["b34" 11 275204] ["b45" 3 296621] ["b50" 3 369366]]
          :let [path (str "test/fixtures/blend/" v "/transforms_compressed.blend")
                raw (slurp-bytes path)
                plain (bytes/decompress path raw)]]
    (testing v
      (is (= frames (count (bytes/zstd-frames path raw))))
      (is (= size (alength plain)))
      (let [bf (file/parse path raw)]
        (is (= (:blocks (fixture-facts v)) (count (:blocks bf))))
        (is (= [4.0 1.0 6.0] (file/fget (light bf) "loc"))))))
  (testing "a plain file is left as it is"
    (let [bs (slurp-bytes "test/fixtures/blend/b34/transforms.blend")]
      (is (identical? bs (bytes/decompress "plain" bs)))))
  (testing "gzip"
    (let [bs (slurp-bytes "test/fixtures/blend/b34/transforms.blend")
          gz (gzip bs)
          half (Arrays/copyOf gz (quot (alength gz) 2))]
      (is (Arrays/equals bs (bytes/decompress "g.blend" gz)))
      (is (= 557 (count (:blocks (file/parse "g.blend" gz)))))
      (is (= "g.blend: gzip data damaged or cut short (Unexpected end of ZLIB input stream)"
             (ex-message (error #(bytes/decompress "g.blend" half)))))))
  (testing "zstd cut short, or damaged"
    (let [raw (slurp-bytes "test/fixtures/blend/b34/transforms_compressed.blend")
          cut (Arrays/copyOf raw 30000)
          longer (Arrays/copyOf raw (+ (alength raw) 4))]
      (is (= "z.blend: zstd stream cut short in block at byte 13880 of 30000"
             (ex-message (error #(bytes/decompress "z.blend" cut)))))
      (is (= "z.blend: not a zstd frame at byte 69754"
             (ex-message (error #(bytes/zstd-frames "z.blend" longer)))))))
  (testing "growth is bounded"
    (let [raw (slurp-bytes "test/fixtures/blend/b34/transforms_compressed.blend")]
      (with-redefs [bytes/max-bytes 100000]
        (is (= "z.blend: decompresses to more than 100000 bytes"
               (ex-message (error #(bytes/decompress "z.blend" raw)))))))))
