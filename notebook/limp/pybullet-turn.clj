;; PyBullet's and MuJoCo's limp drops of the four-legged creature turned about the vertical (HEADINGS,
;; radians; the export test's twelve by default) for SECS (30) seconds: the centre of mass after 1 s
;; and at the end, and the fastest segment over the last half second. Run from the repository root:
;; bin/lein run -m clojure.main notebook/limp/pybullet-turn.clj
(require '[cortex.export-test :as et] '[clojure.java.io :as io])
(def placed @#'et/placed) (def manifest-entry @#'et/manifest-entry) (def check-export @#'et/check-export)
(def py (et/python))
(def out-dir "/tmp/pbturn") (.mkdirs (io/file out-dir))
(def secs (Double/parseDouble (or (System/getenv "SECS") "30")))
(def hs (read-string (or (System/getenv "HEADINGS") "[0.0 0.5235987755982988 1.0471975511965976 1.5707963267948966 2.0943951023931953 2.6179938779938976 3.141592653589793 3.6651914291880923 4.1887902047863905 4.71238898038469 5.235987755982989 5.759586531581287]")))
(def entries (vec (for [h hs :let [[c p] (placed "quadruped" h)
                                   e (manifest-entry (str "q" h) p out-dir)]]
                    (-> e (assoc :name (str h) :seconds secs :compile_only false)
                        (dissoc :mjx_seconds :mjcf_inscribed :held :random_seconds :camera :track)))))
(def r (check-export py out-dir entries))
(doseq [h hs :let [{{:strs [heights rest_speed]} "drop"} (get-in r [(str h) "urdf"])
                   {mh "heights" mr "rest_speed"} (get-in r [(str h) "drop"])]]
  (println (format "heading %.2f PyBullet 1 s %.3f end %.3f speed %.3f | MuJoCo 1 s %.3f end %.3f speed %.3f"
                   h (nth heights 59) (peek heights) rest_speed (nth mh 59) (peek mh) mr)))
(shutdown-agents) (System/exit 0)
