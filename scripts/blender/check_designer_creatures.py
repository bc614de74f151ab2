"""Check test/fixtures/designer/ against expected.json and the creature rules.

    blender -b --factory-startup --python-exit-code 1 \
        --python scripts/blender/check_designer_creatures.py -- [DIR]

DIR defaults to test/fixtures/designer.  Everything is measured on the saved
.blend files (Blender's own geometry: closest_point_on_mesh, world vertices),
and compared with expected.json (written by make_designer_creatures.py from
its design numbers):

- every file: segments (names, float masses, 8 vertices, closed, volume,
  world centre and bounds), joints (parent, position, rotation, spec, the
  distances in "nearest", cortex's order of the two segments), overlaps;
- quadruped.blend: 14 segments with the masses of the brief, feet at z=0,
  no overlaps; for each of its 13 joints the two intended segments at 0.015
  (Euclidean and cube), every other segment >= 0.3 away (both), the
  doubling-then-bisecting cube of cortex's targets-near finds the intended
  pair, proximal segment first; knees rest on their lower limit (0);
- every variant: all joints but the faulty one still obey those rules, its
  one mistake is there (measured), and its dump.py JSON differs from
  quadruped.json only in the objects (and fields) the mistake is about.

Prints a table of the quadruped and one line per variant; exits 1 on a failure.
"""

import json
import math
import os
import sys

import bpy
from mathutils import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402
from check_creatures import (closed, euclid_to_mesh, finish, read_joint, signed_volume,  # noqa: E402
                             world_verts)

TOL = 1e-5
GAP_HALF = 0.015
CLEARANCE = 0.3

MASSES = {"torso": 4.0, "neck": 0.4, "head": 0.6, "tail-1": 0.2, "tail-2": 0.2, "tail-3": 0.2}
LEGS = ("front-r", "front-l", "back-r", "back-l")
for _leg in LEGS:
    MASSES["upper-leg-" + _leg] = 0.5
    MASSES["lower-leg-" + _leg] = 0.3


def proximal_first(joint):
    """The pair a quadruped joint joins, proximal first, from its name."""
    for leg in LEGS:
        if joint == "hip-" + leg:
            return ["torso", "upper-leg-" + leg]
        if joint in ("knee-" + leg, "knee-" + leg + "-2"):
            return ["upper-leg-" + leg, "lower-leg-" + leg]
    if joint == "neck-joint":
        return ["torso", "neck"]
    if joint in ("head-joint", "stray"):
        return ["neck", "head"]
    if joint.startswith("tail-joint-"):
        n = int(joint[len("tail-joint-"):])
        return ["torso" if n == 1 else "tail-%d" % (n - 1), "tail-%d" % n]
    return None


# Each variant: (what its JSON adds, removes, changes: {object: fields}).
DIFFS = {
    "misplaced-joint": ([], [], {"knee-front-r": ["location", "matrix_world"]}),
    "far-joint": ([], [], {"knee-back-l": ["location", "matrix_world"]}),
    "inside-joint": ([], [], {"knee-front-l": ["location", "matrix_world"]}),
    "ambiguous-joint": ([], [], {"tail-joint-2": ["location", "matrix_world"]}),
    "duplicate-joint": (["knee-front-r-2"], [], {}),
    "misnamed-joints": (["Joints"], ["joints"], {}),
    "stray-joint": (["stray"], [], {}),
    "typo-key": ([], [], {"knee-front-r": ["properties"]}),
    "degree-limit": ([], [], {"knee-front-r": ["properties"]}),
    "overlap": (["rock"], [], {}),
}


# ------------------------------------------------------------- measuring

def bounds(obj):
    vs = world_verts(obj)
    return ([min(v[i] for v in vs) for i in range(3)], [max(v[i] for v in vs) for i in range(3)])


def measure(p, meshes):
    """{name: (cube, euclid, inside)} for point p and every mesh."""
    out = {}
    for m in meshes:
        lo, hi = bounds(m)
        cube = abs(max(max(lo[i] - p[i], p[i] - hi[i]) for i in range(3)))
        e = euclid_to_mesh(p, m)
        out[m.name] = (cube, abs(e), e < 0)
    return out


def cortex_pair(dist):
    """The two segments cortex's targets-near picks (by name among those found)."""
    def found(r):
        return sorted(n for n, (cube, _, _) in dist.items() if cube <= r)
    r = 0.01
    while len(found(r)) < 2:
        r *= 2
        if r > 100:
            return None
    lo, hi = r / 2, r
    for _ in range(24):
        if len(found(hi)) == 2:
            break
        mid = (lo + hi) / 2
        if len(found(mid)) >= 2:
            hi = mid
        else:
            lo = mid
    return found(hi)[:2]


