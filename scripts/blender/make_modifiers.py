"""Make test/fixtures/modifiers/: a creature whose segments carry modifiers,
as designers' creatures often do, and Blender's account of them.

    blender -b --factory-startup --python-exit-code 1 --python scripts/blender/make_modifiers.py -- test/fixtures/modifiers
    /work/venvs/bpy52/bin/python scripts/blender/make_modifiers.py -- test/fixtures/modifiers/b52   # Blender 5.2.3

Writes, in the folder given, modifiers.blend and modifiers.json:

- `torso`, modelled as its +x half only (x 0 to 0.5) with a Mirror modifier
  across x, as designers model symmetric bodies: Blender shows x -0.5 to 0.5;
- `head`, a box with a Subdivision Surface modifier (2 levels in the viewport):
  Blender shows it rounded and smaller;
- `tail`, a box with an Array modifier hidden in the viewport and in renders,
  and the Collision modifier Blender adds for the Physics tab's Collision;
- joint empties `neck` (between torso and head) and `hip` (between the tail
  and where the mirrored torso ends, x -0.5: 0.575 from the base mesh).

modifiers.json is dump.py's account of the re-opened file, with, for each
object, "modifiers": [{"name", "type", "show_viewport"}] and "evaluated_bbox"
([min, max] of the mesh Blender shows, in the object's own axes).
"""

import json
import os
import sys

import bpy  # the bpy module (PyPI's wheels) has bmesh only once bpy is imported
import bmesh

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402


def box(name, lo, hi, location):
    me = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    for v in bm.verts:
        v.co = [lo[i] + (hi[i] - lo[i]) * (v.co[i] + 0.5) for i in range(3)]
    bm.to_mesh(me)
    bm.free()
    o = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(o)
    o.location = location
    o["mass"] = 1.0
    return o


def empty(name, location, parent=None, joint=None):
    o = bpy.data.objects.new(name, None)
    bpy.context.scene.collection.objects.link(o)
    o.location = location
    if parent:
        o.parent = parent
    if joint:
        o["joint"] = joint
    return o


def make(out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.preferences.filepaths.save_version = 0
    torso = box("torso", (0.0, -0.2, -0.15), (0.5, 0.2, 0.15), (0, 0, 1))
    m = torso.modifiers.new("Mirror", "MIRROR")
    m.use_axis = (True, False, False)
    head = box("head", (-0.15, -0.15, -0.15), (0.15, 0.15, 0.15), (0.8, 0, 1))
    s = head.modifiers.new("Subdivision", "SUBSURF")
    s.levels = 2
    tail = box("tail", (-0.15, -0.1, -0.1), (0.15, 0.1, 0.1), (-0.8, 0, 1))
    a = tail.modifiers.new("Array", "ARRAY")
    a.show_viewport = False
    a.show_render = False
    tail.modifiers.new("Collision", "COLLISION")
    joints = empty("joints", (0, 0, 0))
    empty("neck", (0.575, 0, 1), joints, "{:type :hinge :axis [0 1 0] :limit [-0.5 0.5]}")
    empty("hip", (-0.575, 0, 1), joints, "{:type :hinge :axis [0 1 0] :limit [-0.5 0.5]}")
    path = os.path.abspath(os.path.join(out, "modifiers.blend"))
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)
    data = dump.dump_data()
    deps = bpy.context.evaluated_depsgraph_get()
    for o in data["objects"]:
        ob = bpy.data.objects[o["name"]]
        o["modifiers"] = [{"name": md.name, "type": md.type, "show_viewport": md.show_viewport}
                          for md in ob.modifiers]
        if ob.type == "MESH":
            me = ob.evaluated_get(deps).to_mesh()
            cs = [v.co for v in me.vertices]
            o["evaluated_bbox"] = [[min(c[i] for c in cs) for i in range(3)],
                                   [max(c[i] for c in cs) for i in range(3)]]
            ob.evaluated_get(deps).to_mesh_clear()
    with open(os.path.join(out, "modifiers.json"), "w") as f:
        f.write(dump._pretty(data) + "\n")


make(sys.argv[sys.argv.index("--") + 1])
