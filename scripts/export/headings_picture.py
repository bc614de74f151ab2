#!/usr/bin/env python3
"""doc/export-headings.png: the limp four-legged creature 30 s after its
drop in MuJoCo, turned about the vertical by 0, 30, ..., 330 degrees,
with MuJoCo's pyramidal friction cone (the top two rows) and with the
elliptic one (the bottom two); org/export.org, "The four-legged
creature's two rests".

    $CORTEX_PYTHON scripts/export/headings_picture.py OUT.png FILE.xml...

The files are the twelve turned documents in heading order, as the test
cortex.export-test/the-four-legged-creature-rests-as-mujocos-does
writes them (notebook/limp/turn.clj writes the same: HEADINGS="[0.0
0.5236 ... 5.7596]" SECS=1 WRITE=1). Each is dropped as check_export.py
drops it (a floor plane at z = 0, actuation off) and drawn from behind,
along its torso (orange), a little above: on its belly its legs are
under it, on its side they point sideways.
"""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_check import choose_gl, write_png  # noqa: E402

SECONDS = 30.0
W, H = 240, 180
GROUND, TORSO, LIMBS = [0.62, 0.68, 0.55, 1], [0.9, 0.55, 0.2, 1], [0.75, 0.75, 0.72, 1]


def tile(mujoco, check, path, cone):
    """The RGB tile of the creature in `path` after SECONDS, friction cone
    `cone`, and its centre of mass's height then."""
    m, err = check.load_on_floor(path)
    if m is None:
        sys.exit(f"{path}: {err}")
    m.opt.cone = cone
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    m.vis.global_.offwidth, m.vis.global_.offheight = max(W, 640), max(H, 480)
    m.vis.headlight.ambient[:] = [0.45, 0.45, 0.45]
    m.vis.headlight.diffuse[:] = [0.6, 0.6, 0.6]
    for g in range(m.ngeom):
        body = m.body(m.geom_bodyid[g]).name
        m.geom_rgba[g] = (GROUND if m.geom_bodyid[g] == 0
                          else TORSO if body == "torso" else LIMBS)
    d = mujoco.MjData(m)
    for _ in range(round(SECONDS / m.opt.timestep)):
        mujoco.mj_step(m, d)
    across = check.com_across(m, d.xipos)
    # from behind, along the torso's length (its own x), so that a belly
    # rest shows the legs under it and a side rest shows them sideways
    x = d.xmat[m.body("torso").id].reshape(3, 3)[:, 0]
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    cam.lookat[:] = [across[0], across[1], 0.4]
    cam.distance, cam.elevation = 4.5, -15.0
    cam.azimuth = float(np.degrees(np.arctan2(x[1], x[0])))
    r = mujoco.Renderer(m, H, W)
    r.update_scene(d, camera=cam)
    rgb = np.array(r.render())
    r.close()
    return rgb, check.com_height(m, d.xipos)


def main():
    gl, why = choose_gl()
    if gl is None:
        sys.exit(f"no GL context for MuJoCo's renderer ({why})")
    os.environ["MUJOCO_GL"] = gl
    import mujoco
    import check_export as check

    out, files = sys.argv[1], sys.argv[2:]
    rows = []
    for cone, name in [(mujoco.mjtCone.mjCONE_PYRAMIDAL, "pyramidal"),
                       (mujoco.mjtCone.mjCONE_ELLIPTIC, "elliptic")]:
        tiles = []
        for k, path in enumerate(files):
            rgb, h = tile(mujoco, check, path, cone)
            print(f"{name}, turned {30 * k} degrees: centre of mass {h:.3f} m", flush=True)
            rgb[:2, :] = rgb[-2:, :] = rgb[:, :2] = rgb[:, -2:] = 255
            tiles.append(rgb)
        half = len(tiles) // 2
        rows += [np.hstack(tiles[:half]), np.hstack(tiles[half:])]
    write_png(out, np.ascontiguousarray(np.vstack(rows)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