def cortex_order(joint, names):
    rot_inv = joint.matrix_world.to_3x3().normalized().inverted()
    p = joint.matrix_world.translation
    return sorted(names, key=lambda n: Vector((1, 1, 1)).dot(
        rot_inv @ (bpy.data.objects[n].matrix_world.translation - p)))


def close(a, b, tol=TOL):
    if not isinstance(a, (int, float)):
        return len(a) == len(b) and all(close(x, y, tol) for x, y in zip(a, b))
    return abs(a - b) <= tol


# ------------------------------------------------------------------ checks

def check_file(path, exp, fail):
    bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path), load_ui=False)
    bpy.context.view_layer.update()
    name = os.path.basename(path)
    meshes = sorted((o for o in bpy.data.objects if o.type == "MESH"), key=lambda o: o.name)

    # segments
    if [m.name for m in meshes] != [s["name"] for s in exp["segments"]]:
        fail("%s: segments %s" % (name, [m.name for m in meshes]))
        return {}
    for m, s in zip(meshes, exp["segments"]):
        lo, hi = bounds(m)
        mass = m.get("mass")
        if not isinstance(mass, float) or not close(mass, s["mass"]):
            fail("%s: %s mass %r" % (name, m.name, mass))
        if len(m.data.vertices) != s["vertices"] or not closed(m):
            fail("%s: %s has %d vertices or is open" % (name, m.name, len(m.data.vertices)))
        if not close(signed_volume(m), s["volume"], 1e-6):
            fail("%s: %s volume %f" % (name, m.name, signed_volume(m)))
        c, h = s["center"], s["half_extents"]
        if not (close(m.matrix_world.translation, c)
                and close(lo, [c[i] - h[i] for i in range(3)])
                and close(hi, [c[i] + h[i] for i in range(3)])):
            fail("%s: %s is not the box of expected.json" % (name, m.name))

    # overlaps (boxes: bounds are exact)
    found = []
    for i, a in enumerate(meshes):
        for b in meshes[i + 1:]:
            (alo, ahi), (blo, bhi) = bounds(a), bounds(b)
            ext = [min(ahi[k], bhi[k]) - max(alo[k], blo[k]) for k in range(3)]
            if min(ext) > TOL:
                found.append((sorted([a.name, b.name]), min(ext)))
    if len(found) != len(exp["overlaps"]) or not all(
            f[0] == e["segments"] and close(f[1], e["depth"])
            for f, e in zip(found, exp["overlaps"])):
        fail("%s: overlaps %s" % (name, found))

    # joints
    root = bpy.data.objects.get(exp["joints_parent"])
    if root is None or root.type != "EMPTY":
        fail("%s: no EMPTY %s" % (name, exp["joints_parent"]))
        return {}
    children = sorted(root.children, key=lambda o: o.name)
    if [c.name for c in children] != [j["name"] for j in exp["joints"]]:
        fail("%s: joints %s" % (name, [c.name for c in children]))
        return {}
    faulty = (exp["mistake"] or {}).get("object")
    rows = {}
    for j, e in zip(children, exp["joints"]):
        p = j.matrix_world.translation.copy()
        dist = measure(p, meshes)
        pair = cortex_pair(dist)
        order = cortex_order(j, e["segments"])
        rows[j.name] = (e, dist, pair, order)
        axes = [list(j.matrix_world.to_3x3().col[i]) for i in range(3)]
        if not (close(p, e["position"]) and close(j.rotation_euler, e["rotation_euler"])
                and close(axes, e["frame_axes"]) and j.get("joint") == e["spec"]
                and read_joint(j["joint"])[":type"] == ":" + e["type"]):
            fail("%s: %s position/rotation/spec differ from expected.json" % (name, j.name))
        for n in e["nearest"]:
            got = dist[n["segment"]]
            if not (close(got[0], n["cube"]) and close(got[1], n["distance"])
                    and got[2] == n["inside"]):
                fail("%s: %s to %s measures %s, expected %s" % (name, j.name, n["segment"], got, n))
        listed = {n["segment"] for n in e["nearest"]}
        if any(v[0] < e["nearest"][-1]["cube"] - TOL for k, v in dist.items() if k not in listed):
            fail("%s: %s has a nearer segment than expected.json lists" % (name, j.name))
        if order != e["segments"]:
            fail("%s: %s cortex order %s, expected.json %s" % (name, j.name, order, e["segments"]))
        if j.name == faulty:
            continue
        # the rules every good joint follows
        want = proximal_first(j.name)
        if e["segments"] != want:
            fail("%s: %s joins %s, want %s (proximal first)" % (name, j.name, e["segments"], want))
        for seg, (cube, eu, inside) in dist.items():
            if seg in want:
                if not (close(cube, GAP_HALF) and close(eu, GAP_HALF) and not inside):
                    fail("%s: %s is %f/%f from %s, not in the gap" % (name, j.name, cube, eu, seg))
            elif cube < CLEARANCE or eu < CLEARANCE:
                fail("%s: %s only %f/%f from %s" % (name, j.name, cube, eu, seg))
        if pair is None or sorted(pair) != sorted(want):
            fail("%s: %s: cortex's cube finds %s" % (name, j.name, pair))
        if e["type"] == "hinge" and j.name.startswith("knee-"):
            spec = read_joint(j["joint"])
            if spec.get(":limit", [None])[0] != 0 or list(spec.get(":axis", [])) != [0, 1, 0]:
                fail("%s: %s does not rest on its lower limit 0 about Y" % (name, j.name))
    return rows


