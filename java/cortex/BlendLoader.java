// Generated from org/blender.org by lein tangle: edit the chapter, not this file.
package cortex;

import clojure.java.api.Clojure;
import clojure.lang.IFn;
import com.jme3.asset.AssetInfo;
import com.jme3.asset.AssetLoader;
import java.io.IOException;

/**
 * jME's door to cortex's .blend reader: register it for "blend" and
 * AssetManager.loadModel reads .blend files with cortex.blender.
 * All the work is done by the Clojure function
 * cortex.blender/load-asset-info, loaded on first use.
 */
public class BlendLoader implements AssetLoader {
    private static volatile IFn load;

    private static IFn loader() {
        IFn f = load;
        if (f == null) {
            synchronized (BlendLoader.class) {
                if (load == null) {
                    IFn require = Clojure.var("clojure.core", "require");
                    require.invoke(Clojure.read("cortex.blender"));
                    load = Clojure.var("cortex.blender", "load-asset-info");
                }
                f = load;
            }
        }
        return f;
    }

    @Override
    public Object load(AssetInfo info) throws IOException {
        return loader().invoke(info);
    }
}
