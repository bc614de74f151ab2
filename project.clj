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
  :dependencies [[org.clojure/clojure "1.11.1"]
                 [org.jmonkeyengine/jme3-core "3.2.4-stable"]
                 [org.jmonkeyengine/jme3-desktop "3.2.4-stable"]
                 [org.jmonkeyengine/jme3-jbullet "3.2.4-stable"
                  :exclusions [jbullet/jbullet stack-alloc/stack-alloc java3d/vecmath]]
                 [com.github.stephengold/jbullet "1.0.3"]
                 ;; pure-Java zstd, for .blend files saved by Blender 3.0 and later
                 [io.airlift/aircompressor "0.27"]
                 ;; OpenGL through LWJGL 3: windows, and offscreen frames drawn
                 ;; with EGL and no X server at all (cortex.render)
                 [org.jmonkeyengine/jme3-lwjgl3 "3.2.4-stable"]
                 [org.lwjgl/lwjgl-egl "3.2.1"]
                 ;; lein run's options
                 [org.clojure/tools.cli "1.1.230"]]
  :source-paths ["src"]
  :java-source-paths ["java"]
  :resource-paths ["assets"]
  :javac-options ["--release" "11" "-Xlint:-options"]
  :jvm-opts ["-Djava.util.logging.config.file=logging.properties"]
  :main cortex.main
  :aliases {"tangle" ["run" "-m" "cortex.tangle"]
            ;; Leiningen's REPL client (REPLy) is only on Clojars; see cortex.repl
            "repl" ["trampoline" "run" "-m" "cortex.repl"]
            ;; lein bench [--quick]: build and simulation timings; see org/bench.org
            "bench" ["run" "-m" "cortex.bench"]}
  :profiles {:dev {:source-paths ["dev"]
                   :dependencies [[org.jmonkeyengine/jme3-blender "3.2.4-stable"]
                                  [org.clojure/test.check "1.1.1"]]}})