def json_diff(variant_json, base_json, rename):
    def objects(path, rename):
        data = json.load(open(path))
        out = {}
        for o in data["objects"]:
            o = dict(o, parent=rename.get(o["parent"], o["parent"]))
            out[o["name"]] = o
        return out
    a, b = objects(variant_json, rename), objects(base_json, {})
    added = sorted(set(a) - set(b))
    removed = sorted(set(b) - set(a))
    changed = {n: sorted(k for k in a[n] if a[n][k] != b[n][k])
               for n in sorted(set(a) & set(b)) if a[n] != b[n]}
    return added, removed, changed


def check_mistake(kind, exp, rows, fail):
    m = exp["mistake"]
    obj = m["object"]
    if kind in ("misplaced-joint", "far-joint", "inside-joint", "ambiguous-joint",
                "duplicate-joint", "typo-key", "degree-limit"):
        e, dist, pair, order = rows[obj]
        by_cube = sorted(dist.items(), key=lambda kv: (kv[1][0], kv[0]))
    want = proximal_first(obj) if obj not in ("Joints", "rock") else None
    if kind == "misplaced-joint":
        two = {n for n, _ in by_cube[:2]}
        ok = (two == set(want) and all(0.19 < v[0] and 0.19 < v[1] for _, v in by_cube[:2])
              and by_cube[2][1][0] >= CLEARANCE)
        info = "%s: %s" % (obj, ", ".join("%s %.4f/%.4f" % (n, v[0], v[1]) for n, v in by_cube[:3]))
    elif kind == "far-joint":
        ok = min(v[1] for v in dist.values()) >= 4.0 - TOL
        info = "%s: nearest (euclid) %s" % (obj, ", ".join(
            "%s %.4f" % (n, v[1]) for n, v in sorted(dist.items(), key=lambda kv: kv[1][1])[:3]))
    elif kind == "inside-joint":
        ok = dist["torso"][2] and close(dist["torso"][1], 0.25)
        info = "%s: inside torso, %.4f from its surface" % (obj, dist["torso"][1])
    elif kind == "ambiguous-joint":
        three = [n for n, _ in by_cube[:3]]
        ok = (set(three) == {"tail-1", "tail-2", "torso"} == set(m["near"])
              and by_cube[2][1][0] <= 1.25 * by_cube[0][1][0]
              and by_cube[3][1][0] >= CLEARANCE)
        info = "%s: %s" % (obj, ", ".join("%s %.4f/%.4f" % (n, v[0], v[1]) for n, v in by_cube[:4]))
    elif kind == "duplicate-joint":
        pairs = [sorted(rows[n][2]) for n in (obj, m["duplicates"])]
        ok = pairs[0] == pairs[1] == sorted(want)
        info = "%s and %s both join %s" % (obj, m["duplicates"], pairs[0])
    elif kind == "misnamed-joints":
        ok = (bpy.data.objects.get("joints") is None
              and len(bpy.data.objects["Joints"].children) == 13)
        info = "no object named joints; Joints has %d children" % len(
            bpy.data.objects["Joints"].children)
    elif kind == "stray-joint":
        s = bpy.data.objects.get("stray")
        dist = measure(s.matrix_world.translation,
                       [o for o in bpy.data.objects if o.type == "MESH"])
        near = sorted(dist.items(), key=lambda kv: (kv[1][0], kv[0]))
        ok = (s.type == "EMPTY" and s.parent is None and s.get("joint") == "{:type :point}"
              and {n for n, _ in near[:2]} == set(want)
              and all(close(v[0], GAP_HALF) for _, v in near[:2]))
        info = "stray: parent None, joint %r, %s" % (s.get("joint"), ", ".join(
            "%s %.4f" % (n, v[0]) for n, v in near[:3]))
    elif kind == "typo-key":
        spec = read_joint(bpy.data.objects[obj]["joint"])
        ok = ":axs" in spec and ":axis" not in spec
        info = "%s: keys %s" % (obj, sorted(spec))
    elif kind == "degree-limit":
        spec = read_joint(bpy.data.objects[obj]["joint"])
        ok = spec[":limit"][1] > 2 * math.pi
        info = "%s: limit %s" % (obj, spec[":limit"])
    elif kind == "overlap":
        rock = bpy.data.objects["rock"]
        rlo, rhi = bounds(rock)
        tlo, thi = bounds(bpy.data.objects["torso"])
        depth = min(min(rhi[k], thi[k]) - max(rlo[k], tlo[k]) for k in range(3))
        near = min(v[1]["rock"][0] for v in rows.values())
        ok = (close(depth, 0.1) and rock.get("mass") == 1.0 and near >= CLEARANCE
              and all("rock" not in v[2] for v in rows.values()))
        info = "rock sunk %.4f into torso; nearest joint %.4f away (cube)" % (depth, near)
    if not ok:
        fail("%s: the mistake is not there: %s" % (kind, info))
    return info


