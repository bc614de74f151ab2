"""Segments made of Blender's primitives, and of things that are not: test/fixtures/shapes/.

    /work/venvs/bpy45/bin/python scripts/blender/make_shape_fixtures.py [OUTDIR]
    blender -b --factory-startup --python-exit-code 1 \
        --python scripts/blender/make_shape_fixtures.py -- [OUTDIR]

OUTDIR defaults to test/fixtures/shapes in the repo.  The script does not
know the tolerance cortex.shapes fits primitives with: it builds each mesh
the way a designer would (Blender's own primitive operators, object-mode
scale and rotation left unapplied, parts joined with Ctrl-J, a capsule
made by extruding a UV sphere's upper half, a bevel, a little noise) and
writes what each segment is meant to be into expected.json, from its own
numbers.

The files (saved uncompressed; no mass, joint or camera: segments only):

- shapes.blend, shapes-0.01.blend, shapes-100.blend: the same objects, every
  length multiplied by 1, 0.01 or 100 (meshes are made at unit size and then
  scaled as data, as Blender's bevel has fixed epsilons).  Objects stand in a
  row along X, 4 units (times the scale) apart.

expected.json: {"notes": [...], "scales": {file: s},
"segments": {name: {...}}} with every length at scale 1 (multiply by the
file's scale).  Each segment is described in the object's OWN frame (its
mesh times its scale, as cortex sees a segment), in jME's axes (Y up:
jME (x, y, z) = Blender (x, z, -y)):

- {"type": "box", "centre": c, "half_extents": h, "axes": [u, v, w]}: the
  box's edges along u, v, w (unit vectors), h along each;
- {"type": "sphere", "centre": c, "radius": r};
- {"type": "cylinder", "centre": c, "radius": r, "half_height": h, "axis": a};
- {"type": "capsule", "centre": c, "radius": r, "height": h, "axis": a}
  (height: the cylinder part's length, as Bullet's capsule has it);
- {"type": "compound", "children": [...]}: one of the above per piece;
- {"type": "hull"}: not a primitive (Suzanne, a wedge, a cone, a
  hemisphere, a hexagonal prism, an icosahedron, a coarse UV sphere, a box
  with a deep bevel), with "why".

Radii are those typed into Blender's operators: the vertices lie on the
primitive's surface (the circumscribed primitive).
"""

import json
import math
import os
import random
import sys

import bpy
import bmesh
from mathutils import Euler, Matrix, Vector

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402
from make_fixtures import empty_file  # noqa: E402

SCALES = {"shapes.blend": 1.0, "shapes-0.01.blend": 0.01, "shapes-100.blend": 100.0}
SPACING = 4.0

TURN = (0.3, 0.5, 0.7)          # an XYZ Euler rotation, radians


def jme(v):
    """Blender (x, y, z) -> jME (x, z, -y)."""
    return [float(v[0]), float(v[2]), -float(v[1])]


def r9(x):
    return round(float(x), 9) + 0.0


def rv(v):
    return [r9(c) for c in v]


def active():
    return bpy.context.active_object


def named(obj, name):
    obj.name = name
    obj.data.name = name
    return obj


def deselect_all():
    for o in bpy.context.view_layer.objects:
        o.select_set(False)


def join(objs, name):
    """Ctrl-J: the objects become one mesh object (the first one)."""
    deselect_all()
    for o in objs:
        o.select_set(True)
    bpy.context.view_layer.objects.active = objs[0]
    bpy.ops.object.join()
    return named(active(), name)


def turned(v, euler):
    return Euler(euler, "XYZ").to_matrix() @ Vector(v)


# ------------------------------------------------------------ the objects
# Each builder makes its object at unit size, at the origin, and returns
# (object, expected description at scale 1).  `place` then scales the mesh
# data by s and moves the object to its slot.


def box():
    """A 2 m cube primitive, rotated and scaled in object mode, unapplied:
    in its own frame it is an aligned box."""
    bpy.ops.mesh.primitive_cube_add(size=2.0)
    o = active()
    o.rotation_euler = TURN
    o.scale = (0.4, 0.25, 0.1)
    return o, {"type": "box", "centre": [0.0, 0.0, 0.0], "half_extents": [0.4, 0.1, 0.25],
               "axes": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]}


