"""Build the .blend test fixtures from scratch and dump a JSON oracle beside each.

Runs inside Blender 3.4 and inside the bpy 4.5 / 5.0 PyPI modules:

    blender -b --factory-startup --python make_fixtures.py -- OUTDIR
    /work/venvs/bpy45/bin/python make_fixtures.py OUTDIR
    /work/venvs/bpy50/bin/python make_fixtures.py OUTDIR

Writes into OUTDIR (e.g. test/fixtures/blend/b34):
    transforms.blend            + transforms.json
    transforms_compressed.blend + transforms_compressed.json
    props.blend                 + props.json

Everything is deterministic (fixed numbers, no randomness), so re-running
gives the same JSON.  See make_fixtures.sh for running all three Blenders.
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dump  # noqa: E402

VERSION = tuple(bpy.app.version)


# ---------------------------------------------------------------- helpers

def small_file_settings():
    """Keep saved files small: no thumbnail, only the "Layout" workspace.

    The factory startup file carries 11 workspaces with their screens; they
    are UI data that the tests do not need.  Their removal is cosmetic, so
    failures are ignored.
    """
    filepaths = bpy.context.preferences.filepaths
    try:
        filepaths.file_preview_type = "NONE"
    except (AttributeError, TypeError):
        pass
    filepaths.save_version = 0   # no .blend1 backups when overwriting
    try:
        keep = bpy.data.workspaces.get("Layout")
        if keep is not None:
            bpy.data.batch_remove([w for w in bpy.data.workspaces if w != keep])
    except Exception as e:  # pragma: no cover - depends on the Blender version
        print("could not remove workspaces:", e)


def empty_file():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    small_file_settings()
    # read_factory_settings(use_empty=True) leaves one empty scene; make sure
    # nothing else (e.g. orphan data) is around.
    for coll in (bpy.data.objects, bpy.data.meshes, bpy.data.materials,
                 bpy.data.lights, bpy.data.cameras):
        for item in list(coll):
            coll.remove(item)
    scene = bpy.data.scenes[0]
    scene.name = "Scene"
    return scene


def scene():
    return bpy.data.scenes[0]


def update():
    bpy.context.view_layer.update()


def mesh_from(name, verts, faces):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(v) for v in verts], [], [tuple(f) for f in faces])
    me.validate()
    me.update()
    return me


def box_mesh(name, sx=1.0, sy=1.0, sz=1.0, center=(0.0, 0.0, 0.0)):
    """Axis-aligned box with half-extents sx, sy, sz (8 verts, 6 quads)."""
    cx, cy, cz = center
    verts = [(cx + x * sx, cy + y * sy, cz + z * sz)
             for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    # vertex index = 4*ix + 2*iy + iz
    faces = [(0, 1, 3, 2), (4, 6, 7, 5),   # -x, +x
             (0, 4, 5, 1), (2, 3, 7, 6),   # -y, +y
             (0, 2, 6, 4), (1, 5, 7, 3)]   # -z, +z
    return mesh_from(name, verts, faces)


def cylinder_mesh(name, sides=8, radius=1.0, depth=2.0):
    """Cylinder along Z with n-gon caps (2*sides verts, sides quads + 2 n-gons)."""
    h = depth / 2.0
    verts = []
    for z in (-h, h):
        for i in range(sides):
            a = 2.0 * math.pi * i / sides
            verts.append((radius * math.cos(a), radius * math.sin(a), z))
    faces = [(i, (i + 1) % sides, sides + (i + 1) % sides, sides + i) for i in range(sides)]
    faces.append(tuple(reversed(range(sides))))        # bottom, facing -Z
    faces.append(tuple(range(sides, 2 * sides)))       # top, facing +Z
    return mesh_from(name, verts, faces)


def new_object(name, data=None, parent=None, location=(0, 0, 0),
               rotation=(0, 0, 0), scale=(1, 1, 1)):
    obj = bpy.data.objects.new(name, data)
    scene().collection.objects.link(obj)
    obj.location = location
    obj.rotation_euler = rotation
    obj.scale = scale
    if parent is not None:
        obj.parent = parent   # matrix_parent_inverse stays identity
    return obj


def material(name, rgba):
    mat = bpy.data.materials.new(name)
    mat.diffuse_color = rgba
    return mat


def save(path, compress=False):
    update()
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(path), compress=compress,
                                check_existing=False)
    # Dump what Blender reads back from the saved file (bpy.data.version is
    # only right after reading a file: before, it is the startup file's).
    bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path), load_ui=False)
    json_path = os.path.splitext(path)[0] + ".json"
    dump.dump(json_path)
    print("wrote", path, "and", json_path)


# ---------------------------------------------------------------- scenes

def build_transforms():
    empty_file()

    # 1. a chain four deep; every parent rotated and non-uniformly scaled.
    chain1 = new_object("chain-1", box_mesh("chain-1"), location=(0.0, 0.0, 1.0),
                        rotation=(0.3, 0.2, 0.1), scale=(1.0, 2.0, 0.5))
    chain2 = new_object("chain-2", box_mesh("chain-2"), parent=chain1,
                        location=(2.0, 0.5, 1.0), rotation=(0.0, 0.6, -0.4),
                        scale=(0.5, 1.5, 1.0))
    chain3 = new_object("chain-3", box_mesh("chain-3"), parent=chain2,
                        location=(1.5, -1.0, 0.5), rotation=(-0.5, 0.25, 0.75),
                        scale=(2.0, 0.75, 1.25))
    new_object("chain-4", box_mesh("chain-4"), parent=chain3,
               location=(0.0, 2.0, -1.0), rotation=(1.0, -0.3, 0.2),
               scale=(0.8, 0.8, 1.6))

    # 2. one object per rotation mode, all with the same non-trivial numbers
    #    so that the modes give different matrices.
    euler = (0.3, -0.7, 1.1)
    for i, mode in enumerate(["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"]):
        obj = new_object("rot-" + mode, box_mesh("rot-" + mode, 0.3, 0.2, 0.1),
                         location=(-6.0 + 1.0 * i, 4.0, 0.0))
        obj.rotation_mode = mode
        obj.rotation_euler = euler
    q = new_object("rot-QUATERNION", box_mesh("rot-QUATERNION", 0.3, 0.2, 0.1),
                   location=(0.0, 4.0, 0.0))
    q.rotation_mode = "QUATERNION"
    # normalized quaternion (w, x, y, z): rotation of 1.2 rad about (1,2,3)/|.|
    ax = [1.0 / math.sqrt(14.0), 2.0 / math.sqrt(14.0), 3.0 / math.sqrt(14.0)]
    s = math.sin(0.6)
    q.rotation_quaternion = (math.cos(0.6), ax[0] * s, ax[1] * s, ax[2] * s)
    aa = new_object("rot-AXIS_ANGLE", box_mesh("rot-AXIS_ANGLE", 0.3, 0.2, 0.1),
                    location=(1.0, 4.0, 0.0))
    aa.rotation_mode = "AXIS_ANGLE"
    aa.rotation_axis_angle = (2.1, 0.0, -0.6, 0.8)   # angle, then a unit axis

    # 3. a child with a non-identity matrix_parent_inverse: parent it with
    #    "keep transform" (parent inverse = inverse of the parent's world
    #    matrix at parenting time, as Ctrl-P > Object does), then move and
    #    rotate the parent.
    kp = new_object("keep-parent", box_mesh("keep-parent", 0.5, 0.5, 0.5),
                    location=(4.0, -3.0, 1.0), rotation=(0.0, 0.0, 0.5),
                    scale=(1.0, 1.0, 2.0))
    kc = new_object("keep-child", box_mesh("keep-child", 0.25, 0.25, 0.25),
                    location=(5.0, -3.0, 2.0), rotation=(0.2, 0.0, 0.0))
    update()
    kc.parent = kp
    kc.matrix_parent_inverse = kp.matrix_world.inverted()
    update()
    kp.location = (4.5, -2.0, 1.5)
    kp.rotation_euler = (0.4, 0.0, 1.0)

    # 4. an empty with children
    hub = new_object("empty-hub", None, location=(-4.0, -3.0, 1.0),
                     rotation=(0.0, 0.0, math.pi / 4), scale=(2.0, 2.0, 2.0))
    hub.empty_display_type = "PLAIN_AXES"
    new_object("hub-child-a", box_mesh("hub-child-a", 0.2, 0.2, 0.2), parent=hub,
               location=(1.0, 0.0, 0.0))
    new_object("hub-child-b", box_mesh("hub-child-b", 0.2, 0.2, 0.2), parent=hub,
               location=(0.0, 1.0, 0.5), rotation=(0.0, 0.5, 0.0))

    # 5. a light and a camera
    light = bpy.data.lights.new("Light", type="POINT")
    new_object("Light", light, location=(4.0, 1.0, 6.0))
    cam = bpy.data.cameras.new("Camera")
    cam_obj = new_object("Camera", cam, location=(7.0, -7.0, 5.0),
                         rotation=(1.1, 0.0, 0.8))
    scene().camera = cam_obj

    # 6. n-gons: a single hexagon face, and a cylinder with octagon caps
    hexagon = [(math.cos(2 * math.pi * i / 6), math.sin(2 * math.pi * i / 6), 0.0)
               for i in range(6)]
    new_object("ngon-hexagon", mesh_from("ngon-hexagon", hexagon, [range(6)]),
               location=(-3.0, 0.0, 0.0))
    new_object("ngon-cylinder", cylinder_mesh("ngon-cylinder", 8, 0.5, 1.0),
               location=(-1.5, 0.0, 0.5))

    # 7. two material slots with different diffuse colours
    me = box_mesh("two-materials", 0.5, 0.5, 0.5)
    me.materials.append(material("red", (0.8, 0.1, 0.1, 1.0)))
    me.materials.append(material("blue", (0.1, 0.2, 0.9, 0.5)))
    for poly in me.polygons:
        poly.material_index = 1 if poly.index >= 3 else 0
    new_object("two-materials", me, location=(2.0, 2.0, 0.5))

    # 8. negative scale on one axis
    new_object("mirrored", box_mesh("mirrored", 0.5, 0.25, 0.25, center=(0.5, 0.0, 0.0)),
               location=(2.0, -1.0, 0.5), rotation=(0.0, 0.0, 0.3),
               scale=(-1.0, 1.5, 1.0))
    update()


def build_props():
    empty_file()
    basic = new_object("props-basic", box_mesh("props-basic-mesh", 0.5, 0.5, 0.5))
    basic["a_string"] = "hello, blender"
    basic["a_unicode_string"] = "h\u00e9llo \u2013 \u03c0"
    basic["an_empty_string"] = ""
    basic["an_int"] = 42
    basic["a_negative_int"] = -7
    basic["a_float"] = 3.25
    basic["a_bool_true"] = True     # stored as an int 1 before Blender 4.0
    basic["a_bool_false"] = False
    basic["an_int_array"] = [1, 2, 3, -4]
    basic["a_float_array"] = [0.5, -1.25, 2.0]
    basic["a_bool_array"] = [True, False, True]
    basic["a_group"] = {
        "inner_int": 7,
        "inner_float": 0.125,
        "inner_string": "nested",
        "inner_array": [1.5, 2.5],
        "deeper": {"level": 3, "name": "deepest", "flags": [0, 1, 1]},
    }
    basic["a_list_of_groups"] = [{"n": 1}, {"n": 2, "s": "two"}]
    basic["a_long_string"] = " ".join("segment-%02d of a long custom property string" % i
                                      for i in range(8))
    basic["mass"] = 2.5
    basic["joint"] = "{:type :hinge :limit [0 (/ Math/PI 2)] :axis (Vector3f. 0 1 0)}"
    try:  # UI metadata (min/max/description); must not show up as a property
        ui = basic.id_properties_ui("mass")
        ui.update(min=0.0, max=100.0, description="mass in kg")
    except (AttributeError, TypeError):
        pass

    # custom properties on the mesh data
    basic.data["mesh_note"] = "on the mesh datablock"
    basic.data["mesh_weight"] = 0.75
    basic.data["mesh_ids"] = [10, 20, 30]

    # a second object: mass + joint only (the body conventions), and a
    # pointer to another ID (stored as an ID property since Blender 3.0)
    other = new_object("props-joint", None, location=(2.0, 0.0, 0.0))
    other.empty_display_type = "CUBE"
    other["joint"] = "{:type :point}"
    other["mass"] = 1.0
    other["an_object_pointer"] = basic

    # an object without any custom property
    new_object("props-none", box_mesh("props-none-mesh", 0.25, 0.25, 0.25),
               location=(-2.0, 0.0, 0.0))
    update()


def main():
    args = dump.script_args()
    if len(args) != 1:
        sys.exit("usage: make_fixtures.py OUTDIR")
    out = os.path.abspath(args[0])
    os.makedirs(out, exist_ok=True)
    print("Blender", bpy.app.version_string, "->", out)

    build_transforms()
    save(os.path.join(out, "transforms.blend"))
    build_transforms()
    save(os.path.join(out, "transforms_compressed.blend"), compress=True)
    build_props()
    save(os.path.join(out, "props.blend"))


if __name__ == "__main__":
    main()
