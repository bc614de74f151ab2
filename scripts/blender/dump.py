"""Dump what Blender itself says about a .blend file to JSON ("oracle" data).

Works inside Blender 3.4 (``blender -b ... --python dump.py``) and inside the
``bpy`` PyPI module (4.5, 5.0).  The JSON schema is read by the Clojure tests;
keep it stable:

    {"blender_version": "3.4.1", "file": "<basename>", "file_version": [2, 93, 0],
     "objects": [{"name", "type", "parent", "parent_type", "rotation_mode",
                  "location", "scale", "rotation_euler", "rotation_quaternion",
                  "rotation_axis_angle", "matrix_parent_inverse", "matrix_world",
                  "mesh": null | {"name", "vertices", "polygons", "triangles",
                                  "max_polygon_sides", "bbox_min", "bbox_max",
                                  "material_colors"},
                  "properties": {...}, "mesh_properties": {...}}, ...],
     "scene": "Scene", "scene_objects": [...]}

Objects are sorted by name.  Matrices are row-major lists of 4 rows, in
Blender's own (Z-up) coordinates.  Mesh numbers are those of the base mesh
(obj.data, no modifiers).  "mesh_properties" is {} for objects whose data is
not a mesh.  Custom-property conversion: groups -> JSON objects, arrays ->
lists, ID pointers -> the ID's name (without the two-letter code), byte
strings -> str (latin-1), non-finite floats -> null.

Command line (arguments after ``--`` when run inside Blender):

    blender -b --factory-startup FILE.blend --python dump.py -- [-o OUT.json]
    blender -b --factory-startup --python dump.py -- -i FILE.blend [-o OUT.json]
    python dump.py -i FILE.blend [-o OUT.json]          # bpy wheel
Without -o the JSON goes to stdout.
"""

import json
import math
import os
import sys

import bpy

# Keys that Blender keeps in the custom-property storage but that are not
# user custom properties.
INTERNAL_KEYS = {"_RNA_UI"}


def _num(x):
    x = float(x)
    if math.isfinite(x):
        return x
    return None


def _vec(v):
    return [_num(c) for c in v]


def _matrix(m):
    return [[_num(c) for c in row] for row in m]