def box_turned():
    """A cube whose rotation and scale were applied and which was then moved
    off the origin in edit mode: in its own frame a turned, off-centre box."""
    bpy.ops.mesh.primitive_cube_add(size=2.0)
    o = active()
    half = (0.3, 0.2, 0.15)
    offset = (0.2, -0.1, 0.15)
    o.data.transform(Matrix.Translation(offset) @ Euler(TURN, "XYZ").to_matrix().to_4x4()
                     @ Matrix.Diagonal((*half, 1.0)))
    m = Euler(TURN, "XYZ").to_matrix()
    axes = [jme(m.col[i]) for i in range(3)]
    return o, {"type": "box", "centre": jme(offset), "half_extents": list(half), "axes": axes}


def uv_sphere(segments, rings, radius):
    def make():
        bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=rings, radius=radius)
        return active(), {"type": "sphere", "centre": [0.0, 0.0, 0.0], "radius": radius}
    return make


def ico_sphere(subdivisions, radius):
    def make():
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=subdivisions, radius=radius)
        return active(), {"type": "sphere", "centre": [0.0, 0.0, 0.0], "radius": radius}
    return make


def cylinder(vertices, radius, depth, along_x=False):
    """Blender's cylinder primitive (along Z; laid along X with its rotation
    applied when along_x)."""
    def make():
        bpy.ops.mesh.primitive_cylinder_add(vertices=vertices, radius=radius, depth=depth)
        o = active()
        axis = [0.0, 1.0, 0.0]
        if along_x:
            o.data.transform(Euler((0.0, math.pi / 2, 0.0), "XYZ").to_matrix().to_4x4())
            axis = [1.0, 0.0, 0.0]
        return o, {"type": "cylinder", "centre": [0.0, 0.0, 0.0], "radius": radius,
                   "half_height": depth / 2, "axis": axis}
    return make


def extruded_capsule(segments, rings, radius, length, centred):
    """The way people make a capsule: a UV sphere, its upper half's faces
    extruded up by `length` (the equator becomes two rings joined by the
    cylinder).  Not centred: the lower hemisphere stays at the origin."""
    def make():
        bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=rings, radius=radius)
        o = active()
        bm = bmesh.new()
        bm.from_mesh(o.data)
        upper = [f for f in bm.faces if f.calc_center_median().z > 0]
        made = bmesh.ops.extrude_face_region(bm, geom=upper)
        moved = [v for v in made["geom"] if isinstance(v, bmesh.types.BMVert)]
        bmesh.ops.translate(bm, verts=moved, vec=(0.0, 0.0, length))
        bmesh.ops.delete(bm, geom=upper, context="FACES")
        if centred:
            bmesh.ops.translate(bm, verts=bm.verts, vec=(0.0, 0.0, -length / 2))
        bm.to_mesh(o.data)
        bm.free()
        o.data.update()
        centre = [0.0, 0.0, 0.0] if centred else jme((0.0, 0.0, length / 2))
        return o, {"type": "capsule", "centre": centre, "radius": radius, "height": length,
                   "axis": [0.0, 1.0, 0.0]}
    return make


def capsule_parts():
    """A cylinder and two UV spheres on its ends, joined (Ctrl-J) but not
    merged: three closed pieces in one object."""
    r, h = 0.2, 0.5
    bpy.ops.mesh.primitive_cylinder_add(vertices=16, radius=r, depth=h)
    c = active()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8, radius=r, location=(0, 0, h / 2))
    a = active()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8, radius=r, location=(0, 0, -h / 2))
    b = active()
    o = join([c, a, b], "capsule-parts")
    return o, {"type": "compound", "children": [
        {"type": "cylinder", "centre": [0.0, 0.0, 0.0], "radius": r, "half_height": h / 2,
         "axis": [0.0, 1.0, 0.0]},
        {"type": "sphere", "centre": jme((0, 0, h / 2)), "radius": r},
        {"type": "sphere", "centre": jme((0, 0, -h / 2)), "radius": r}]}


