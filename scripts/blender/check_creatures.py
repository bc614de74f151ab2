"""Check the reference creatures against the body conventions; print a table.

    blender -b --factory-startup --python-exit-code 1 \
        --python scripts/blender/check_creatures.py -- [FILE.blend ...]

Default files: assets/Models/test-creature/{worm,hand}.blend.  For every
child of the "joints" empty it checks that

- the two mesh segments nearest to the joint are the intended ones (from the
  names: worm-joint -> worm-1/worm-2, joint-F-1 -> palm/F-1,
  joint-F-n -> F-(n-1)/F-n), by the Euclidean distance from the joint to each
  mesh's surface and by the L-infinity distance to each mesh's world bounding
  box (what a growing axis-aligned cube meets);
- a cube centred on the joint whose half-size doubles from 0.01 (as cortex's
  joint-targets does) first meets two segments, and they are the intended ones;
- the "joint" string parses, and for hinges it tells where the distal segment's
  centre moves when rotated (right-hand rule, about the axis in the joint's
  frame) by the upper and the lower limit;

and for every segment that it has a float "mass", <= 100 vertices and a
closed mesh with outward normals (positive volume).  Exits 1 on a failure.
"""

import math
import os
import re
import sys

import bpy
from mathutils import Matrix, Vector

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402


# ------------------------------------------------- tiny Clojure-ish reader

TOKEN = re.compile(r"[\s,]*(\(|\)|\[|\]|\{|\}|[^\s,()\[\]{}]+)")


def parse(text):
    tokens = TOKEN.findall(text)
    pos = 0

    def read():
        nonlocal pos
        t = tokens[pos]
        pos += 1
        if t in "([{":
            close = {"(": ")", "[": "]", "{": "}"}[t]
            items = []
            while tokens[pos] != close:
                items.append(read())
            pos += 1
            if t == "{":
                return dict(zip(items[0::2], items[1::2]))
            return ("list", items) if t == "(" else items
        try:
            return int(t)
        except ValueError:
            pass
        try:
            return float(t)
        except ValueError:
            return t

    value = read()
    if pos != len(tokens):
        raise ValueError("trailing text in %r" % text)
    return value


def evaluate(x):
    if isinstance(x, tuple) and x[0] == "list":
        op, *args = x[1]
        vals = [evaluate(a) for a in args]
        if op == "/":
            return vals[0] / vals[1] if len(vals) == 2 else 1.0 / vals[0]
        if op == "*":
            return math.prod(vals)
        if op == "+":
            return sum(vals)
        if op == "-":
            return -vals[0] if len(vals) == 1 else vals[0] - sum(vals[1:])
        if op == "Vector3f.":
            return Vector(vals)
        raise ValueError("unknown form %r" % op)
    if isinstance(x, list):
        return [evaluate(v) for v in x]
    if isinstance(x, dict):
        return {k: evaluate(v) for k, v in x.items()}
    if x == "Math/PI":
        return math.pi
    return x


def read_joint(text):
    return evaluate(parse(text))


# ------------------------------------------------------------- geometry

def world_verts(obj):
    mw = obj.matrix_world
    return [mw @ v.co for v in obj.data.vertices]


def linf_to_aabb(p, obj):
    vs = world_verts(obj)
    d = 0.0
    for i in range(3):
        lo = min(v[i] for v in vs)
        hi = max(v[i] for v in vs)
        d = max(d, lo - p[i], p[i] - hi)
    return max(d, 0.0)


def euclid_to_mesh(p, obj):
    inv = obj.matrix_world.inverted()
    ok, loc, normal, _ = obj.closest_point_on_mesh(inv @ p)
    if not ok:
        return float("inf")
    wloc = obj.matrix_world @ loc
    d = (p - wloc).length
    wnormal = (obj.matrix_world.to_3x3().inverted().transposed() @ normal).normalized()
    return -d if (p - wloc).dot(wnormal) < 0 else d   # negative: inside


def signed_volume(obj):
    me = obj.data
    vol = 0.0
    for poly in me.polygons:
        vs = [me.vertices[i].co for i in poly.vertices]
        for k in range(1, len(vs) - 1):
            vol += vs[0].dot(vs[k].cross(vs[k + 1])) / 6.0
    return vol


def closed(obj):
    me = obj.data
    count = {}
    for poly in me.polygons:
        for e in poly.edge_keys:
            count[e] = count.get(e, 0) + 1
    return all(c == 2 for c in count.values())


def intended(joint_name):
    if joint_name == "worm-joint":
        return ("worm-1", "worm-2")
    m = re.fullmatch(r"joint-(\w+)-(\d+)", joint_name)
    if not m:
        return None
    f, n = m.group(1), int(m.group(2))
    return ("palm" if n == 1 else "%s-%d" % (f, n - 1), "%s-%d" % (f, n))


def direction(v, eps=1e-6):
    parts = []
    for comp, name in zip(v, "XYZ"):
        if abs(comp) > max(eps, 0.25 * v.length):
            parts.append(("+" if comp > 0 else "-") + name)
    return "".join(parts) or "0"


def fmt(x):
    return "%.3f" % x


# ------------------------------------------------------------------ check

