#!/usr/bin/env python3
"""MuJoCo's half of doc/export-side-by-side.png (org/export.org, "One
creature in both").

    $CORTEX_PYTHON scripts/export/side_by_side.py SCENE.json OUT.png

Run by cortex.export-picture (bin/lein run -m cortex.export-picture),
which writes SCENE.json, draws cortex's half, and puts the two together.

SCENE.json: {"mjcf": path, "floor": the floor's top (Z up), "seconds":
how long the creature falls, "width", "height": the picture's size,
"camera": {"pos", "forward", "up" (Z up), "fovy" (degrees)}, "sky",
"ground": [r g b] (0 to 1), "colours": {segment: [r g b]}}.

The creature is dropped as the exporter's checks drop it
(scripts/export/check_export.py): a floor plane of friction 0 at the
floor's height (MuJoCo takes the larger of two frictions, so each
segment's own rules, as on cortex's floor of friction 1, where Bullet
multiplies), actuation off (limp: cortex's creature is sent no
actions), for "seconds". Then it is drawn from the given camera, with a
sky and ground of cortex's colours, each segment in its colour in
cortex, and a sun; the picture is written to OUT.png. Prints the
centre of mass's height at the end.
"""

import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_check import choose_gl, write_png  # noqa: E402


def main():
    scene = json.load(open(sys.argv[1]))
    gl, why = choose_gl()
    if gl is None:
        sys.exit(f"no GL context for MuJoCo's renderer ({why})")
    os.environ["MUJOCO_GL"] = gl
    import mujoco
    import numpy as np

    w, h = scene["width"], scene["height"]
    spec = mujoco.MjSpec.from_file(scene["mjcf"])
    spec.visual.global_.offwidth = max(w, 640)
    spec.visual.global_.offheight = max(h, 480)
    spec.visual.quality.shadowsize = 4096
    sky = scene["sky"]
    spec.add_texture(name="sky", type=mujoco.mjtTexture.mjTEXTURE_SKYBOX,
                     builtin=mujoco.mjtBuiltin.mjBUILTIN_FLAT, rgb1=sky, rgb2=sky,
                     width=64, height=64)
    world = spec.worldbody
    floor = world.add_geom()
    floor.name = "floor"
    floor.type = mujoco.mjtGeom.mjGEOM_PLANE
    floor.size = [0.0, 0.0, 1.0]
    floor.pos = [0.0, 0.0, scene["floor"]]
    floor.friction = [0.0, 0.005, 0.0001]
    floor.rgba = scene["ground"] + [1.0]
    sun = world.add_light()
    sun.type = mujoco.mjtLightType.mjLIGHT_DIRECTIONAL
    # cortex's sun (cortex.demo/light!), from jME's (0.35, -1, -0.45)
    sun.dir = [0.35, 0.45, -1.0]
    sun.pos = [-3.5, -4.5, 10.0]
    sun.diffuse = [0.75, 0.75, 0.7]
    sun.castshadow = True
    c = scene["camera"]
    forward = np.array(c["forward"], dtype=float)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, c["up"])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    # MuJoCo's camera looks along its -Z, its Y up, its X to the right
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.column_stack([right, up, -forward]).ravel())
    cam = world.add_camera()
    cam.name = "side-by-side"
    cam.pos = c["pos"]
    cam.quat = quat
    cam.fovy = c["fovy"]
    m = spec.compile()
    m.vis.headlight.ambient = [0.35, 0.35, 0.35]
    m.vis.headlight.diffuse = [0.3, 0.3, 0.3]
    m.vis.map.znear = 0.05 / m.stat.extent
    for g in range(m.ngeom):
        body = m.body(m.geom_bodyid[g]).name
        if body in scene["colours"]:
            m.geom_rgba[g] = scene["colours"][body] + [1.0]
    d = mujoco.MjData(m)
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    for _ in range(round(scene["seconds"] / m.opt.timestep)):
        mujoco.mj_step(m, d)
    mass = m.body_mass[1:]
    com = (d.xipos[1:] * mass[:, None]).sum(axis=0) / mass.sum()
    print(f"MuJoCo {mujoco.__version__}: centre of mass {com[2] - scene['floor']:.3f} m above "
          f"the floor after {scene['seconds']} s")
    r = mujoco.Renderer(m, h, w)
    r.update_scene(d, camera="side-by-side")
    write_png(sys.argv[2], np.ascontiguousarray(r.render()))
    r.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
