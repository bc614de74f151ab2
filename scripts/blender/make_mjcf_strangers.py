"""Convert MuJoCo MJCF models into cortex creatures (.blend), the way an
outside designer following doc/designing-creatures.md would.

    blender -b --factory-startup --python scripts/blender/make_mjcf_strangers.py -- OUTDIR MODEL.xml ...

test/fixtures/strangers/walker2d*.blend were made by Blender 3.4 with OUTDIR
a scratch directory and MODEL.xml pybullet_data 3.2.7's mjcf/walker2d.xml
(target/python after .ci/run), plus walker2d-apart (the legs 0.06 apart,
otherwise clean; see `apart` below); test/fixtures/strangers/mjcf.json keeps
the joints of the three .json files it wrote. It was written from the
designer's guide alone, without reading cortex's rules.

For each MODEL.xml it writes OUTDIR/MODEL.blend (clean) and
OUTDIR/MODEL-sloppy.blend, plus OUTDIR/MODEL.json (what was built: segments,
masses, joints, anchors, axes, ranges) for the comparison scripts.

Conventions (from the doc only):
- one mesh object per MuJoCo body that has its own hinge; a body with no
  joint is welded to its parent in MuJoCo, and the doc has no fixed joint,
  so its geoms go into the parent's mesh object; the root body's own
  joints (free / slide / root hinge) are dropped: a cortex creature is free.
- geoms: capsule = tube with hemispherical ringed caps, cylinder = tube
  with flat caps, sphere = UV sphere, box = cube; each a closed piece.
- custom properties: `mass` (MuJoCo's: density x volume, settotalmass
  applied), `friction` (the geom's sliding friction).
- an empty `joints`; under it one empty per hinge at the MuJoCo anchor,
  `joint` = "{:type :hinge :limit [lo hi] :axis [x y z]}" (radians, axis in
  the empty's frame), the empty turned so that the parent segment lies
  towards -X-Y-Z of it (the doc: that one comes first), so that cortex's
  angle is MuJoCo's (child relative to parent).
- several hinges in one body (none in ant/cheetah/hopper/walker2d): the
  doc has no multi-axis hinge; nearest documented form is a :cone about
  the first hinge's axis with the limits taken from the hinges' ranges.

Sloppy variant: every segment object gets an unapplied rotation and
non-uniform scale (mesh counter-transformed so the world shape is the
same), names with spaces and dots, joint empties off the anchor by 4% of
the child segment's size in a random direction and turned arbitrarily
(keeping the documented segment order); walker2d's two legs, which sit in
exactly the same place in the MJCF, are moved 0.06 apart sideways (+-y).
"""

import json
import math
import os
import random
import sys
import xml.etree.ElementTree as ET

import bpy
from mathutils import Matrix, Quaternion, Vector


# ------------------------------------------------------------- MJCF

def fl(s, n=None):
    v = [float(x) for x in s.split()]
    return v


def quat_of(el, angle_scale, default=None):
    """Orientation of an element (quat, axisangle, euler [xyz], zaxis)."""
    if el.get("quat"):
        w, x, y, z = fl(el.get("quat"))
        return Quaternion((w, x, y, z)).normalized()
    if el.get("axisangle"):
        x, y, z, a = fl(el.get("axisangle"))
        return Quaternion(Vector((x, y, z)).normalized(), a * angle_scale)
    if el.get("euler"):
        e = [c * angle_scale for c in fl(el.get("euler"))]
        q = Quaternion()
        # MuJoCo default eulerseq "xyz" (intrinsic)
        for ax, a in zip(((1, 0, 0), (0, 1, 0), (0, 0, 1)), e):
            q = q @ Quaternion(Vector(ax), a)
        return q
    if el.get("zaxis"):
        z = Vector(fl(el.get("zaxis"))).normalized()
        return Vector((0, 0, 1)).rotation_difference(z)
    return Quaternion() if default is None else default


