"""Check test/fixtures/humanoid/ against expected.json and cortex's creature rules.

    blender -b --factory-startup --python-exit-code 1 \
        --python scripts/blender/check_humanoid.py -- [DIR]

DIR defaults to test/fixtures/humanoid.  Everything is measured on the saved
.blend files (their float32 geometry) and compared with expected.json, which
make_humanoid.py wrote from its own numbers:

- segments: the 11 names, float masses (MuJoCo's, or the heavy hands'), closed
  convex meshes with outward faces and at most 100 vertices, origin, volume,
  centroid and bounds; the lowest point at z = 0;
- joints: parent `joints`, position, rotation, spec (parsed), hinge axis in
  the world equal to MuJoCo's, limits equal to MuJoCo's range (hinges) or to
  the larger magnitude of each MuJoCo range (cones);
- cortex's joint search, as body.clj does it (a cube centred on the empty,
  doubling from 0.01, meeting the segments' triangles): it finds the intended
  two; both are 0.015 from the empty (Euclidean), within the tolerance (a
  tenth of the median segment size); no third segment is within the second
  one's distance plus the tolerance (no ambiguous-joint doubt); cortex's
  order puts the proximal segment first; the four nearest match expected.json;
- no two segments intersect; no unjoined pair meets the other's bounds as
  cortex's overlap warning tests it;
- the heavy-hands file: the same geometry, lower arms 10 times the upper arms,
  and its dump.py JSON differs from humanoid.json only in those masses.

Prints a table of the humanoid; exits 1 on a failure.
"""

import json
import math
import os
import sys

import bpy
from mathutils.bvhtree import BVHTree

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402
from check_creatures import closed, finish, read_joint, signed_volume  # noqa: E402
from make_humanoid import (cube_distance, euclid_distance, inside_convex, r9,  # noqa: E402
                           size_of, tri_box_overlap, triangles, volume_properties)

TOL = 1e-5
GAP_HALF = 0.015
NAMES = ["left_lower_arm", "left_shin", "left_thigh", "left_upper_arm", "lwaist", "pelvis",
         "right_lower_arm", "right_shin", "right_thigh", "right_upper_arm", "torso"]


def close(a, b, tol=TOL):
    if isinstance(a, (int, float)):
        return abs(a - b) <= tol
    return len(a) == len(b) and all(close(x, y, tol) for x, y in zip(a, b))


def mesh_of(obj):
    mw = obj.matrix_world
    vs = [list(mw @ v.co) for v in obj.data.vertices]
    fs = [list(p.vertices) for p in obj.data.polygons]
    return vs, fs


def convex(vs, fs, tol=5e-5):
    """Is every vertex behind every face's plane (Newell normals; merged faces of float32
    vertices are planar to about 1e-5)?"""
    for f in fs:
        n = [0.0, 0.0, 0.0]
        for i in range(len(f)):
            a, b = vs[f[i]], vs[f[(i + 1) % len(f)]]
            n[0] += (a[1] - b[1]) * (a[2] + b[2])
            n[1] += (a[2] - b[2]) * (a[0] + b[0])
            n[2] += (a[0] - b[0]) * (a[1] + b[1])
        ln = math.sqrt(sum(x * x for x in n))
        if ln == 0:
            return False
        c = [sum(vs[i][k] for i in f) / len(f) for k in range(3)]
        if any(sum(n[k] * (v[k] - c[k]) for k in range(3)) / ln > tol for v in vs):
            return False
    return True


def shrunk_bounds_met(tris, vs):
    """cortex's overlap test: do the triangles meet the other segment's bounds shrunk to 99.8%?"""
    lo = [min(v[k] for v in vs) for k in range(3)]
    hi = [max(v[k] for v in vs) for k in range(3)]
    c = [(lo[k] + hi[k]) / 2 for k in range(3)]
    e = [0.499 * (hi[k] - lo[k]) for k in range(3)]
    # an axis-aligned box is a cube after scaling the axes
    s = [e[0] / e[k] for k in range(3)]
    scaled = [tuple([p[k] * s[k] for k in range(3)] for p in t) for t in tris]
    return any(tri_box_overlap([c[k] * s[k] for k in range(3)], e[0], t) for t in scaled)


