;; The four-legged creature rolled onto its side (ROLLS, radians about its length, jME's x; a quarter
;; turn each way by default), dropped limp for SECS (5) seconds in cortex, MuJoCo and PyBullet: the
;; centre of mass after 1 s and at the end, the fastest segment, where it ends across the floor.
;; Run from the repository root (add with-profile +native for native Bullet):
;; bin/lein run -m clojure.main notebook/limp/side.clj
(require '[cortex.export-test :as et] '[clojure.java.io :as io] '[cortex.util :as util] '[cortex.drops :as drops] '[cortex.plan :as plan] '[cortex.body :as body] '[cortex.engine :as engine])
(def manifest-entry @#'et/manifest-entry) (def check-export @#'et/check-export) (def cortex-drop @#'et/cortex-drop)
(def py (et/python))
(def out-dir "/tmp/side") (.mkdirs (io/file out-dir))
(def secs (Double/parseDouble (or (System/getenv "SECS") "5")))
(def rolls (read-string (or (System/getenv "ROLLS") "[1.5707963 -1.5707963]")))
(defn placed [roll]
  (let [c (util/load-blender-model "test/fixtures/designer/quadruped.blend")]
    (.rotate c (doto (com.jme3.math.Quaternion.) (.fromAngles (float roll) (float 0) (float 0))))
    (drops/lift! c)
    (let [p (plan/plan c)] (body/body! c) [c p])))
(def runs (vec (for [r rolls :let [[c p] (placed r)]]
                 {:r r :e (-> (manifest-entry (str "side" r) p out-dir) (assoc :name (str r) :seconds secs)
                              (dissoc :mjx_seconds :mjcf_inscribed :held :random_seconds :camera :track))
                  :cortex (cortex-drop c p nil secs "torso")})))
(def res (check-export py out-dir (map :e runs)))
(doseq [{:keys [r cortex]} runs
        :let [pb (get-in res [(str r) "urdf" "drop"]) mj (get-in res [(str r) "drop"])
              f (fn [who hs sp a] (format "%s %.3f/%.3f %.3f m/s (%.2f,%.2f)" who (nth hs 59) (peek hs) sp (first a) (second a)))]]
  (println (format "%s roll %.2f: " engine/name r)
           (f "cortex" (:heights cortex) (:rest-speed cortex) (peek (:across cortex)))
           "|" (f "MuJoCo" (mj "heights") (mj "rest_speed") (peek (mj "across")))
           "|" (f "PyBullet" (pb "heights") (pb "rest_speed") (peek (pb "across")))))
(shutdown-agents) (System/exit 0)
