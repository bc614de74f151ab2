"""Play a file's rigid body simulation in Blender and write where the
rigid bodies are, frame by frame: the oracle for what cortex's jBullet
bodies should do.

    blender -b --factory-startup --python-exit-code 1 --python simulate_physics.py -- FILE.blend OUT.json [FRAMES]
    /work/venvs/bpy50/bin/python simulate_physics.py FILE.blend OUT.json [FRAMES]

OUT.json: {"blender_version", "fps", "frames": [f0, fn-1, fn],
           "objects": {name: [matrix_world at each, row-major 4x4, Z up]}}
for every object with a rigid body.  Frame f0 is the scene's start frame
(the rest pose); FRAMES (default 96) frames are played after it, every
one of them (a rigid body simulation has to be stepped through), but
only the last two are kept: where the bodies came to rest, and how fast
they were still moving.
"""

import json
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402


def main():
    args = dump.script_args()
    if len(args) not in (2, 3):
        sys.exit("usage: simulate_physics.py FILE.blend OUT.json [FRAMES]")
    bpy.ops.wm.open_mainfile(filepath=os.path.abspath(args[0]), load_ui=False)
    frames = int(args[2]) if len(args) == 3 else 96
    scene = bpy.context.scene
    start = scene.frame_start
    scene.frame_end = max(scene.frame_end, start + frames)
    scene.rigidbody_world.point_cache.frame_end = scene.frame_end
    bodies = sorted(o.name for o in scene.objects if o.rigid_body is not None)
    out = {"blender_version": bpy.app.version_string,
           "fps": scene.render.fps / scene.render.fps_base,
           "frames": [], "objects": {n: [] for n in bodies}}
    for f in range(start, start + frames + 1):
        scene.frame_set(f)
        if f not in (start, start + frames - 1, start + frames):
            continue
        depsgraph = bpy.context.evaluated_depsgraph_get()
        out["frames"].append(f)
        for n in bodies:
            ob = scene.objects[n].evaluated_get(depsgraph)
            out["objects"][n].append(dump._matrix(ob.matrix_world))
    with open(args[1], "w", encoding="utf-8") as fh:
        json.dump(out, fh, indent=None, separators=(",", ":"))
        fh.write("\n")
    print("wrote", args[1])


if __name__ == "__main__":
    main()