def parse(path):
    root = ET.parse(path).getroot()
    comp = root.find("compiler")
    comp = comp.attrib if comp is not None else {}
    angle_scale = math.pi / 180 if comp.get("angle", "degree") == "degree" else 1.0
    glob = comp.get("coordinate", "local") == "global"
    total = comp.get("settotalmass")
    dflt = {"joint": {}, "geom": {}}
    d = root.find("default")
    if d is not None:
        for k in dflt:
            e = d.find(k)
            if e is not None:
                dflt[k] = dict(e.attrib)

    def attr(el, kind):
        a = dict(dflt[kind])
        a.update(el.attrib)
        return a

    bodies = []

    def walk(el, parent, pw, qw, depth):
        if glob:
            p = Vector(fl(el.get("pos", "0 0 0")))
            q = quat_of(el, angle_scale)
        else:
            p = pw + qw @ Vector(fl(el.get("pos", "0 0 0")))
            q = qw @ quat_of(el, angle_scale)

        def to_world(v):
            return Vector(v) if glob else p + q @ Vector(v)

        def rot_world(r):
            return r if glob else q @ r

        geoms = []
        for g in el.findall("geom"):
            a = attr(g, "geom")
            t = a.get("type", "sphere")
            size = fl(a.get("size", "0"))
            dens = float(a.get("density", "1000"))
            fr = fl(a.get("friction", "1"))[0]
            if a.get("fromto"):
                f = fl(a["fromto"])
                p0, p1 = to_world(f[:3]), to_world(f[3:])
                c = (p0 + p1) / 2
                ax = p1 - p0
                half = ax.length / 2
                rot = Vector((0, 0, 1)).rotation_difference(ax.normalized()) if ax.length > 1e-12 else Quaternion()
            else:
                c = to_world(fl(a.get("pos", "0 0 0")))
                rot = rot_world(quat_of(g, angle_scale))
                half = size[1] if len(size) > 1 else 0
            r = size[0]
            if t == "capsule":
                vol = math.pi * r * r * 2 * half + 4 / 3 * math.pi * r ** 3
            elif t == "cylinder":
                vol = math.pi * r * r * 2 * half
            elif t == "sphere":
                vol = 4 / 3 * math.pi * r ** 3
            elif t == "box":
                vol = 8 * size[0] * size[1] * size[2]
            else:
                raise ValueError("geom type %s not handled" % t)
            geoms.append({"name": a.get("name", ""), "type": t, "size": size, "r": r,
                          "half": half, "centre": c, "rot": rot,
                          "mass": dens * vol, "friction": fr})
        joints = []
        for j in el.findall("joint"):
            a = attr(j, "joint")
            t = a.get("type", "hinge")
            rng = fl(a.get("range", "0 0"))
            joints.append({"name": a.get("name", ""), "type": t,
                           "anchor": to_world(fl(a.get("pos", "0 0 0"))),
                           "axis": rot_world(Quaternion()) @ Vector(fl(a.get("axis", "0 0 1"))) if not glob
                           else Vector(fl(a.get("axis", "0 0 1"))),
                           "limited": a.get("limited", "false") == "true",
                           "range": [x * angle_scale for x in rng]})
        if not glob:
            for jj in joints:
                jj["axis"] = (q @ Vector(jj["axis"])).normalized() if False else jj["axis"]
        b = {"name": el.get("name") or "body%d" % len(bodies), "parent": parent,
             "pos": p, "geoms": geoms, "joints": joints, "depth": depth}
        bodies.append(b)
        for c in el.findall("body"):
            walk(c, b["name"], p, q, depth + 1)

    for b in root.find("worldbody").findall("body"):
        walk(b, None, Vector((0, 0, 0)), Quaternion(), 0)
    if total:
        s = float(total) / sum(g["mass"] for b in bodies for g in b["geoms"])
        for b in bodies:
            for g in b["geoms"]:
                g["mass"] *= s
    return root.get("model", "model"), bodies


# ------------------------------------------------------------- meshes

N = 16      # sides of tubes and spheres
RINGS = 4   # rings per hemispherical cap


def basis(rot):
    return rot.to_matrix()


def capsule_piece(c, rot, r, half, flat=False):
    """Vertices and faces (world) of a closed capsule (or cylinder with
    flat caps when flat) along the local z of rot, centre c."""
    m = basis(rot)
    verts, faces = [], []
    rings = []   # list of (z, radius)
    if flat:
        rings = [(-half, r), (half, r)]
    else:
        for k in range(RINGS, 0, -1):
            phi = math.pi / 2 * k / (RINGS + 0.0)
            if k == RINGS:
                continue
            rings.append((-half - r * math.sin(phi), r * math.cos(phi)))
        rings.append((-half, r))
        rings.append((half, r))
        for k in range(1, RINGS):
            phi = math.pi / 2 * k / RINGS
            rings.append((half + r * math.sin(phi), r * math.cos(phi)))
    for z, rr in rings:
        for i in range(N):
            a = 2 * math.pi * i / N
            verts.append(c + m @ Vector((rr * math.cos(a), rr * math.sin(a), z)))
    bottom = len(verts)
    verts.append(c + m @ Vector((0, 0, -half - (0 if flat else r))))
    top = len(verts)
    verts.append(c + m @ Vector((0, 0, half + (0 if flat else r))))
    nr = len(rings)
    for k in range(nr - 1):
        for i in range(N):
            a0, a1 = k * N + i, k * N + (i + 1) % N
            faces.append((a0, a1, a1 + N, a0 + N))
    if flat:
        faces.append(tuple(range(N - 1, -1, -1)))
        faces.append(tuple((nr - 1) * N + i for i in range(N)))
    else:
        for i in range(N):
            faces.append((bottom, (i + 1) % N, i))
            faces.append((top, (nr - 1) * N + i, (nr - 1) * N + (i + 1) % N))
    return verts, faces