def convert_value(v):
    """Convert an ID-property value to plain JSON data."""
    if isinstance(v, bool):
        return v
    if isinstance(v, int):
        return v
    if isinstance(v, float):
        return _num(v)
    if isinstance(v, str):
        return v
    if isinstance(v, (bytes, bytearray)):
        return bytes(v).decode("latin-1")
    if isinstance(v, bpy.types.ID):
        return v.name
    if hasattr(v, "to_dict"):  # IDPropertyGroup
        return {str(k): convert_value(v[k]) for k in v.keys()}
    if hasattr(v, "to_list"):  # IDPropertyArray
        return [convert_value(x) for x in v.to_list()]
    if isinstance(v, dict):
        return {str(k): convert_value(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [convert_value(x) for x in v]
    if v is None:
        return None
    try:  # anything iterable left (e.g. mathutils types)
        return [convert_value(x) for x in v]
    except TypeError:
        return str(v)


def custom_properties(idblock):
    """User custom properties of an ID block (obj.keys() minus internal ones)."""
    if idblock is None:
        return {}
    rna_props = set(idblock.bl_rna.properties.keys())
    out = {}
    for k in sorted(idblock.keys()):
        if k in INTERNAL_KEYS or k in rna_props:
            continue
        out[k] = convert_value(idblock[k])
    return out


def mesh_info(obj):
    me = obj.data
    verts = me.vertices
    polys = me.polygons
    sides = [len(p.vertices) for p in polys]
    if len(verts):
        cos = [v.co for v in verts]
        bbox_min = [_num(min(c[i] for c in cos)) for i in range(3)]
        bbox_max = [_num(max(c[i] for c in cos)) for i in range(3)]
    else:
        bbox_min = bbox_max = None
    colors = []
    for slot in obj.material_slots:
        mat = slot.material
        colors.append(_vec(mat.diffuse_color) if mat is not None else None)
    return {
        "name": me.name,
        "vertices": len(verts),
        "polygons": len(polys),
        "triangles": sum(max(s - 2, 0) for s in sides),
        "max_polygon_sides": max(sides) if sides else 0,
        "bbox_min": bbox_min,
        "bbox_max": bbox_max,
        "material_colors": colors,
    }


def object_info(obj):
    is_mesh = obj.type == "MESH" and isinstance(obj.data, bpy.types.Mesh)
    return {
        "name": obj.name,
        "type": obj.type,
        "parent": obj.parent.name if obj.parent is not None else None,
        "parent_type": obj.parent_type,
        "rotation_mode": obj.rotation_mode,
        "location": _vec(obj.location),
        "scale": _vec(obj.scale),
        "rotation_euler": _vec(obj.rotation_euler),
        "rotation_quaternion": _vec(obj.rotation_quaternion),
        "rotation_axis_angle": _vec(obj.rotation_axis_angle),
        "matrix_parent_inverse": _matrix(obj.matrix_parent_inverse),
        "matrix_world": _matrix(obj.matrix_world),
        "mesh": mesh_info(obj) if is_mesh else None,
        "properties": custom_properties(obj),
        "mesh_properties": custom_properties(obj.data) if is_mesh else {},
    }


def current_scene():
    scene = None
    try:
        scene = bpy.context.scene
    except AttributeError:
        scene = None
    if scene is None:
        try:
            scene = bpy.context.window.scene
        except AttributeError:
            scene = None
    if scene is None and len(bpy.data.scenes):
        scene = bpy.data.scenes[0]
    return scene


def dump_data():
    """The JSON-ready dict for the currently open file."""
    # Make sure matrix_world etc. are evaluated (they are stored in the file
    # anyway, but a freshly built scene may not have been updated yet).
    try:
        bpy.context.view_layer.update()
    except Exception:
        pass
    scene = current_scene()
    objects = sorted(bpy.data.objects, key=lambda o: o.name)
    return {
        "blender_version": bpy.app.version_string,
        "file": os.path.basename(bpy.data.filepath),
        "file_version": list(bpy.data.version),
        "objects": [object_info(o) for o in objects],
        "scene": scene.name if scene is not None else None,
        "scene_objects": sorted(o.name for o in scene.objects) if scene is not None else [],
    }


def _is_leaf(v):
    return not isinstance(v, (dict, list)) or (
        isinstance(v, list) and all(not isinstance(x, (dict, list)) for x in v))


def _pretty(v, indent=0):
    """Indented JSON with lists of scalars (and matrix rows) kept on one line."""
    pad = " " * indent
    if isinstance(v, dict):
        if not v:
            return "{}"
        items = ["%s %s: %s" % (pad, json.dumps(k, ensure_ascii=False), _pretty(x, indent + 1))
                 for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(v, list) and not _is_leaf(v):
        if all(_is_leaf(x) and not isinstance(x, dict) for x in v):
            rows = ["%s %s" % (pad, json.dumps(x, ensure_ascii=False)) for x in v]
        else:
            rows = ["%s %s" % (pad, _pretty(x, indent + 1)) for x in v]
        return "[\n" + ",\n".join(rows) + "\n" + pad + "]"
    return json.dumps(v, ensure_ascii=False)


def dumps():
    return _pretty(dump_data()) + "\n"


def dump(path):
    """Write the JSON of the currently open file to PATH."""
    text = dumps()
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def script_args():
    """Command-line arguments meant for the script.

    Inside the Blender executable they follow "--" (none without it); with
    the bpy module it is a plain python command line.
    """
    argv = sys.argv
    if "--" in argv:
        return argv[argv.index("--") + 1:]
    if os.path.basename(argv[0]).lower().startswith("blender"):
        return []
    return argv[1:]


def main(args=None):
    import argparse

    p = argparse.ArgumentParser(prog="dump.py", description=__doc__.split("\n")[0])
    p.add_argument("-i", "--input", help=".blend file to open first (default: the file already open)")
    p.add_argument("-o", "--output", help="JSON file to write (default: stdout)")
    a = p.parse_args(script_args() if args is None else args)
    if a.input:
        bpy.ops.wm.open_mainfile(filepath=os.path.abspath(a.input), load_ui=False)
    if a.output:
        dump(a.output)
    else:
        sys.stdout.write(dumps())
        sys.stdout.flush()


if __name__ == "__main__":
    main()
