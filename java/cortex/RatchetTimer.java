// Generated from org/world.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.jme3.system.Timer;

/**
 * A timer that ignores the wall clock: every frame advances simulated
 * time by exactly 1/fps seconds, however long the frame really took.
 * One tick is one frame, so time never accumulates rounding error.
 */
public final class RatchetTimer extends Timer {
    private final int fps;
    private long frames;

    public RatchetTimer(int fps) {
        if (fps <= 0) {
            throw new IllegalArgumentException("frames per second must be positive, not " + fps);
        }
        this.fps = fps;
    }

    /** Frames elapsed since the last reset. */
    @Override public long getTime() { return frames; }

    /** Ticks per second: one per frame. */
    @Override public long getResolution() { return fps; }

    @Override public float getFrameRate() { return fps; }

    @Override public float getTimePerFrame() { return 1f / fps; }

    @Override public void update() { frames++; }

    @Override public void reset() { frames = 0; }
}
