;; The physics engine is chosen by profile (see org/engine.org): the default is
;; jme3-jbullet (pure Java); lein with-profile +native ... uses stephengold's
;; Minie (native Bullet) instead. Both use the packages com.jme3.bullet.*, so
;; they replace each other; these are the dependencies they share.
(def shared-dependencies
  '[[org.clojure/clojure "1.11.1"]
    [org.jmonkeyengine/jme3-core "3.2.4-stable"]
    [org.jmonkeyengine/jme3-desktop "3.2.4-stable"]
    ;; pure-Java zstd, for .blend files saved by Blender 3.0 and later
    [io.airlift/aircompressor "0.27"]
    ;; OpenGL through LWJGL 3: windows, and offscreen frames drawn
    ;; with EGL and no X server at all (cortex.render)
    [org.jmonkeyengine/jme3-lwjgl3 "3.2.4-stable"]
    [org.lwjgl/lwjgl-egl "3.2.1"]
    ;; lein run's options
    [org.clojure/tools.cli "1.1.230"]])

(def dev-dependencies
  '[[org.jmonkeyengine/jme3-blender "3.2.4-stable"]
    [org.clojure/test.check "1.1.1"]
    ;; (user/reset): reload what changed
    [org.clojure/tools.namespace "1.5.0"]])