def shin():
    """A shin (12-sided cylinder) and its foot (a box below it, reaching
    forward), joined into one mesh object: two pieces."""
    r, depth = 0.08, 0.6
    bpy.ops.mesh.primitive_cylinder_add(vertices=12, radius=r, depth=depth)
    leg = active()
    foot_half, foot_at = (0.1, 0.25, 0.05), (0.0, 0.12, -0.37)
    bpy.ops.mesh.primitive_cube_add(size=2.0, location=foot_at, scale=foot_half)
    foot = active()
    bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)
    o = join([leg, foot], "shin")
    return o, {"type": "compound", "children": [
        {"type": "cylinder", "centre": [0.0, 0.0, 0.0], "radius": r, "half_height": depth / 2,
         "axis": [0.0, 1.0, 0.0]},
        {"type": "box", "centre": jme(foot_at), "half_extents": list(foot_half),
         "axes": [jme((1, 0, 0)), jme((0, 1, 0)), jme((0, 0, 1))]}]}


def hull(why, build):
    def make():
        o = build()
        return o, {"type": "hull", "why": why}
    return make


def suzanne():
    bpy.ops.mesh.primitive_monkey_add(size=1.0)
    return active()


def wedge():
    me = bpy.data.meshes.new("wedge")
    vs = [(-0.5, -0.3, -0.2), (0.5, -0.3, -0.2), (0.5, 0.3, -0.2), (-0.5, 0.3, -0.2),
          (-0.5, -0.3, 0.2), (0.5, -0.3, 0.2)]
    fs = [(0, 3, 2, 1), (0, 1, 5, 4), (3, 0, 4), (1, 2, 5), (2, 3, 4, 5)]
    me.from_pydata(vs, [], fs)
    me.validate()
    me.update()
    o = bpy.data.objects.new("wedge", me)
    bpy.context.scene.collection.objects.link(o)
    return o


def cone():
    bpy.ops.mesh.primitive_cone_add(vertices=32, radius1=0.4, depth=0.8)
    return active()


def hemisphere():
    """A UV sphere's lower half, its rim filled: half a sphere, not a sphere."""
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=0.5)
    o = active()
    bm = bmesh.new()
    bm.from_mesh(o.data)
    bmesh.ops.delete(bm, geom=[v for v in bm.verts if v.co.z > 1e-6], context="VERTS")
    rim = [e for e in bm.edges if e.is_boundary]
    bmesh.ops.contextual_create(bm, geom=rim)
    bm.to_mesh(o.data)
    bm.free()
    o.data.update()
    return o


def plain(build):
    def make():
        return build()
    return make


def beveled_box(offset, segments):
    """Blender's 2 m cube with every edge bevelled by `offset`."""
    def make():
        bpy.ops.mesh.primitive_cube_add(size=2.0)
        o = active()
        bm = bmesh.new()
        bm.from_mesh(o.data)
        bmesh.ops.bevel(bm, geom=list(bm.edges), offset=offset, segments=segments, profile=0.5,
                        affect="EDGES", clamp_overlap=True)
        bm.to_mesh(o.data)
        bm.free()
        o.data.update()
        return o
    return make


def noisy_cylinder():
    """Blender's default cylinder (32 vertices, radius 1, depth 2) scaled to
    radius 0.3, every vertex moved by up to 1e-4 of its size (0.6) at random."""
    bpy.ops.mesh.primitive_cylinder_add(vertices=32, radius=0.3, depth=0.6)
    o = active()
    rng = random.Random(27)
    for v in o.data.vertices:
        v.co = v.co + Vector([rng.uniform(-1.0, 1.0) * 0.6e-4 for _ in range(3)])
    o.data.update()
    return o, {"type": "cylinder", "centre": [0.0, 0.0, 0.0], "radius": 0.3, "half_height": 0.3,
               "axis": [0.0, 1.0, 0.0], "noise": 0.6e-4}


def beveled(offset, segments, expected):
    def make():
        o = beveled_box(offset, segments)()
        return o, dict(expected)
    return make


