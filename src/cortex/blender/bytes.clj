;; Generated from org/blend-format.org by lein tangle: edit the chapter, not this file.
(ns cortex.blender.bytes
  "A .blend file's bytes as they come: stored plain, gzipped or
  zstd-compressed, decompressed within a bound; and the error that
  names the file.

  Entry points: `decompress`, `zstd-frames`, `max-bytes`, `fail`."
  (:import [java.io ByteArrayInputStream ByteArrayOutputStream InputStream]
           [java.util.zip GZIPInputStream]
           [io.airlift.compress.zstd ZstdInputStream]))

(set! *warn-on-reflection* true)

(defn fail
  "Throw an ex-info whose message begins with the file's name."
  ([source msg] (fail source msg {}))
  ([source msg data]
   (throw (ex-info (str source ": " msg) (assoc data :file (str source))))))

(def max-bytes
  "The most bytes a decompressed file may have: Java arrays stop just
  short of 2 GiB, and an eighth of the heap leaves room for the copies
  a growing output buffer makes on the way."
  (long (min (- Integer/MAX_VALUE 64)
             (quot (.maxMemory (Runtime/getRuntime)) 8))))

(defn- drain
  "All bytes of stream `in`, refusing to grow past `max-bytes`."
  ^bytes [source ^InputStream in]
  (let [out (ByteArrayOutputStream.)
        buf (byte-array 65536)]
    (loop []
      (let [n (.read in buf)]
        (when (pos? n)
          (when (> (+ (.size out) n) max-bytes)
            (fail source (str "decompresses to more than " max-bytes " bytes")))
          (.write out buf 0 n)
          (recur))))
    (.toByteArray out)))

(defn- magic?
  "Does byte array `b` begin with the unsigned bytes `prefix`?"
  [^bytes b prefix]
  (and (>= (alength b) (count prefix))
       (every? true? (map-indexed (fn [i p] (= (bit-and (aget b i) 0xff) p))
                                  prefix))))

(defn- u8 ^long [^bytes b ^long i] (bit-and (aget b i) 0xff))

(defn- u32le ^long [^bytes b ^long i]
  (bit-or (u8 b i) (bit-shift-left (u8 b (+ i 1)) 8)
          (bit-shift-left (u8 b (+ i 2)) 16) (bit-shift-left (u8 b (+ i 3)) 24)))

(defn zstd-frames
  "The [start end] byte ranges of the data frames of zstd stream `b`,
  leaving out skippable frames (Blender 3.0+ appends a seek table in
  one, which the decoder refuses). Frame extents are found by walking
  block headers, so a cut stream is noticed here."
  [source ^bytes b]
  (let [n (alength b)
        need (fn [^long p ^long k what]
               (when (> (+ p k) n)
                 (fail source (str "zstd stream cut short in " what
                                   " at byte " p " of " n))))]
    (loop [p 0, frames []]
      (if (>= p n)
        frames
        (do
          (need p 4 "frame magic")
          (let [magic (u32le b p)]
            (cond
              (= (bit-and magic 0xFFFFFFF0) 0x184D2A50)
              (do (need p 8 "skippable frame")
                  (let [size (u32le b (+ p 4))
                        end (+ p 8 size)]
                    (need p (+ 8 size) "skippable frame")
                    (recur end frames)))

              (= magic 0xFD2FB528)
              (do
                (need p 5 "frame header")
                (let [fhd (u8 b (+ p 4))
                      single (bit-test fhd 5)
                      dict-size ([0 1 2 4] (bit-and fhd 3))
                      fcs-flag (bit-shift-right fhd 6)
                      fcs-size (case (int fcs-flag) 0 (if single 1 0) 1 2 2 4 3 8)
                      checksum (if (bit-test fhd 2) 4 0)
                      first-block (+ p 5 (if single 0 1) dict-size fcs-size)
                      end (loop [q first-block]
                            (need q 3 "block header")
                            (let [h (bit-or (u8 b q) (bit-shift-left (u8 b (+ q 1)) 8)
                                            (bit-shift-left (u8 b (+ q 2)) 16))
                                  last? (bit-test h 0)
                                  type (bit-and (bit-shift-right h 1) 3)
                                  size (bit-shift-right h 3)
                                  len (case (int type) 0 size 1 1 2 size
                                            (fail source (str "zstd block of reserved type at byte " q)))
                                  nq (+ q 3 len)]
                              (need q (+ 3 len) "block")
                              (if last? nq (recur nq))))]
                  (need end checksum "checksum")
                  (recur (long (+ (long end) checksum)) (conj frames [p (+ (long end) checksum)]))))

              :else
              (fail source (str "not a zstd frame at byte " p)))))))))

(defn decompress
  "The plain bytes of a .blend file: gzip (Blender before 3.0) and zstd
  (3.0 and later) are undone, anything else is returned as it is."
  ^bytes [source ^bytes raw]
  (cond
    (magic? raw [0x1F 0x8B])
    (try (drain source (GZIPInputStream. (ByteArrayInputStream. raw)))
         (catch java.io.IOException e
           (fail source (str "gzip data damaged or cut short (" (.getMessage e) ")"))))

    (magic? raw [0x28 0xB5 0x2F 0xFD])
    (let [out (ByteArrayOutputStream.)]
      (doseq [[^long s ^long e] (zstd-frames source raw)]
        (let [^bytes part (try (drain source (ZstdInputStream.
                                       (ByteArrayInputStream. raw s (- e s))))
                        (catch RuntimeException e
                          (if (instance? clojure.lang.ExceptionInfo e)
                            (throw e)
                            (fail source (str "zstd data damaged (" (.getMessage e) ")")))))]
          (when (> (+ (.size out) (alength part)) max-bytes)
            (fail source (str "decompresses to more than " max-bytes " bytes")))
          (.write out part 0 (alength part))))
      (.toByteArray out))

    :else raw))
