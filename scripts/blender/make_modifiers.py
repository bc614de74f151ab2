"""Make test/fixtures/modifiers/: a creature whose segments carry modifiers,
as designers' creatures often do, and Blender's account of them.

    blender -b --factory-startup --python-exit-code 1 --python scripts/blender/make_modifiers.py -- test/fixtures/modifiers
    /work/venvs/bpy52/bin/python scripts/blender/make_modifiers.py -- test/fixtures/modifiers/b52   # Blender 5.2.3

Writes, in the folder given, modifiers.blend and modifiers.json. Objects
(Blender's axes, Z up):

- `torso`, modelled as its +x half (x 0 to 0.5, its face on x = 0 left out,
  as for mirror modelling) with a Mirror across x, merging the vertices on
  the mirror plane (the default): Blender shows a closed box, x -0.5 to 0.5;
- `leg`, a box at y 0.05 to 0.15 of the torso (below it) with a Mirror
  across y whose mirror object is the torso: a second prong at y -0.15 to
  -0.05;
- `fin`, a box above the torso (x -0.05 to 0.2) with a Mirror across x
  that bisects it first: Blender shows x -0.2 to 0.2;
- `head`, a box with a Subdivision Surface modifier (2 levels in the
  viewport): Blender shows it rounded and smaller;
- `tail`, a box with an Array modifier hidden in the viewport and in renders,
  and the Collision modifier Blender adds for the Physics tab's Collision;
- joint empties `neck` (torso, head), `hip` (torso, tail: 0.075 from where
  the mirrored torso ends, 0.575 from its half), `leg` (torso, leg: above
  the prong the mirror makes, 0.15 from the modelled one) and `fin-root`
  (torso, fin: above the torso at x -0.15, over the half of the fin that
  only the bisecting mirror makes).

modifiers.json is dump.py's account of the re-opened file, with, for each
object, "modifiers": [{"name", "type", "show_viewport"} and, for a Mirror,
"use_axis", "use_bisect_axis", "use_mirror_merge", "merge_threshold",
"mirror_object"], and for a mesh "evaluated_bbox" ([min, max] of the mesh
Blender shows, in the object's own axes) and "evaluated_vertices" (its
vertices, in the object's own axes, rounded to 6 places, sorted).
"""

import os
import sys

import bpy  # the bpy module (PyPI's wheels) has bmesh only once bpy is imported
import bmesh

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402


def box(name, lo, hi, location, drop_face_at_x0=False):
    me = bpy.data.meshes.new(name)
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    for v in bm.verts:
        v.co = [lo[i] + (hi[i] - lo[i]) * (v.co[i] + 0.5) for i in range(3)]
    if drop_face_at_x0:
        faces = [f for f in bm.faces if all(abs(v.co[0]) < 1e-9 for v in f.verts)]
        bmesh.ops.delete(bm, geom=faces, context="FACES_ONLY")
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


def modifier_info(md):
    out = {"name": md.name, "type": md.type, "show_viewport": md.show_viewport}
    if md.type == "MIRROR":
        out.update({"use_axis": list(md.use_axis), "use_bisect_axis": list(md.use_bisect_axis),
                    "use_mirror_merge": md.use_mirror_merge,
                    "merge_threshold": md.merge_threshold,
                    "mirror_object": md.mirror_object.name if md.mirror_object else None})
    return out


def make(out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.preferences.filepaths.save_version = 0
    torso = box("torso", (0.0, -0.2, -0.15), (0.5, 0.2, 0.15), (0, 0, 1), drop_face_at_x0=True)
    m = torso.modifiers.new("Mirror", "MIRROR")
    m.use_axis = (True, False, False)
    leg = box("leg", (-0.05, 0.05, -0.2), (0.05, 0.15, 0.2), (0, 0, 0.6))
    m = leg.modifiers.new("Mirror", "MIRROR")
    m.use_axis = (False, True, False)
    m.mirror_object = torso
    fin = box("fin", (-0.05, -0.05, -0.1), (0.2, 0.05, 0.1), (0, 0, 1.3))
    m = fin.modifiers.new("Mirror", "MIRROR")
    m.use_axis = (True, False, False)
    m.use_bisect_axis = (True, False, False)
    head = box("head", (-0.15, -0.15, -0.15), (0.15, 0.15, 0.15), (0.8, 0, 1))
    s = head.modifiers.new("Subdivision", "SUBSURF")
    s.levels = 2
    tail = box("tail", (-0.15, -0.1, -0.1), (0.15, 0.1, 0.1), (-0.8, 0, 1))
    a = tail.modifiers.new("Array", "ARRAY")
    a.show_viewport = False
    a.show_render = False
    tail.modifiers.new("Collision", "COLLISION")
    joints = empty("joints", (0, 0, 0))
    hinge = "{:type :hinge :axis [0 1 0] :limit [-0.5 0.5]}"
    empty("neck", (0.575, 0, 1), joints, hinge)
    empty("hip", (-0.575, 0, 1), joints, hinge)
    empty("leg", (0, -0.1, 0.825), joints, hinge)
    empty("fin-root", (-0.15, 0, 1.175), joints, hinge)
    path = os.path.abspath(os.path.join(out, "modifiers.blend"))
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)
    data = dump.dump_data()
    deps = bpy.context.evaluated_depsgraph_get()
    for o in data["objects"]:
        ob = bpy.data.objects[o["name"]]
        o["modifiers"] = [modifier_info(md) for md in ob.modifiers]
        if ob.type == "MESH":
            ev = ob.evaluated_get(deps)
            me = ev.to_mesh()
            cs = [v.co for v in me.vertices]
            o["evaluated_bbox"] = [[min(c[i] for c in cs) for i in range(3)],
                                   [max(c[i] for c in cs) for i in range(3)]]
            o["evaluated_vertices"] = sorted([round(c[i], 6) + 0.0 for i in range(3)] for c in cs)
            ev.to_mesh_clear()
    with open(os.path.join(out, "modifiers.json"), "w") as f:
        f.write(dump._pretty(data) + "\n")


make(sys.argv[sys.argv.index("--") + 1])