def table(exp, rows):
    print("%-18s %5s %5s %8s  %-22s %s" % ("segment", "mass", "verts", "volume", "centre",
                                          "half extents"))
    for s in exp["segments"]:
        print("%-18s %5s %5d %8.5f  %-22s %s" % (s["name"], s["mass"], s["vertices"], s["volume"],
                                                 s["center"], s["half_extents"]))
    print()
    print("%-14s %-6s %-36s %-20s %-16s %s" % ("joint", "type", "segments (cortex order)",
                                               "position", "rotation", "limits / 3rd nearest"))
    for n, (e, dist, pair, order) in sorted(rows.items()):
        lim = e.get("limit") or ("xz %s xy %s twist %s" % (e["limit-xz"], e["limit-xy"], e["twist"])
                                 if e["type"] == "cone" else "-")
        third = e["nearest"][2]
        print("%-14s %-6s %-36s %-20s %-16s %s; %s %.3f" % (
            n, e["type"], " -> ".join(order), e["position"],
            [round(x, 4) for x in e["rotation_euler"]], lim, third["segment"], third["cube"]))


def main():
    args = dump.script_args()
    folder = os.path.normpath(os.path.abspath(args[0]) if args else os.path.join(
        HERE, "..", "..", "test", "fixtures", "designer"))
    with open(os.path.join(folder, "expected.json")) as f:
        expected = json.load(f)["files"]
    failures = []
    fail = failures.append
    if list(expected)[0] != "quadruped.blend" or set(expected) != {
            "quadruped.blend"} | {k + ".blend" for k in DIFFS}:
        fail("expected.json files: %s" % list(expected))

    rows = check_file(os.path.join(folder, "quadruped.blend"), expected["quadruped.blend"], fail)
    q = expected["quadruped.blend"]
    if q["mistake"] is not None or q["overlaps"] or len(q["segments"]) != 14 or len(rows) != 13:
        fail("quadruped: %d segments, %d joints" % (len(q["segments"]), len(rows)))
    if {s["name"]: s["mass"] for s in q["segments"]} != MASSES:
        fail("quadruped: masses differ from the brief")
    if not close(min(bounds(o)[0][2] for o in bpy.data.objects if o.type == "MESH"), 0.0):
        fail("quadruped: feet not at z = 0")
    print("\n== quadruped.blend (%s)" % bpy.app.version_string)
    table(q, rows)

    print("\n== variants")
    base_json = os.path.join(folder, "quadruped.json")
    for kind, (add, remove, change) in DIFFS.items():
        exp = expected[kind + ".blend"]
        if exp["mistake"] is None or exp["mistake"]["kind"] != kind:
            fail("%s: expected.json has no mistake" % kind)
            continue
        rows = check_file(os.path.join(folder, kind + ".blend"), exp, fail)
        if not rows:
            continue
        info = check_mistake(kind, exp, rows, fail)
        diff = json_diff(os.path.join(folder, kind + ".json"), base_json,
                         {"Joints": "joints"} if kind == "misnamed-joints" else {})
        if diff != (add, remove, change):
            fail("%s: differs from quadruped.json by %s" % (kind, diff))
        print("%-16s %s" % (kind, info))

    finish(failures, "designer creature")


if __name__ == "__main__":
    main()
