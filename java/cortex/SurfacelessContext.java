// Generated from org/render.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.jme3.input.JoyInput;
import com.jme3.input.KeyInput;
import com.jme3.input.MouseInput;
import com.jme3.input.TouchInput;
import com.jme3.input.dummy.DummyKeyInput;
import com.jme3.input.dummy.DummyMouseInput;
import com.jme3.system.AppSettings;
import com.jme3.system.JmeContext;
import com.jme3.system.NanoTimer;
import com.jme3.system.lwjgl.LwjglContext;
import java.nio.IntBuffer;
import java.util.concurrent.atomic.AtomicBoolean;
import org.lwjgl.PointerBuffer;
import org.lwjgl.egl.EGL;
import org.lwjgl.opengl.GL;
import org.lwjgl.system.JNI;

import static org.lwjgl.egl.EGL10.*;
import static org.lwjgl.egl.EGL12.EGL_RENDERABLE_TYPE;
import static org.lwjgl.egl.EGL12.eglBindAPI;
import static org.lwjgl.egl.EGL12.eglReleaseThread;
import static org.lwjgl.egl.EGL14.EGL_OPENGL_API;
import static org.lwjgl.egl.EGL14.EGL_OPENGL_BIT;

/**
 * A jME context that draws into an offscreen framebuffer made with
 * Mesa's EGL surfaceless platform: real OpenGL, no window, no X server.
 * Select it with settings.setRenderer("CUSTOMcortex.SurfacelessContext")
 * and start the application with JmeContext.Type.OffscreenSurface.
 * Keyboard and mouse are dummies: nothing can press a key here.
 */
public final class SurfacelessContext extends LwjglContext implements Runnable {
    /** EGL_PLATFORM_SURFACELESS_MESA, from EGL_MESA_platform_surfaceless. */
    private static final int SURFACELESS = 0x31DD;
    private static final String PACKAGES =
        "on Debian: apt-get install libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri";

    private final AtomicBoolean needClose = new AtomicBoolean();
    private final DummyKeyInput keys = new DummyKeyInput();
    private final DummyMouseInput mouse = new DummyMouseInput();
    private volatile Thread thread;
    private long display = EGL_NO_DISPLAY;
    private long surface = EGL_NO_SURFACE;
    private long context = EGL_NO_CONTEXT;
    /** Every context of this class shares the one surfaceless EGLDisplay,
     *  and eglTerminate ends it for all of them: contexts made and ended
     *  at once on several threads (simulations with eyes, see vision.org)
     *  count their use of it under this lock, and the last one out
     *  terminates it. */
    private static final Object EGL_LOCK = new Object();
    private static int eglUsers = 0;
    private boolean counted = false;

    /** Keep the caller's settings, but render with jME's LWJGL OpenGL
     *  renderer: the CUSTOM name only served to find this class. */
    @Override public void setSettings(AppSettings s) {
        super.setSettings(s);
        String r = settings.getRenderer();
        if (r == null || !r.startsWith("LWJGL")) settings.setRenderer(AppSettings.LWJGL_OPENGL2);
    }

    @Override public JmeContext.Type getType() { return JmeContext.Type.OffscreenSurface; }
    @Override public MouseInput getMouseInput() { return mouse; }
    @Override public KeyInput getKeyInput() { return keys; }
    @Override public JoyInput getJoyInput() { return null; }
    @Override public TouchInput getTouchInput() { return null; }
    @Override public void setTitle(String title) { }
    @Override public void setAutoFlushFrames(boolean enabled) { }
    @Override public void restart() { }

    @Override public void create(boolean waitFor) {
        if (thread != null) return;
        thread = new Thread(this, "cortex surfaceless OpenGL");
        thread.start();
        if (waitFor) await(true);
    }

    @Override public void destroy(boolean waitFor) {
        needClose.set(true);
        if (waitFor) await(false);
    }

    /** Wait until created is `value`, or until the loop's thread has
     *  died, so that a context that failed to start never hangs us. */
    private void await(boolean value) {
        synchronized (createdLock) {
            while (created.get() != value && thread != null && thread.isAlive()) {
                try { createdLock.wait(100); }
                catch (InterruptedException e) { Thread.currentThread().interrupt(); return; }
            }
        }
    }