OBJECTS = [
    ("box", box),
    ("box-turned", box_turned),
    ("uv-sphere", uv_sphere(32, 16, 0.5)),
    ("uv-sphere-16", uv_sphere(16, 8, 0.5)),
    ("uv-sphere-8", lambda: (uv_sphere(8, 4, 0.5)()[0],
                             {"type": "hull", "why": "an 8 x 4 UV sphere: 32 faces, 45 degrees apart"})),
    ("icosphere", ico_sphere(2, 0.5)),
    ("icosphere-3", ico_sphere(3, 0.5)),
    ("icosphere-1", lambda: (ico_sphere(1, 0.5)()[0],
                             {"type": "hull", "why": "an icosahedron: a die, not a ball"})),
    ("cylinder", cylinder(32, 0.3, 0.8)),
    ("cylinder-8", cylinder(8, 0.2, 0.6, along_x=True)),
    ("cylinder-10", cylinder(10, 0.25, 0.5)),
    ("cylinder-12", cylinder(12, 0.15, 0.9, along_x=True)),
    ("cylinder-6", lambda: (cylinder(6, 0.25, 0.5)()[0],
                            {"type": "hull", "why": "a hexagonal prism: it does not roll"})),
    ("cylinder-noisy", noisy_cylinder),
    ("capsule", extruded_capsule(32, 16, 0.25, 0.5, False)),
    ("capsule-10", extruded_capsule(10, 6, 0.2, 0.4, True)),
    ("capsule-parts", capsule_parts),
    ("shin", shin),
    ("suzanne", hull("Suzanne", suzanne)),
    ("wedge", hull("a wedge: half a box", wedge)),
    ("cone", hull("a cone (cortex fits no cones)", cone)),
    ("hemisphere", hull("half a UV sphere, its rim filled", hemisphere)),
    ("box-bevel-2", beveled(0.04, 1, {"type": "box", "centre": [0.0, 0.0, 0.0],
                                      "half_extents": [1.0, 1.0, 1.0],
                                      "axes": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                                      "bevel": 0.04})),
    ("box-round-2", beveled(0.04, 3, {"type": "box", "centre": [0.0, 0.0, 0.0],
                                      "half_extents": [1.0, 1.0, 1.0],
                                      "axes": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                                      "bevel": 0.04})),
    ("box-round-20", beveled(0.4, 3, {"type": "hull",
                                      "why": "a 2 m cube rounded by 0.4: a pebble, not a box"})),
]


def build(s):
    empty_file()
    for i, (name, make) in enumerate(OBJECTS):
        o, _ = make()
        named(o, name)
        o.data.transform(Matrix.Scale(s, 4))
        o.location = (i * SPACING * s, 0.0, 0.0)
    bpy.context.view_layer.update()


def expected():
    out = {}
    for name, make in OBJECTS:
        empty_file()
        _, e = make()
        out[name] = e
    return out


def rounded(x):
    if isinstance(x, dict):
        return {k: rounded(v) for k, v in x.items()}
    if isinstance(x, list):
        return [rounded(v) for v in x]
    if isinstance(x, float):
        return r9(x)
    return x


def main():
    args = dump.script_args()
    out = os.path.normpath(os.path.abspath(args[0]) if args else os.path.join(
        HERE, "..", "..", "test", "fixtures", "shapes"))
    os.makedirs(out, exist_ok=True)
    print("Blender", bpy.app.version_string, "->", out)
    segments = expected()
    with open(os.path.join(out, "expected.json"), "w", encoding="utf-8") as f:
        json.dump({"notes": [
            "Written by scripts/blender/make_shape_fixtures.py from its own numbers, not read"
            " back from Blender; see its docstring.  Lengths at scale 1: multiply by the"
            " file's scale.  Each segment in its object's own frame (mesh times object"
            " scale), jME axes (x, y, z) = Blender (x, z, -y).  Files store float32."],
            "scales": SCALES, "spacing": SPACING, "segments": rounded(segments)},
            f, indent=1, sort_keys=True)
        f.write("\n")
    for fname, s in SCALES.items():
        build(s)
        path = os.path.join(out, fname)
        bpy.ops.wm.save_as_mainfile(filepath=path, compress=False, check_existing=False)
        print("wrote", path, os.path.getsize(path), "bytes")


if __name__ == "__main__":
    main()