def check_file(path):
    bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path), load_ui=False)
    bpy.context.view_layer.update()
    failures = []
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    root = bpy.data.objects.get("joints")
    print("\n== %s (%s)" % (os.path.basename(path), bpy.app.version_string))
    if root is None or root.type != "EMPTY":
        failures.append("no EMPTY named joints")
        return failures

    print("%-10s %5s %5s %8s %s" % ("segment", "mass", "verts", "volume", "closed"))
    for o in sorted(meshes, key=lambda o: o.name):
        mass = o.get("mass")
        vol = signed_volume(o)
        ok_closed = closed(o)
        print("%-10s %5s %5d %8.4f %s" % (o.name, mass, len(o.data.vertices), vol, ok_closed))
        if not isinstance(mass, float) or mass <= 0:
            failures.append("%s: mass %r" % (o.name, mass))
        if len(o.data.vertices) > 100:
            failures.append("%s: %d vertices" % (o.name, len(o.data.vertices)))
        if vol <= 0 or not ok_closed:
            failures.append("%s: not a closed outward mesh" % o.name)

    header = ("joint", "type", "nearest two (euclid)", "d1", "d2", "3rd nearest", "d3",
              "cube r", "cube meets", "cortex order", "hinge: +limit / -limit moves distal")
    rows = []
    for j in sorted(root.children, key=lambda o: o.name):
        p = j.matrix_world.translation.copy()
        want = intended(j.name)
        spec = read_joint(j["joint"])
        none = (float("inf"), "-")      # stands in for a missing third segment
        eu = sorted(((euclid_to_mesh(p, m), m.name) for m in meshes)) + [none]
        li = sorted(((linf_to_aabb(p, m), m.name) for m in meshes)) + [none]
        near_eu = {eu[0][1], eu[1][1]}
        near_li = {li[0][1], li[1][1]}
        # cortex: an axis-aligned box of half-size r, doubling from 0.01,
        # until it meets at least two geometries.
        r = 0.01
        while True:
            hit = [n for d, n in li[:-1] if d <= r]
            if len(hit) >= 2:
                break
            r *= 2
        # cortex's order of the two targets: by (1,1,1) . (position in the joint frame)
        rot_inv = j.matrix_world.to_3x3().normalized().inverted()
        order = sorted(hit[:2], key=lambda n: Vector((1, 1, 1)).dot(
            rot_inv @ (bpy.data.objects[n].matrix_world.translation - p)))
        motion = ""
        if spec.get(":type") == ":hinge":
            axis = spec.get(":axis", Vector((1, 0, 0)))
            waxis = (j.matrix_world.to_3x3().normalized() @ axis).normalized()
            lo, hi = spec[":limit"]
            distal = bpy.data.objects[want[1]] if want else None
            if distal is not None:
                c = distal.matrix_world.translation - p
                moves = []
                for ang in (hi, lo):
                    delta = Matrix.Rotation(ang, 3, waxis) @ c - c
                    moves.append("%s%s" % (fmt(ang), "->" + direction(delta) if ang else "->0"))
                motion = "axis(world)=%s  %s" % (direction(waxis), " / ".join(moves))
        elif spec.get(":type") == ":cone":
            xaxis = j.matrix_world.to_3x3().normalized() @ Vector((1, 0, 0))
            motion = "twist axis X(world)=%s  xz=%s xy=%s twist=%s" % (
                direction(xaxis), spec[":limit-xz"], spec[":limit-xy"], spec[":twist"])
        rows.append((j.name, spec.get(":type", "?")[1:], "/".join(n for d, n in eu[:2]),
                     fmt(eu[0][0]), fmt(eu[1][0]), eu[2][1], fmt(eu[2][0]),
                     fmt(r), "/".join(sorted(hit)), "->".join(order), motion))
        if want is None:
            failures.append("%s: unexpected joint name" % j.name)
            continue
        if near_eu != set(want) or near_li != set(want) or set(hit) != set(want):
            failures.append("%s: nearest %s / %s / cube %s, want %s"
                            % (j.name, near_eu, near_li, hit, want))
        if min(eu[2][0], li[2][0]) <= max(eu[0][0], eu[1][0]):
            failures.append("%s: third segment not farther than the intended two" % j.name)
        if eu[0][0] < 0 or eu[1][0] < 0:
            failures.append("%s: joint inside a segment" % j.name)
        if list(order) != list(want):
            failures.append("%s: cortex order %s is not proximal first" % (j.name, order))
    widths = [max(len(str(r[i])) for r in rows + [header]) for i in range(len(header))]
    line = "  ".join("%-" + str(w) + "s" for w in widths)
    print()
    print(line % header)
    for r in rows:
        print(line % r)
    return failures


def main():
    args = dump.script_args()
    if not args:
        base = os.path.join(HERE, "..", "..", "assets", "Models", "test-creature")
        args = [os.path.join(base, "worm.blend"), os.path.join(base, "hand.blend")]
    failures = []
    for path in args:
        failures += check_file(path)
    finish(failures, "creature")



def finish(failures, what):
    """Print the failures and exit 1, or say that every `what` check passed."""
    print()
    if failures:
        print("FAILED:")
        for f in failures:
            print("  " + f)
        sys.exit(1)
    print("all %s checks passed" % what)

if __name__ == "__main__":
    main()