    private static void check(boolean ok, String what) {
        if (!ok) {
            throw new IllegalStateException(what + " failed (EGL error 0x"
                                            + Integer.toHexString(eglGetError()) + ")");
        }
    }

    private void createEgl() {
        synchronized (EGL_LOCK) { createEglLocked(); }
    }

    private void createEglLocked() {
        String clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (clientExtensions == null || !clientExtensions.contains("EGL_MESA_platform_surfaceless")) {
            throw new IllegalStateException("EGL has no surfaceless platform (Mesa's EGL is needed; "
                                            + PACKAGES + ")");
        }
        // LWJGL's binding insists on a native display; surfaceless has none
        long getPlatformDisplay = EGL.getCapabilities().eglGetPlatformDisplayEXT;
        check(getPlatformDisplay != 0L, "finding eglGetPlatformDisplayEXT");
        display = JNI.callPPP(getPlatformDisplay, SURFACELESS, 0L, 0L);
        check(display != EGL_NO_DISPLAY, "eglGetPlatformDisplayEXT(surfaceless)");
        check(eglInitialize(display, new int[1], new int[1]), "eglInitialize");
        eglUsers++;
        counted = true;
        check(eglBindAPI(EGL_OPENGL_API), "eglBindAPI(OpenGL)");
        int depth = settings.getDepthBits() > 0 ? settings.getDepthBits() : 24;
        int[] wanted = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                        EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
                        EGL_DEPTH_SIZE, depth, EGL_STENCIL_SIZE, settings.getStencilBits(),
                        EGL_NONE};
        PointerBuffer configs = PointerBuffer.allocateDirect(1);
        int[] found = new int[1];
        check(eglChooseConfig(display, wanted, configs, found) && found[0] > 0,
              "eglChooseConfig(RGBA8, depth " + depth + ", pbuffer)");
        long config = configs.get(0);
        surface = eglCreatePbufferSurface(display, config, new int[]{
                EGL_WIDTH, settings.getWidth(), EGL_HEIGHT, settings.getHeight(), EGL_NONE});
        check(surface != EGL_NO_SURFACE,
              "eglCreatePbufferSurface(" + settings.getWidth() + "x" + settings.getHeight() + ")");
        context = eglCreateContext(display, config, EGL_NO_CONTEXT, (IntBuffer) null);
        check(context != EGL_NO_CONTEXT, "eglCreateContext");
        check(eglMakeCurrent(display, surface, surface, context), "eglMakeCurrent");
    }

    private void destroyEgl() {
        synchronized (EGL_LOCK) {
            if (display != EGL_NO_DISPLAY) {
                eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
                if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
                if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
                if (counted && --eglUsers == 0) eglTerminate(display);
                counted = false;
                eglReleaseThread();
                GL.setCapabilities(null);
            }
            display = EGL_NO_DISPLAY;
            surface = EGL_NO_SURFACE;
            context = EGL_NO_CONTEXT;
        }
    }

    /** The frame loop: make the context, let the application initialise,
     *  then update (which draws) until asked to close; always tear down,
     *  telling the application, whatever went wrong. */
    @Override public void run() {
        boolean started = false;
        try {
            timer = new NanoTimer();
            createEgl();
            internalCreate();
            listener.initialize();
            started = true;
        } catch (Throwable t) {
            listener.handleError("cortex could not open an offscreen OpenGL context ("
                                 + PACKAGES + ")", t);
        }
        try {
            while (started && !needClose.get()) {
                listener.update();
                if (renderer != null) renderer.postFrame();
            }
        } catch (Throwable t) {
            listener.handleError("offscreen frame failed", t);
        } finally {
            try {
                listener.destroy();
            } finally {
                try {
                    // forget every GL object jME made: cached shaders and
                    // textures would otherwise keep names from this context
                    // and draw nothing in the next one
                    if (renderer != null && created.get()) renderer.cleanup();
                } finally {
                    try { destroyEgl(); } finally { internalDestroy(); }
                }
            }
        }
    }
}
