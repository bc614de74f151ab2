;; Generated from org/evolve.org by lein tangle: edit the chapter, not this file.
(ns cortex.evolve
  "The worm learns to crawl: a (mu/mu, lambda)-ES with self-adapted
  step size over its gait's frequency, amplitude and rise, every
  generation's rollouts run by cortex.rollout/rollouts (or
  cortex.spark/run). lein evolve [options]; see org/evolve.org.

  Entry points: `evolve` (the strategy, on any fitness), `worm-fitness`,
  `plot!`, `record-gait!`, `learn!` (what lein evolve does), `-main`."
  (:require [clojure.java.io :as io]
            [clojure.string :as str]
            [clojure.tools.cli :as cli]
            [cortex.demo :as demo]
            [cortex.render :as render]
            [cortex.rollout :as r]
            [cortex.sim :as sim])
  (:import (java.awt BasicStroke Color Font Graphics2D RenderingHints)
           (java.awt.image BufferedImage)
           (java.util Random)
           (javax.imageio ImageIO)))

(set! *warn-on-reflection* true)

(def genes
  "The gait's genes: crawl-gait's parameters, with their bounds."
  [{:name :frequency :min 0.3 :max 4.0}
   {:name :amplitude :min 0.05 :max 0.8}
   {:name :rise :min 0.05 :max 0.95}])

(defn decode
  "The crawl-gait parameters of genes `x`, each in [0, 1]."
  [x]
  (into {} (map (fn [{:keys [name min max]} v]
                  [name (+ (double min) (* (double v) (- (double max) (double min))))])
                genes x)))

(defn encode
  "The genes, in [0, 1], of crawl-gait parameters `params`."
  [params]
  (mapv (fn [{:keys [name min max]}]
          (/ (- (double (get params name)) min) (- (double max) (double min))))
        genes))

(def hand-tuned
  "The simulation chapter's gait."
  {:frequency 1.5 :amplitude 0.6 :rise 0.8})

(def poor-start
  "Where the search starts: a slow, shallow, even gait."
  {:frequency 0.5 :amplitude 0.15 :rise 0.5})

(defn- clip01 ^double [^double v] (max 0.0 (min 1.0 v)))

(defn children
  "The `lambda` children of `mean` with step size `sigma`, drawn from
  `rng`: [{:x genes :sigma s}]."
  [^Random rng mean sigma lambda]
  (let [tau (/ 1.0 (Math/sqrt (* 2.0 (count mean))))]
    (vec (repeatedly lambda
                     #(let [s (* (double sigma) (Math/exp (* tau (.nextGaussian rng))))]
                        {:sigma s
                         :x (mapv (fn [m] (clip01 (+ (double m) (* s (.nextGaussian rng))))) mean)})))))

