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

With --times (seconds, comma-separated), the comparison cortex's tests
make with each fixture of test/fixtures/physics-sim:

    blender -b --factory-startup --python-exit-code 1 --python simulate_physics.py -- FILE.blend OUT.json --times 0.5,1,2,4

OUT.json: {"blender_version", "fps", "times": [0, t...], "frames": [f0, ...],
           "objects": {name: [matrix_world at each time]},
           "constraints": {name: {"type", "object1", "object2", "matrix_world"
                                  (at the start), "in_world", "enabled"}},
           "world": {"bodies": [names in the RigidBodyWorld collection],
                     "substeps_per_frame", "solver_iterations", "time_scale",
                     "gravity"}}
Each time t is frame f0 + round(t * fps), played through from f0.

With --first-frame as well, OUT.json also has "first_frame": {"substeps",
"step" (seconds), "objects": {name: [matrix_world after each substep of
the first frame, the start first]}}: the file played again at
substeps_per_frame times its frame rate, one substep a frame (the same
steps of the same length, so the same positions), for the speeds the
bodies leave each substep with (Blender's Python gives no velocities;
Bullet moves a body by its velocity times the step).
"""

import json
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402


def first_frame(path):
    """Each rigid body's matrix_world after each substep of the first frame."""
    bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path), load_ui=False)
    scene = bpy.context.scene
    w = scene.rigidbody_world
    n = w.substeps_per_frame
    fps = scene.render.fps / scene.render.fps_base
    scene.render.fps = int(round(fps * n))
    scene.render.fps_base = 1.0
    w.substeps_per_frame = 1
    start = scene.frame_start
    scene.frame_end = max(scene.frame_end, start + n)
    w.point_cache.frame_end = scene.frame_end
    bodies = sorted(o.name for o in scene.objects if o.rigid_body is not None)
    objects = {b: [] for b in bodies}
    for f in range(start, start + n + 1):
        scene.frame_set(f)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        for b in bodies:
            objects[b].append(dump._matrix(scene.objects[b].evaluated_get(depsgraph).matrix_world))
    return {"substeps": n, "step": w.time_scale / (fps * n), "objects": objects}


def at_times(path, out_path, times, first=False):
    bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path), load_ui=False)
    scene = bpy.context.scene
    fps = scene.render.fps / scene.render.fps_base
    start = scene.frame_start
    frames = [start + int(round(t * fps)) for t in times]
    last = max(frames)
    scene.frame_end = max(scene.frame_end, last)
    w = scene.rigidbody_world
    w.point_cache.frame_end = scene.frame_end
    bodies = sorted(o.name for o in scene.objects if o.rigid_body is not None)
    members = sorted(o.name for o in w.collection.objects) if w.collection else []
    con_members = set(o.name for o in w.constraints.objects) if w.constraints else set()
    cons = {}
    for o in scene.objects:
        c = o.rigid_body_constraint
        if c is None:
            continue
        cons[o.name] = {"type": c.type,
                        "object1": c.object1.name if c.object1 else None,
                        "object2": c.object2.name if c.object2 else None,
                        "matrix_world": dump._matrix(o.matrix_world),
                        "in_world": o.name in con_members,
                        "enabled": c.enabled}
    out = {"blender_version": bpy.app.version_string, "fps": fps,
           "times": list(times), "frames": frames,
           "objects": {n: [] for n in bodies}, "constraints": cons,
           "world": {"bodies": members,
                     "substeps_per_frame": w.substeps_per_frame,
                     "solver_iterations": w.solver_iterations,
                     "time_scale": w.time_scale,
                     "gravity": list(scene.gravity)}}
    for f in range(start, last + 1):
        scene.frame_set(f)
        if f not in frames:
            continue
        depsgraph = bpy.context.evaluated_depsgraph_get()
        for n in bodies:
            ob = scene.objects[n].evaluated_get(depsgraph)
            out["objects"][n].append(dump._matrix(ob.matrix_world))
    if first:
        out["first_frame"] = first_frame(path)
    with open(out_path, "w", encoding="utf-8") as fh:
        json.dump(out, fh, indent=None, separators=(",", ":"))
        fh.write("\n")
    print("wrote", out_path)


def main():
    args = dump.script_args()
    first = "--first-frame" in args
    if first:
        args.remove("--first-frame")
    if "--times" in args:
        i = args.index("--times")
        times = [0.0] + [float(t) for t in args[i + 1].split(",")]
        rest = args[:i] + args[i + 2:]
        if len(rest) != 2:
            sys.exit("usage: simulate_physics.py FILE.blend OUT.json --times 0.5,1,2,4")
        at_times(rest[0], rest[1], times, first)
        return
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