(defproject cortex "0.1.0-SNAPSHOT"
  :description "Build physical creatures for jMonkeyEngine 3 from Blender files."
  :url "https://github.com/aurellem/cortex"
  :license {:name "GNU General Public License, version 3"
            :url "https://www.gnu.org/licenses/gpl-3.0.html"}
  ;; Leiningen's base profile wants nrepl 1.0.0 and org.nrepl/incomplete,
  ;; which Maven Central lacks; Debian's packages put them here.
  :repositories [["debian" {:url "file:///usr/share/maven-repo"
                            :checksum :ignore
                            :snapshots false}]]
  :dependencies ~(into shared-dependencies
                       '[[org.jmonkeyengine/jme3-jbullet "3.2.4-stable"
                          :exclusions [jbullet/jbullet stack-alloc/stack-alloc java3d/vecmath]]
                         [com.github.stephengold/jbullet "1.0.3"]])
  :source-paths ["src" "engine/jbullet/src"]
  ;; one target folder per profile set: classes compiled ahead of time for
  ;; an uberjar (lein with-profile +spark uberjar) never shadow the sources
  :target-path "target/%s/"
  :java-source-paths ["java" "engine/jbullet/java"]
  :resource-paths ["assets"]
  :javac-options ["--release" "11" "-Xlint:-options"]
  :jvm-opts ["-Djava.util.logging.config.file=logging.properties"]
  :main cortex.main
  ;; REPLs (lein repl, lein term, editors' jack-in) start in user: dev/user.clj
  :repl-options {:init-ns user
                 ;; what goes wrong at the REPL is said to be at the REPL, not in
                 ;; the temporary file Leiningen starts the server from
                 :init (when (thread-bound? #'*file* #'*source-path*)
                         (set! *file* "NO_SOURCE_PATH")
                         (set! *source-path* "NO_SOURCE_FILE"))}
  :aliases {"tangle" ["run" "-m" "cortex.tangle"]
            ;; lein term: a terminal REPL, for machines without Clojars, where
            ;; Leiningen's own client (REPLy) lives; it honours :repl-options,
            ;; so middleware injected the way editors do it is served too.
            ;; bin/lein term adds line editing (rlwrap). See org/repl.org.
            "term" ["trampoline" "run" "-m" "cortex.repl" :project/repl-options]
            ;; lein bench [--quick]: build and simulation timings; see org/bench.org
            "bench" ["run" "-m" "cortex.bench"]
            ;; lein engines: jBullet and native Bullet side by side; see org/engine.org
            "engines" ["do" ["run" "-m" "cortex.engine-speed" "--write"]
                       ["with-profile" "+native" "run" "-m" "cortex.engine-speed" "--write"]
                       ["run" "-m" "cortex.engine-speed" "--compare"]]
            ;; lein evolve: the worm learns to crawl; see org/evolve.org
            "evolve" ["run" "-m" "cortex.evolve"]}
  :profiles {:dev {;; engine/jbullet/dev: measuring tools that reach into jBullet
                   ;; (org/physics-trust.org), left out by the native profile
                   :source-paths ["dev" "engine/jbullet/dev"]
                   :dependencies ~dev-dependencies}
             ;; lein with-profile +native ...: native Bullet through Minie, in
             ;; place of jme3-jbullet; cortex's code is the same but for one
             ;; namespace (cortex.engine) and three Java classes, tangled twice
             ;; from org/engine.org. Minie 8.2.0 bundles its natives; it is
             ;; built against jME 3.6.1, whose jme3-core is kept out here so
             ;; that both engines run on the same jME (3.2.4).
             ;; engine/native/dev: measuring tools that reach into native
             ;; Bullet (org/featherstone.org), left out by the default profile
             :native {:source-paths ^:replace ["src" "engine/native/src" "dev" "engine/native/dev"]
                      :java-source-paths ^:replace ["java" "engine/native/java"]
                      :dependencies ~(with-meta
                                       (into (into shared-dependencies dev-dependencies)
                                             '[[com.github.stephengold/Minie "8.2.0"
                                                :exclusions [org.jmonkeyengine/jme3-core]]
                                               ;; what Leiningen's base profile adds,
                                               ;; which ^:replace drops
                                               [nrepl "1.0.0" :exclusions [org.clojure/clojure]]
                                               [org.nrepl/incomplete "0.1.0"
                                                :exclusions [org.clojure/clojure]]])
                                       {:replace true})
                      :target-path "target/native"}
             ;; lein with-profile +spark ...: cortex.spark runs rollouts as a Spark
             ;; job (see org/rollout.org); the base library never pulls Spark in
             :spark {:source-paths ["spark/src"]
                     :test-paths ["spark/test"]
                     :java-source-paths ["spark/java"]
                     :dependencies [[org.apache.spark/spark-core_2.13 "3.5.6"]
                                    [org.apache.spark/spark-sql_2.13 "3.5.6"]
                                    ;; Spark logs through log4j2 by slf4j 2 (avro's 1.7 would win)
                                    [org.slf4j/slf4j-api "2.0.7"]]
                     ;; Spark on Java 17: the module openings spark-submit adds
                     :jvm-opts ["-XX:+IgnoreUnrecognizedVMOptions"
                                "--add-opens=java.base/java.lang=ALL-UNNAMED"
                                "--add-opens=java.base/java.lang.invoke=ALL-UNNAMED"
                                "--add-opens=java.base/java.lang.reflect=ALL-UNNAMED"
                                "--add-opens=java.base/java.io=ALL-UNNAMED"
                                "--add-opens=java.base/java.net=ALL-UNNAMED"
                                "--add-opens=java.base/java.nio=ALL-UNNAMED"
                                "--add-opens=java.base/java.util=ALL-UNNAMED"
                                "--add-opens=java.base/java.util.concurrent=ALL-UNNAMED"
                                "--add-opens=java.base/java.util.concurrent.atomic=ALL-UNNAMED"
                                "--add-opens=java.base/jdk.internal.ref=ALL-UNNAMED"
                                "--add-opens=java.base/sun.nio.ch=ALL-UNNAMED"
                                "--add-opens=java.base/sun.nio.cs=ALL-UNNAMED"
                                "--add-opens=java.base/sun.security.action=ALL-UNNAMED"
                                "--add-opens=java.base/sun.util.calendar=ALL-UNNAMED"
                                "-Djdk.reflect.useDirectMethodHandle=false"]}})