(defn evolve
  "Run the ES for :generations (12) with :lambda children (10), :mu
  parents (3), from genes :start (0.5 each) with step size :sigma
  (0.15), seeded by :seed (1); `fitness` maps a vector of gene vectors
  to their fitnesses. Calls (report entry) after every generation.
  Returns the history: a vector of {:generation :best :mean :sigma
  :best-x :mean-x :best-ever}, :best-ever being the fittest child so
  far, {:x :fitness :generation}."
  [fitness {:keys [generations lambda mu start sigma seed report]
            :or {generations 12 lambda 10 mu 3 sigma 0.15 seed 1 report (fn [_])}}]
  (let [start (or start (vec (repeat (count genes) 0.5)))]
    (loop [g 1 mean start sigma (double sigma) best-ever nil history []]
      (if (> g generations)
        history
        (let [rng (Random. (+ (* 1000003 (long seed)) g))
              kids (children rng mean sigma lambda)
              fs (vec (fitness (mapv :x kids)))
              ranked (sort-by (comp - double second) (map vector kids fs))
              parents (map first (take mu ranked))
              [best-kid best-f] (first ranked)
              best-ever (if (or (nil? best-ever) (> (double best-f) (double (:fitness best-ever))))
                          {:x (:x best-kid) :fitness best-f :generation g}
                          best-ever)
              entry {:generation g :best best-f :mean (/ (reduce + fs) (count fs))
                     :sigma sigma :best-x (:x best-kid) :mean-x mean :best-ever best-ever}
              new-mean (apply mapv (fn [& vs] (/ (reduce + vs) (count vs))) (map :x parents))
              new-sigma (Math/exp (/ (reduce + (map #(Math/log (:sigma %)) parents)) (count parents)))]
          (report entry)
          (recur (inc g) new-mean new-sigma best-ever (conj history entry)))))))

(def worm "Models/test-creature/worm.blend")

(defn gait-spec
  "The rollout of the gait `params` from start `seed`."
  [params seed seconds]
  {:creature worm :controller 'cortex.rollout/crawl-gait :params params
   :seconds seconds :seed seed :start {:shift 0.3 :turn 0.2}})

(defn crawl-score
  "How far a rollout's result went towards the worm's head (-x); 0 when
  it fell over or failed."
  ^double [{:keys [displacement fell? error]}]
  (if (or error fell?) 0.0 (- (double (first displacement)))))

(defn worm-fitness
  "A fitness for `evolve`: each gene vector's gait run from `starts`
  starts (seeds 1 to starts) for `seconds`, all of a generation in one
  call of `run` (cortex.rollout/rollouts, or a Spark job), scored by
  `crawl-score`, averaged over the starts."
  [run starts seconds]
  (fn [xs]
    (let [specs (vec (for [x xs seed (range 1 (inc starts))]
                       (gait-spec (decode x) seed seconds)))
          scores (map crawl-score (run specs))]
      (mapv #(/ (reduce + %) starts) (partition starts scores)))))

(defn plot!
  "Draw `history` (see `evolve`) as a PNG at `file`, `reference` (a
  fitness, or nil) as a dotted line; return the file's path."
  [history reference file]
  (let [w 800 h 480 left 70 right 20 top 40 bottom 60
        img (BufferedImage. w h BufferedImage/TYPE_INT_RGB)
        ^Graphics2D g (.createGraphics img)
        gens (map :generation history)
        ys (concat (map :best history) (map :mean history) (when reference [reference]) [0.0])
        y-min (min 0.0 (apply min ys))
        y-max (let [m (apply max ys)] (if (= m y-min) (+ y-min 1.0) (* 1.1 m)))
        g-max (max 2 (apply max gens))
        px (fn [gen] (+ left (* (- w left right) (/ (- (double gen) 1) (- g-max 1)))))
        py (fn [y] (- h bottom (* (- h top bottom) (/ (- (double y) y-min) (- y-max y-min)))))
        line! (fn [pts ^Color c ^BasicStroke s]
                (.setColor g c) (.setStroke g s)
                (doseq [[[x1 y1] [x2 y2]] (partition 2 1 pts)]
                  (.drawLine g (int x1) (int y1) (int x2) (int y2)))
                (doseq [[x y] pts] (.fillOval g (- (int x) 3) (- (int y) 3) 7 7)))]
    (.setRenderingHint g RenderingHints/KEY_ANTIALIASING RenderingHints/VALUE_ANTIALIAS_ON)
    (.setColor g Color/WHITE) (.fillRect g 0 0 w h)
    (.setFont g (Font. Font/SANS_SERIF Font/PLAIN 13))
    ;; axes, ticks and labels
    (.setColor g Color/DARK_GRAY) (.setStroke g (BasicStroke. 1.0))
    (.drawLine g left (- h bottom) (- w right) (- h bottom))
    (.drawLine g left top left (- h bottom))
    (doseq [i (range 6)
            :let [y (+ y-min (* i (/ (- y-max y-min) 5)))]]
      (.drawLine g (- left 4) (int (py y)) left (int (py y)))
      (.drawString g (format "%.1f" y) 20 (int (+ 5 (py y)))))
    (doseq [gen gens :when (or (<= g-max 20) (zero? (mod gen 5)) (= gen 1))]
      (.drawString g (str gen) (int (- (px gen) 4)) (+ (- h bottom) 18)))
    (.drawString g "generation" (int (/ w 2)) (- h 18))
    (.drawString g "fitness: units crawled towards the head" 10 20)
    (when reference
      (.setColor g (Color. 120 120 120))
      (.setStroke g (BasicStroke. 1.5 BasicStroke/CAP_BUTT BasicStroke/JOIN_MITER 10.0
                                  (float-array [6 6]) 0.0))
      (.drawLine g left (int (py reference)) (- w right) (int (py reference)))
      (.drawString g (format "hand-tuned gait %.2f" (double reference)) (+ left 8) (int (- (py reference) 6))))
    (line! (map (fn [e] [(px (:generation e)) (py (:mean e))]) history)
           (Color. 70 130 200) (BasicStroke. 2.0))
    (line! (map (fn [e] [(px (:generation e)) (py (:best e))]) history)
           (Color. 200 60 40) (BasicStroke. 2.5))
    (.setColor g (Color. 200 60 40)) (.drawString g "best" (- w 140) 20)
    (.setColor g (Color. 70 130 200)) (.drawString g "mean" (- w 80) 20)
    (.dispose g)
    (io/make-parents (io/file file))
    (ImageIO/write img "png" (io/file file))
    (str file)))

(defn record-gait!
  "Record the rollout of `spec` offscreen into folder `dir` (frames, then
  DIR/NAME.mp4 and .gif), lit as the demo is and framed on the whole
  path the creature takes; return what render/make-videos! returns."
  [spec dir]
  (let [s (r/check-spec! nil spec)
        d (:displacement (r/run-checked s))
        sim (r/simulation s)
        [lo hi] (demo/bounds (:creature sim))
        w (sim/world sim (r/controller s)
                     (fn [world]
                       (demo/light! world)
                       (demo/frame! world (mapv min lo (mapv + lo d)) (mapv max hi (mapv + hi d)))))
        frames (long (Math/round (* 60.0 (double (:seconds s)))))]
    (render/record! w dir {:progress nil})
    (render/run-offscreen! w frames {:size [640 360]})
    (render/make-videos! dir 60)))

(def cli-options
  [["-g" "--generations N" "generations" :default 12 :parse-fn parse-long :validate [pos? "at least 1"]]
   ["-l" "--lambda N" "children a generation" :default 10 :parse-fn parse-long :validate [pos? "at least 1"]]
   ["-m" "--mu N" "parents a generation" :default 3 :parse-fn parse-long :validate [pos? "at least 1"]]
   ["-k" "--starts N" "starts (seeds) each gait is run from" :default 2 :parse-fn parse-long
    :validate [pos? "at least 1"]]
   ["-s" "--seconds S" "simulated seconds a rollout" :default 10.0 :parse-fn parse-double
    :validate [pos? "more than 0"]]
   [nil "--seed N" "the run's seed" :default 1 :parse-fn parse-long]
   ["-t" "--threads N" "threads for rollouts (default: every core)" :parse-fn parse-long
    :validate [pos? "at least 1"]]
   [nil "--spark MASTER" "run each generation as a Spark job (needs the spark profile)"]
   ["-o" "--out FOLDER" "where the plot, history and video go" :default "out/evolve"]
   [nil "--no-video" "skip recording the best gait"]
   ["-h" "--help" "say how to use lein evolve"]])

(defn- runner
  "What runs a generation's specs."
  [{:keys [spark threads]}]
  (if spark
    (let [run (or (try (requiring-resolve 'cortex.spark/run) (catch Exception _ nil))
                  (throw (ex-info "--spark needs the spark profile: lein with-profile +spark evolve ..." {})))]
      #(run % {:master spark}))
    #(r/rollouts % {:threads threads})))

(defn- history-csv [history]
  (str "generation,best,mean,sigma,best_frequency,best_amplitude,best_rise\n"
       (str/join (for [{:keys [generation best mean sigma best-x]} history
                       :let [{:keys [frequency amplitude rise]} (decode best-x)]]
                   (str (str/join "," [generation best mean sigma frequency amplitude rise]) "\n")))))

(defn- params-text [{:keys [frequency amplitude rise]}]
  (format "%.2f Hz, %.2f rad, rise %.2f" (double frequency) (double amplitude) (double rise)))

(defn learn!
  "Evolve the worm's gait with `opts` (see `cli-options`); print each
  generation, write the plot, history and video under :out. Returns
  {:history :best :reference :files}."
  [{:keys [generations lambda mu starts seconds seed out no-video] :as opts}]
  (let [run (runner opts)
        fitness (worm-fitness run starts seconds)
        t0 (System/nanoTime)
        _ (println (format "the worm learns to crawl: %d generations of %d gaits, %d starts each, %.0f s each"
                           generations lambda starts (double seconds)))
        reference (first (fitness [(encode hand-tuned)]))
        _ (println (format "the hand-tuned gait (%s) scores %.3f" (params-text hand-tuned) reference))
        history (evolve fitness
                        {:generations generations :lambda lambda :mu mu :seed seed
                         :start (encode poor-start)
                         :report (fn [{:keys [generation best mean sigma best-x]}]
                                   (println (format "generation %3d  best %6.3f  mean %6.3f  sigma %.3f  best gait %s"
                                                    generation (double best) (double mean) (double sigma)
                                                    (params-text (decode best-x))))
                                   (flush))})
        {:keys [x fitness generation]} (:best-ever (peek history))
        best (decode x)
        png (plot! history reference (io/file out "fitness.png"))
        files (cond-> [png]
                true (conj (do (spit (io/file out "history.edn") (r/edn history)) (str (io/file out "history.edn"))))
                true (conj (do (spit (io/file out "history.csv") (history-csv history)) (str (io/file out "history.csv")))))]
    (println (format "best gait (generation %d): %s, scores %.3f (hand-tuned %.3f); took %.0f s"
                     generation (params-text best) (double fitness) (double reference)
                     (/ (- (System/nanoTime) t0) 1e9)))
    (let [videos (when-not no-video
                   (println "recording the best gait offscreen ...")
                   (record-gait! (gait-spec best 1 seconds) (str (io/file out "best-gait"))))
          files (into files (vals videos))]
      (doseq [f files] (println "wrote" f))
      {:history history :best best :reference reference :files files})))

(defn -main
  "lein evolve [options]: see `cli-options`, or lein evolve --help."
  [& args]
  (let [{:keys [options errors summary]} (cli/parse-opts args cli-options)]
    (cond
      (:help options) (println (str "lein evolve [options]: the worm learns to crawl\n" summary))
      errors (do (binding [*out* *err*] (run! println errors)) (System/exit 2))
      :else (learn! options))
    (shutdown-agents)))