def intersect(a, b):
    """Do two closed convex meshes intersect (triangles cross or one holds the other)?"""
    ta = BVHTree.FromPolygons([tuple(v) for v in a[0]], [tuple(f) for f in a[1]])
    tb = BVHTree.FromPolygons([tuple(v) for v in b[0]], [tuple(f) for f in b[1]])
    if ta.overlap(tb):
        return True
    return inside_convex(a[0][0], *b) or inside_convex(b[0][0], *a)


def closest_approach(a, b):
    """Smallest vertex-to-surface distance between two meshes (an upper bound of the gap)."""
    return min(min(euclid_distance(v, *b) for v in a[0]), min(euclid_distance(v, *a) for v in b[0]))


def cortex_search(dist):
    """The pair cortex's doubling cube finds first, and the cube size that found it."""
    r = 0.01
    while sum(1 for c, _, _ in dist.values() if c <= r) < 2:
        r *= 2
    return sorted(n for n, (c, _, _) in dist.items() if c <= r), r


def cortex_order(joint, names):
    rot_inv = joint.matrix_world.to_3x3().normalized().inverted()
    p = joint.matrix_world.translation
    return sorted(names, key=lambda n: sum(rot_inv @ (bpy.data.objects[n].matrix_world.translation - p)))


def check_file(path, exp, fail):
    bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path), load_ui=False)
    bpy.context.view_layer.update()
    name = os.path.basename(path)
    objs = sorted((o for o in bpy.data.objects if o.type == "MESH"), key=lambda o: o.name)
    if [o.name for o in objs] != NAMES or [s["name"] for s in exp["segments"]] != NAMES:
        fail("%s: segments %s" % (name, [o.name for o in objs]))
        return None
    shapes = {o.name: mesh_of(o) for o in objs}
    for o, s in zip(objs, exp["segments"]):
        vs, fs = shapes[o.name]
        mass = o.get("mass")
        if not isinstance(mass, float) or not close(mass, s["mass"], 1e-6 * s["mass"]):
            fail("%s: %s mass %r, expected %r" % (name, o.name, mass, s["mass"]))
        if len(vs) != s["vertices"] or len(vs) > 100 or not closed(o) or signed_volume(o) <= 0:
            fail("%s: %s: %d vertices, closed %s, volume %f" % (name, o.name, len(vs), closed(o),
                                                                signed_volume(o)))
        if not convex(vs, fs):
            fail("%s: %s is not convex" % (name, o.name))
        vol, cen, _ = volume_properties(vs, fs)
        lo = [min(v[k] for v in vs) for k in range(3)]
        hi = [max(v[k] for v in vs) for k in range(3)]
        if not (close(list(o.matrix_world.translation), s["origin"])
                and close(vol, s["volume"], 1e-6) and close(cen, s["centroid"])
                and close([lo, hi], s["bounds"]) and close(size_of(vs), s["size"])):
            fail("%s: %s: origin, volume, centroid or bounds differ from expected.json"
                 % (name, o.name))
        if any(abs(x) > 1e-6 for x in o.rotation_euler) or not close(list(o.scale), [1, 1, 1]):
            fail("%s: %s is rotated or scaled" % (name, o.name))
    lowest = min(v[2] for vs, _ in shapes.values() for v in vs)
    if not close(lowest, 0.0, 1e-6) or not close(lowest, exp["lowest_z"], 1e-6):
        fail("%s: lowest point at z = %f, not 0" % (name, lowest))
    sizes = sorted(size_of(vs) for vs, _ in shapes.values())
    tol = 0.1 * sizes[len(sizes) // 2]
    if not close(tol, exp["tolerance"]):
        fail("%s: tolerance %f, expected.json %f" % (name, tol, exp["tolerance"]))

    root = bpy.data.objects.get("joints")
    if root is None or root.type != "EMPTY" or root.parent is not None:
        fail("%s: no EMPTY named joints at the top" % name)
        return None
    children = sorted(root.children, key=lambda o: o.name)
    if [c.name for c in children] != [j["name"] for j in exp["joints"]]:
        fail("%s: joints %s" % (name, [c.name for c in children]))
        return None
    rows = []
    joined = set()
    for j, e in zip(children, exp["joints"]):
        p = list(j.matrix_world.translation)
        frame = j.matrix_world.to_3x3()
        axes = [list(frame.col[i]) for i in range(3)]
        spec = read_joint(j.get("joint", ""))
        if not (close(p, e["position"]) and close(list(j.rotation_euler), e["rotation_euler"])
                and close(axes, e["frame_axes"]) and j.get("joint") == e["spec"]
                and spec[":type"] == ":" + e["type"] and j.rotation_mode == "XYZ"):
            fail("%s: %s position/rotation/spec differ from expected.json" % (name, j.name))
        mj = e["mujoco"]
        if e["type"] == "hinge":
            axis = spec[":axis"]
            world = list(frame @ type(frame.col[0])(axis))
            lo, hi = mj[0]["range_deg"]
            if not (close(list(axis), e["axis"]) and close(world, mj[0]["axis_world"])
                    and close(spec[":limit"], [math.radians(lo), math.radians(hi)], 1e-12)
                    and close(spec[":limit"], e["limit"]) and set(spec) == {":type", ":limit", ":axis"}):
                fail("%s: %s: axis %s (world %s) or limit %s is not MuJoCo's %s %s"
                     % (name, j.name, axis, world, spec[":limit"], mj[0]["axis_world"], (lo, hi)))
            limits = "[%.4f %.4f] axis %s" % (spec[":limit"][0], spec[":limit"][1],
                                              [round(c, 3) + 0.0 for c in world])
        else:
            by_name = {d["joint"]: d for d in mj}
            for key, dof in e["cone_dofs"].items():
                want = (math.radians(max(abs(a) for a in by_name[dof]["range_deg"])) if dof
                        else (0.0 if key == "twist" else 0.1))
                if not (close(spec[":" + key], want, 1e-12) and close(spec[":" + key], e[key])):
                    fail("%s: %s: %s = %s, want %s" % (name, j.name, key, spec[":" + key], want))
                if dof:   # the MuJoCo hinge's axis is the swing's (or twist's) axis
                    col = {"twist": 0, "limit-xz": 1, "limit-xy": 2}[key]
                    if abs(abs(sum(a * b for a, b in zip(axes[col], by_name[dof]["axis_world"])))
                           - 1) > 1e-5:
                        fail("%s: %s: local axis %d is not MuJoCo's %s" % (name, j.name, col, dof))
            limits = "xz %.4f xy %.4f twist %.4f" % (spec[":limit-xz"], spec[":limit-xy"],
                                                     spec[":twist"])
        dist = {}
        for n, (vs, fs) in shapes.items():
            inside = inside_convex(p, vs, fs)
            dist[n] = (0.0 if inside else cube_distance(p, triangles(vs, fs)),
                       euclid_distance(p, vs, fs), inside)
        near = sorted(dist.items(), key=lambda kv: (r9(kv[1][0]), r9(kv[1][1]), kv[0]))
        for got, want in zip(near, e["nearest"]):
            if not (got[0] == want["segment"] and close(got[1][0], want["cube"])
                    and close(got[1][1], want["distance"]) and got[1][2] == want["inside"]):
                fail("%s: %s: nearest %s %s, expected.json %s" % (name, j.name, got[0], got[1], want))
        a, b = e["segments"]
        pair, r = cortex_search(dist)
        if pair != sorted([a, b]):
            fail("%s: %s: cortex's cube finds %s" % (name, j.name, pair))
        for s in (a, b):
            c, eu, inside = dist[s]
            if inside or not close(eu, GAP_HALF) or c > GAP_HALF + 1e-6 or c > tol:
                fail("%s: %s: %s at cube %f / %f, not in the gap" % (name, j.name, s, c, eu))
        d2 = max(dist[a][0], dist[b][0])
        third = near[2]
        if third[1][0] <= d2 + tol or third[1][1] <= tol:
            fail("%s: %s: %s only %f away (ambiguous within %f)" % (name, j.name, third[0],
                                                                    third[1][0], d2 + tol))
        order = cortex_order(j, [a, b])
        if order != [a, b]:
            fail("%s: %s: cortex order %s, expected %s" % (name, j.name, order, [a, b]))
        joined.add(frozenset((a, b)))
        rows.append((j.name, e["type"], "%s -> %s" % (a, b), dist[a][0], dist[b][0],
                     "%s %.3f" % (third[0], third[1][0]), limits, e["spec"]))

    # overlaps
    gaps = {}
    for i, a in enumerate(NAMES):
        for b in NAMES[i + 1:]:
            if intersect(shapes[a], shapes[b]):
                fail("%s: %s and %s intersect" % (name, a, b))
            pair = frozenset((a, b))
            if pair in joined:
                gaps[tuple(sorted(pair))] = closest_approach(shapes[a], shapes[b])
            elif (shrunk_bounds_met(triangles(*shapes[a]), shapes[b][0])
                  and shrunk_bounds_met(triangles(*shapes[b]), shapes[a][0])):
                fail("%s: %s and %s would get cortex's overlap warning" % (name, a, b))
    return {"rows": rows, "tolerance": tol, "gaps": gaps, "sizes": sizes,
            "masses": {o.name: o["mass"] for o in objs}}


def print_table(exp, got):
    print("%-16s %9s %5s %6s %8s  %-22s %s" % ("segment", "mass", "verts", "size", "volume",
                                                 "origin (MuJoCo COM)", "MuJoCo bodies"))
    for s in exp["segments"]:
        print("%-16s %9.4f %5d %6.3f %8.5f  %-22s %s" % (
            s["name"], s["mass"], s["vertices"], s["size"], s["volume"],
            "[%.3f %.3f %.3f]" % tuple(s["origin"]), "+".join(s["mujoco_bodies"])))
    print("total mass %.4f; tolerance %.4f (a tenth of the median size %.3f)"
          % (exp["total_mass"], got["tolerance"], got["sizes"][len(got["sizes"]) // 2]))
    print()
    print("%-15s %-6s %-34s %6s %6s  %-22s %s" % ("joint", "type", "segments (cortex order)",
                                                  "cube a", "cube b", "3rd nearest (cube)",
                                                  "limits (rad)"))
    for n, t, segs, ca, cb, third, limits, _ in got["rows"]:
        print("%-15s %-6s %-34s %6.4f %6.4f  %-22s %s" % (n, t, segs, ca, cb, third, limits))
    print()
    print("closest approach of joined segments (vertex to surface): " + ", ".join(
        "%s/%s %.3f" % (a, b, d) for (a, b), d in sorted(got["gaps"].items())))


def json_diff(a_path, b_path):
    def objects(path):
        return {o["name"]: o for o in json.load(open(path))["objects"]}
    a, b = objects(a_path), objects(b_path)
    if set(a) != set(b):
        return sorted(set(a) ^ set(b))
    return {n: sorted(k for k in a[n] if a[n][k] != b[n][k]) for n in sorted(a) if a[n] != b[n]}


def main():
    args = dump.script_args()
    folder = os.path.normpath(os.path.abspath(args[0]) if args else os.path.join(
        HERE, "..", "..", "test", "fixtures", "humanoid"))
    with open(os.path.join(folder, "expected.json")) as f:
        expected = json.load(f)
    files = expected["files"]
    failures = []
    fail = failures.append
    if list(files) != ["humanoid.blend", "humanoid-heavy-hands.blend"]:
        fail("expected.json files: %s" % list(files))
    results = {}
    for fname, exp in files.items():
        results[fname] = check_file(os.path.join(folder, fname), exp, fail)
    base = results.get("humanoid.blend")
    heavy = results.get("humanoid-heavy-hands.blend")
    if base and heavy:
        h = files["humanoid-heavy-hands.blend"]
        m = heavy["masses"]
        for side in ("right", "left"):
            if not close(m[side + "_lower_arm"] / m[side + "_upper_arm"], 10.0, 1e-6):
                fail("heavy hands: %s lower/upper arm mass ratio %f" % (
                    side, m[side + "_lower_arm"] / m[side + "_upper_arm"]))
        if not close(h["max_joined_mass_ratio"], 10.0, 1e-6):
            fail("heavy hands: largest joined mass ratio %s" % h["max_joined_mass_ratio"])
        diff = json_diff(os.path.join(folder, "humanoid-heavy-hands.json"),
                         os.path.join(folder, "humanoid.json"))
        if diff != {"left_lower_arm": ["properties"], "right_lower_arm": ["properties"]}:
            fail("heavy hands: differs from humanoid.json by %s" % diff)
    if base:
        print("\n== humanoid.blend (%s)" % bpy.app.version_string)
        print_table(files["humanoid.blend"], base)
    if heavy:
        print("\n== humanoid-heavy-hands.blend: lower arms %.4f kg (10 x upper arms); "
              "largest joined mass ratio %.2f"
              % (heavy["masses"]["right_lower_arm"],
                 files["humanoid-heavy-hands.blend"]["max_joined_mass_ratio"]))
    finish(failures, "humanoid")


if __name__ == "__main__":
    main()