def sphere_piece(c, r):
    verts, faces = [], []
    lat = N // 2
    for k in range(1, lat):
        th = math.pi * k / lat
        for i in range(N):
            a = 2 * math.pi * i / N
            verts.append(c + Vector((r * math.sin(th) * math.cos(a), r * math.sin(th) * math.sin(a), r * math.cos(th))))
    top = len(verts)
    verts.append(c + Vector((0, 0, r)))
    bot = len(verts)
    verts.append(c + Vector((0, 0, -r)))
    for k in range(lat - 2):
        for i in range(N):
            a0, a1 = k * N + i, k * N + (i + 1) % N
            faces.append((a0, a0 + N, a1 + N, a1))
    for i in range(N):
        faces.append((top, i, (i + 1) % N))
        last = (lat - 2) * N
        faces.append((bot, last + (i + 1) % N, last + i))
    return verts, faces


def box_piece(c, rot, size):
    m = basis(rot)
    verts = [c + m @ Vector((sx * size[0], sy * size[1], sz * size[2]))
             for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return verts, faces


def geom_piece(g):
    if g["type"] == "capsule":
        if g["half"] < 1e-9:
            return sphere_piece(g["centre"], g["r"])
        return capsule_piece(g["centre"], g["rot"], g["r"], g["half"])
    if g["type"] == "cylinder":
        return capsule_piece(g["centre"], g["rot"], g["r"], g["half"], flat=True)
    if g["type"] == "sphere":
        return sphere_piece(g["centre"], g["r"])
    if g["type"] == "box":
        return box_piece(g["centre"], g["rot"], g["size"])
    raise ValueError(g["type"])


# ------------------------------------------------------------- creature

def segments_of(bodies):
    """Group bodies into segments: a body with a non-root hinge starts a
    segment; a body without joints joins its parent's."""
    by = {b["name"]: b for b in bodies}
    seg_of = {}
    segs = {}
    for b in bodies:                       # pre-order: parents first
        hinges = [j for j in b["joints"] if j["type"] == "hinge"]
        if b["parent"] is None or (hinges and b["depth"] > 0):
            seg_of[b["name"]] = b["name"]
            segs[b["name"]] = {"name": b["name"], "bodies": [b["name"]], "geoms": list(b["geoms"]),
                               "parent": seg_of.get(b["parent"]) if b["parent"] else None,
                               "hinges": hinges if b["parent"] is not None else []}
        else:
            s = seg_of[b["parent"]]
            seg_of[b["name"]] = s
            segs[s]["bodies"].append(b["name"])
            segs[s]["geoms"].extend(b["geoms"])
    return list(segs.values())


def clear():
    bpy.ops.wm.read_factory_settings(use_empty=True)


def r6(x):
    return round(float(x), 6) + 0.0


def sloppy_name(n, i):
    n = n.replace("_", " ")
    return n + (".L" if i % 3 == 0 else ".001" if i % 3 == 1 else "")


def build(model, bodies, out, sloppy, rng, apart=False):
    clear()
    if (sloppy or apart) and model == "walker2d":
        # the MJCF's two legs coincide; move them apart sideways
        def shift(name, dy):
            for b in bodies:
                pass
        left = set()
        by = {b["name"]: b for b in bodies}
        for b in bodies:
            n = b["name"]
            x = b
            while x is not None:
                if x["name"].endswith("_left") and x["name"].startswith("thigh"):
                    left.add(n)
                x = by.get(x["parent"]) if x["parent"] else None
        for b in bodies:
            if b["parent"] is None:
                continue
            dy = 0.06 if b["name"] in left else -0.06
            for g in b["geoms"]:
                g["centre"] = g["centre"] + Vector((0, dy, 0))
            for j in b["joints"]:
                j["anchor"] = j["anchor"] + Vector((0, dy, 0))
    segs = segments_of(bodies)
    names = {}
    objs = {}
    record = {"model": model, "sloppy": sloppy, "segments": [], "joints": []}
    for i, s in enumerate(segs):
        verts, faces = [], []
        for g in s["geoms"]:
            v, f = geom_piece(g)
            o = len(verts)
            verts += v
            faces += [tuple(k + o for k in face) for face in f]
        lo = Vector([min(v[k] for v in verts) for k in range(3)])
        hi = Vector([max(v[k] for v in verts) for k in range(3)])
        origin = (lo + hi) / 2
        name = sloppy_name(s["name"], i) if sloppy else s["name"]
        names[s["name"]] = name
        if sloppy:
            rot = Quaternion(Vector((rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))).normalized(),
                             rng.uniform(0.3, 2.5))
            scale = Vector((rng.uniform(0.6, 1.6), rng.uniform(0.6, 1.6), rng.uniform(0.6, 1.6)))
        else:
            rot, scale = Quaternion(), Vector((1, 1, 1))
        mw = Matrix.Translation(origin) @ rot.to_matrix().to_4x4() @ Matrix.Diagonal(scale.to_4d())
        inv = mw.inverted()
        local = [inv @ v for v in verts]
        me = bpy.data.meshes.new(name)
        me.from_pydata([tuple(v) for v in local], [], faces)
        me.validate()
        me.update()
        ob = bpy.data.objects.new(name, me)
        bpy.context.scene.collection.objects.link(ob)
        ob.location = origin
        ob.rotation_mode = "QUATERNION"
        ob.rotation_quaternion = rot
        ob.scale = scale
        mass = sum(g["mass"] for g in s["geoms"])
        ob["mass"] = float(mass)
        ob["friction"] = float(s["geoms"][0]["friction"]) if s["geoms"] else 0.5
        objs[s["name"]] = (ob, origin, hi - lo)
        record["segments"].append({"name": name, "mjcf-bodies": s["bodies"], "mass": r6(mass),
                                   "origin": [r6(c) for c in origin], "size": [r6(c) for c in hi - lo]})
    bpy.context.view_layer.update()
    root = bpy.data.objects.new("joints", None)
    root.empty_display_type = "PLAIN_AXES"
    bpy.context.scene.collection.objects.link(root)
    flip = Quaternion(Vector((1, -1, 0)).normalized(), math.pi)   # (1,1,1) -> -(1,1,1)
    one = Vector((1, 1, 1)).normalized()
    for s in segs:
        if not s["hinges"]:
            continue
        parent = s["parent"]
        pc, cc = objs[parent][1], objs[s["name"]][1]
        d = (cc - pc)
        h0 = s["hinges"][0]
        anchor = Vector(h0["anchor"])
        if sloppy:
            R = Quaternion(Vector((rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))).normalized(),
                           rng.uniform(0, math.pi))
            if (R @ one).dot(d) < 0:
                R = R @ flip
            size = max(objs[s["name"]][2])
            off = Vector((rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))).normalized() * 0.04 * size
            pos = anchor + off
        else:
            R = one.rotation_difference(d.normalized())
            pos = anchor
        Rinv = R.inverted()
        if len(s["hinges"]) == 1:
            axis = (Rinv @ Vector(h0["axis"]).normalized())
            lo, hi = h0["range"] if h0["limited"] else (-math.pi, math.pi)
            spec = "{:type :hinge :limit [%.6f %.6f] :axis [%.6f %.6f %.6f]}" % (lo, hi, axis.x, axis.y, axis.z)
        else:
            # nearest documented multi-axis form: a cone about the first axis
            m = max(max(abs(x) for x in h["range"]) for h in s["hinges"])
            R = Vector((1, 0, 0)).rotation_difference(Vector(h0["axis"]).normalized())
            spec = "{:type :cone :limit-xz %.6f :limit-xy %.6f :twist %.6f}" % (m, m, m)
        jname = (h0["name"].replace("_", " ") + ".j") if sloppy else h0["name"]
        e = bpy.data.objects.new(jname, None)
        e.empty_display_type = "ARROWS"
        e.empty_display_size = 0.1
        bpy.context.scene.collection.objects.link(e)
        e.parent = root
        e.location = pos
        e.rotation_mode = "QUATERNION"
        e.rotation_quaternion = R
        e["joint"] = spec
        record["joints"].append({"name": jname, "mjcf-joints": [h["name"] for h in s["hinges"]],
                                 "segments": [names[parent], names[s["name"]]],
                                 "anchor": [r6(c) for c in anchor], "position": [r6(c) for c in pos],
                                 "spec": spec})
    bpy.context.view_layer.update()
    path = os.path.join(out, model + ("-sloppy" if sloppy else "-apart" if apart else "") + ".blend")
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=False)
    with open(path[:-6] + ".json", "w") as f:
        json.dump(record, f, indent=1)
    print("wrote", path, len(segs), "segments", len(record["joints"]), "joints")


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out, files = argv[0], argv[1:]
    os.makedirs(out, exist_ok=True)
    for f in files:
        model = os.path.splitext(os.path.basename(f))[0]
        for sloppy in (False, True):
            _, bodies = parse(f)
            build(model, bodies, out, sloppy, random.Random(sum(map(ord, model))))
        if model == "walker2d":   # clean, but with the legs 0.06 either side of the middle
            _, bodies = parse(f)
            build(model, bodies, out, False, random.Random(0), apart=True)


main()
