// Generated from org/rollout.org by lein tangle: edit the chapter, not this file.
package cortex.spark;

import org.apache.spark.api.java.function.Function;
import org.apache.spark.sql.Row;
import org.apache.spark.sql.RowFactory;

/** A Spark function from a rollout's EDN [index result] to its table
 *  row (cortex.rollout/columns), by cortex.spark/row-values. */
public final class RowFunction implements Function<String, Row> {
    private static final long serialVersionUID = 1L;

    @Override
    public Row call(String line) {
        return RowFactory.create((Object[]) RolloutFunction.Fns.ROW_VALUES.invoke(line));
    }
}
