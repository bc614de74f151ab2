// Generated from org/rollout.org by lein tangle: edit the chapter, not this file.
package cortex.spark;

import clojure.java.api.Clojure;
import clojure.lang.IFn;
import org.apache.spark.api.java.function.Function;

/** A Spark function that runs one rollout: EDN [index spec] in, EDN
 *  [index result] out, by cortex.spark/run-line. Stateless, so any
 *  executor can run it. */
public final class RolloutFunction implements Function<String, String> {
    private static final long serialVersionUID = 1L;

    /** cortex.spark's functions, loaded once per JVM. */
    static final class Fns {
        static final IFn RUN_LINE;
        static final IFn ROW_VALUES;
        static {
            Clojure.var("clojure.core", "require").invoke(Clojure.read("cortex.spark"));
            RUN_LINE = Clojure.var("cortex.spark", "run-line");
            ROW_VALUES = Clojure.var("cortex.spark", "row-values");
        }
    }

    @Override
    public String call(String line) {
        return (String) Fns.RUN_LINE.invoke(line);
    }
}
