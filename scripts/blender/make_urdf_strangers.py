"""Turn URDF robots into cortex creatures (.blend), the way a careful robotics
person would by hand after reading doc/designing-creatures.md only.

    blender -b --factory-startup --python make_urdf_strangers.py -- OUTDIR a.urdf b.urdf ...

For each ROBOT.urdf it writes OUTDIR/ROBOT.blend (clean) and
OUTDIR/ROBOT-sloppy.blend, each with a .json beside it (segments, joints,
what was skipped and why).

Conventions (from the guide only):
- one segment (mesh object) per group of links welded by `fixed` joints,
  made of the links' <collision> geometry: box, cylinder (flat caps, 16
  sides), sphere (UV), capsule (pybullet's extension) as closed pieces;
  mesh files (.obj/.stl) imported with Blender's importers with no axis
  change (URDF meshes are in the link frame), scaled as the URDF says,
  merged by distance (STL repeats vertices) and decimated to at most
  MAXTRI triangles a file (the guide: keep segments low-poly; cortex hulls
  such pieces anyway).  Materials are not kept.
- a group with no collision geometry is no segment (recorded).
- mass: sum of the group's <inertial><mass>; 0/none -> 10% of the median
  of the other segments' masses (0.1 kg if none), recorded (mass 0 would
  make a segment that never moves).
- revolute/continuous -> {:type :hinge}; spherical (pybullet extension) ->
  {:type :point}; prismatic/floating/planar: skipped (no joint; the child
  keeps its own segment, unattached), recorded.
- a movable joint whose parent group has no geometry: walk up through
  geometry-less groups (via movable joints) to the first segment; the
  creature gets ONE joint (the child-most URDF joint, at its origin, its
  axis and limits); the others on the way are recorded as dropped.  If no
  segment is found (the chain reaches the world / a prismatic joint), the
  joint is skipped.
- empty at the URDF joint origin (world); the empty is turned so that the
  parent segment (bbox centre) lies towards -X-Y-Z of it, the child towards
  +X+Y+Z, so the guide's angle (second relative to first) is the URDF's
  angle (child relative to parent); the URDF axis (joint frame) is taken to
  world, then into the empty's frame.
- limits: URDF lower/upper, clamped into [-pi, pi] (recorded); continuous,
  missing limits or lower >= upper: [(- Math/PI) Math/PI].

Sloppy twin: about 60% of the segments get an unapplied rotation and a
non-uniform scale (mesh counter-transformed: same world shape), names with
spaces and dots, every joint empty moved by 4% of the median segment size in
a random direction (seeded) and turned arbitrarily (keeping the parent
towards -X-Y-Z).
"""

import json
import math
import os
import random
import re
import statistics
import sys
import xml.etree.ElementTree as ET

import bmesh
import bpy
from mathutils import Euler, Matrix, Quaternion, Vector

MAXTRI = 2000
N = 16
RINGS = 4


def num(s, default=0.0):
    """Lenient float: URDFs in the wild have '-1.57.' and '+3'."""
    if s is None:
        return default
    m = re.match(r"\s*([+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?)", s)
    return float(m.group(1)) if m else default


def vec(s, default=(0.0, 0.0, 0.0)):
    if s is None:
        return list(default)
    # xacro leftovers such as "$(optenv HUSKY_IMU_XYZ 0.19 0 0.149)": take the default
    s = re.sub(r"\$\(optenv\s+\S+\s*([^)]*)\)", r"\1", s)
    return [num(x) for x in s.split()]


def origin_matrix(el):
    o = el.find("origin") if el is not None else None
    if o is None:
        return Matrix.Identity(4)
    xyz = vec(o.get("xyz"))
    rpy = vec(o.get("rpy"))
    return Matrix.Translation(Vector(xyz)) @ Euler(rpy, "XYZ").to_matrix().to_4x4()


# ------------------------------------------------------------------ URDF

def parse(path):
    raw = open(path, "rb").read().replace(b"\0", b"").strip()
    root = ET.fromstring(raw)
    links = {}
    order = []
    for l in root.findall("link"):
        name = l.get("name")
        inert = l.find("inertial")
        mass = None
        if inert is not None and inert.find("mass") is not None:
            mass = num(inert.find("mass").get("value"), None)
        cols = []
        for c in l.findall("collision"):
            g = c.find("geometry")
            if g is None or len(g) == 0:
                continue
            cols.append({"origin": origin_matrix(c), "geom": g[0]})
        links[name] = {"name": name, "mass": mass, "collisions": cols}
        order.append(name)
    joints = []
    for j in root.findall("joint"):
        lim = j.find("limit")
        ax = j.find("axis")
        joints.append({
            "name": j.get("name"), "type": j.get("type"),
            "parent": j.find("parent").get("link"), "child": j.find("child").get("link"),
            "origin": origin_matrix(j),
            "axis": vec(ax.get("xyz")) if ax is not None else [1.0, 0.0, 0.0],
            "lower": None if lim is None or lim.get("lower") is None else num(lim.get("lower")),
            "upper": None if lim is None or lim.get("upper") is None else num(lim.get("upper")),
            "has_limit": lim is not None})
    # world frames
    children = {}
    parent_joint = {}
    for j in joints:
        children.setdefault(j["parent"], []).append(j)
        parent_joint[j["child"]] = j
    roots = [n for n in order if n not in parent_joint]
    world = {}

    def walk(n, m):
        world[n] = m
        for j in children.get(n, []):
            walk(j["child"], m @ j["origin"])

    for r in roots:
        walk(r, Matrix.Identity(4))
    for j in joints:
        j["world"] = world[j["parent"]] @ j["origin"]     # the joint frame = child link frame
    return root.get("name", "robot"), links, order, joints, world, parent_joint


# ------------------------------------------------------------------ pieces

def box_piece(m, size):
    hx, hy, hz = [s / 2 for s in size]
    verts = [m @ Vector((sx * hx, sy * hy, sz * hz)) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return verts, faces


def tube_piece(m, r, half, flat):
    verts, faces = [], []
    if flat:
        rings = [(-half, r), (half, r)]
    else:
        rings = []
        for k in range(RINGS - 1, 0, -1):
            phi = math.pi / 2 * k / RINGS
            rings.append((-half - r * math.sin(phi), r * math.cos(phi)))
        rings += [(-half, r), (half, r)]
        for k in range(1, RINGS):
            phi = math.pi / 2 * k / RINGS
            rings.append((half + r * math.sin(phi), r * math.cos(phi)))
    for z, rr in rings:
        for i in range(N):
            a = 2 * math.pi * i / N
            verts.append(m @ Vector((rr * math.cos(a), rr * math.sin(a), z)))
    nr = len(rings)
    for k in range(nr - 1):
        for i in range(N):
            a0, a1 = k * N + i, k * N + (i + 1) % N
            faces.append((a0, a1, a1 + N, a0 + N))
    if flat:
        faces.append(tuple(range(N - 1, -1, -1)))
        faces.append(tuple((nr - 1) * N + i for i in range(N)))
    else:
        bottom = len(verts)
        verts.append(m @ Vector((0, 0, -half - r)))
        top = len(verts)
        verts.append(m @ Vector((0, 0, half + r)))
        for i in range(N):
            faces.append((bottom, (i + 1) % N, i))
            faces.append((top, (nr - 1) * N + i, (nr - 1) * N + (i + 1) % N))
    return verts, faces


def sphere_piece(m, r):
    verts, faces = [], []
    lat = N // 2
    for k in range(1, lat):
        th = math.pi * k / lat
        for i in range(N):
            a = 2 * math.pi * i / N
            verts.append(m @ Vector((r * math.sin(th) * math.cos(a), r * math.sin(th) * math.sin(a), r * math.cos(th))))
    top = len(verts)
    verts.append(m @ Vector((0, 0, r)))
    bot = len(verts)
    verts.append(m @ Vector((0, 0, -r)))
    for k in range(lat - 2):
        for i in range(N):
            a0, a1 = k * N + i, k * N + (i + 1) % N
            faces.append((a0, a0 + N, a1 + N, a1))
    last = (lat - 2) * N
    for i in range(N):
        faces.append((top, i, (i + 1) % N))
        faces.append((bot, last + (i + 1) % N, last + i))
    return verts, faces


MESH_CACHE = {}
MESH_NOTES = []


def resolve(filename, urdf_path):
    base = os.path.dirname(os.path.abspath(urdf_path))
    f = filename
    if f.startswith("package://"):
        f = f[len("package://"):]
        # try beside the urdf, then dropping leading package names, then up the tree
        parts = f.split("/")
        cands = []
        for d in (base, os.path.dirname(base), os.path.dirname(os.path.dirname(base))):
            for k in range(len(parts)):
                cands.append(os.path.join(d, *parts[k:]))
        for c in cands:
            if os.path.exists(c):
                return c
        return None
    if f.startswith("file://"):
        f = f[len("file://"):]
    c = f if os.path.isabs(f) else os.path.join(base, f)
    return c if os.path.exists(c) else None


def import_mesh(path):
    """Local vertices and faces of a mesh file, merged by distance and
    decimated to MAXTRI triangles at most."""
    if path in MESH_CACHE:
        return MESH_CACHE[path]
    before = set(bpy.data.objects)
    ext = os.path.splitext(path)[1].lower()
    if ext == ".stl":
        bpy.ops.import_mesh.stl(filepath=path, axis_forward="Y", axis_up="Z", global_scale=1.0)
    elif ext == ".obj":
        bpy.ops.wm.obj_import(filepath=path, forward_axis="Y", up_axis="Z", global_scale=1.0)
    else:
        MESH_CACHE[path] = None
        return None
    new = [o for o in bpy.data.objects if o not in before and o.type == "MESH"]
    bm = bmesh.new()
    for o in new:
        me = o.data.copy()
        me.transform(o.matrix_world)
        bm.from_mesh(me)
        bpy.data.meshes.remove(me)
    for o in list(bpy.data.objects):
        if o not in before:
            bpy.data.objects.remove(o, do_unlink=True)
    bmesh.ops.remove_doubles(bm, verts=bm.verts, dist=1e-6)
    bmesh.ops.triangulate(bm, faces=bm.faces)
    ntri = len(bm.faces)
    me = bpy.data.meshes.new("tmp")
    bm.to_mesh(me)
    bm.free()
    if ntri > MAXTRI:
        ob = bpy.data.objects.new("tmp", me)
        bpy.context.scene.collection.objects.link(ob)
        mod = ob.modifiers.new("dec", "DECIMATE")
        mod.ratio = MAXTRI / ntri
        dg = bpy.context.evaluated_depsgraph_get()
        ev = ob.evaluated_get(dg)
        me2 = bpy.data.meshes.new_from_object(ev)
        bpy.data.objects.remove(ob, do_unlink=True)
        bpy.data.meshes.remove(me)
        me = me2
    verts = [v.co.copy() for v in me.vertices]
    faces = [tuple(p.vertices) for p in me.polygons]
    MESH_NOTES.append({"file": path, "triangles": ntri, "kept-faces": len(faces), "vertices": len(verts)})
    bpy.data.meshes.remove(me)
    MESH_CACHE[path] = (verts, faces, ntri)
    return MESH_CACHE[path]


def collision_pieces(link, link_world, urdf_path, notes):
    pieces = []
    for c in link["collisions"]:
        g = c["geom"]
        m = link_world @ c["origin"]
        t = g.tag
        if t == "box":
            pieces.append(box_piece(m, vec(g.get("size"), (1, 1, 1))))
        elif t == "cylinder":
            pieces.append(tube_piece(m, num(g.get("radius")), num(g.get("length")) / 2, True))
        elif t == "capsule":
            pieces.append(tube_piece(m, num(g.get("radius")), num(g.get("length")) / 2, False))
        elif t == "sphere":
            pieces.append(sphere_piece(m, num(g.get("radius"))))
        elif t == "mesh":
            p = resolve(g.get("filename"), urdf_path)
            if p is None:
                notes.append("link %s: mesh %s not found, piece left out" % (link["name"], g.get("filename")))
                continue
            got = import_mesh(p)
            if got is None:
                notes.append("link %s: mesh %s of a kind not importable, piece left out" % (link["name"], p))
                continue
            verts, faces, ntri = got
            s = vec(g.get("scale"), (1, 1, 1))
            if len(s) == 1:
                s = s * 3
            ms = m @ Matrix.Diagonal(Vector(s).to_4d())
            pieces.append(([ms @ v for v in verts], list(faces)))
            if ntri > MAXTRI:
                notes.append("link %s: mesh %s decimated from %d to about %d triangles"
                             % (link["name"], os.path.basename(p), ntri, MAXTRI))
        else:
            notes.append("link %s: collision geometry <%s> not handled" % (link["name"], t))
    return pieces


# ------------------------------------------------------------------ creature

MOVABLE = {"revolute": "hinge", "continuous": "hinge", "spherical": "point"}


def plan(links, order, joints, world, parent_joint, urdf_path):
    notes = []
    # groups welded by fixed joints
    grp = {n: n for n in order}

    def find(n):
        while grp[n] != n:
            grp[n] = grp[grp[n]]
            n = grp[n]
        return n

    for j in joints:
        if j["type"] == "fixed":
            a, b = find(j["parent"]), find(j["child"])
            if a != b:
                grp[b] = a
    groups = {}
    for n in order:
        groups.setdefault(find(n), []).append(n)
    segs = {}
    for g, members in groups.items():
        pieces = []
        for n in members:
            pieces += collision_pieces(links[n], world[n], urdf_path, notes)
        masses = [links[n]["mass"] for n in members]
        mass = sum(m for m in masses if m)
        segs[g] = {"key": g, "links": members, "pieces": pieces, "mass": mass, "mass-note": None}
    with_geom = {g for g, s in segs.items() if s["pieces"]}
    skipped_links = []
    for g, s in segs.items():
        if g not in with_geom:
            skipped_links.append({"links": s["links"], "mass": s["mass"],
                                  "why": "no collision geometry"})
    # joints
    out_joints, skipped = [], []
    for j in joints:
        if j["type"] == "fixed":
            continue
        if j["type"] not in MOVABLE:
            skipped.append({"urdf-joint": j["name"], "type": j["type"],
                            "why": "%s joint: no such joint in cortex; child left unattached" % j["type"]})
            continue
        cg = find(j["child"])
        if cg not in with_geom:
            # handled (if at all) by the joints below it
            skipped.append({"urdf-joint": j["name"], "type": j["type"],
                            "why": "child %s has no geometry (no segment)" % j["child"]})
            continue
        pg = find(j["parent"])
        dropped = []
        ok = True
        while pg not in with_geom:
            # walk up from the geometry-less group
            up = None
            for n in segs[pg]["links"]:
                pj = parent_joint.get(n)
                if pj is not None and find(pj["parent"]) != pg:
                    up = pj
            if up is None or up["type"] not in MOVABLE:
                ok = False
                why = ("parent %s has no geometry and sits on %s" %
                       (j["parent"], "the root" if up is None else "a %s joint %s" % (up["type"], up["name"])))
                break
            dropped.append(up["name"])
            pg = find(up["parent"])
        if not ok:
            skipped.append({"urdf-joint": j["name"], "type": j["type"], "why": why})
            continue
        out_joints.append({"j": j, "parent": pg, "child": cg, "dropped": dropped})
    return segs, with_geom, out_joints, skipped, skipped_links, notes


def clear():
    bpy.ops.wm.read_factory_settings(use_empty=True)


def r6(x):
    return round(float(x), 6) + 0.0


def sloppy_name(n, i):
    n = n.replace("_", " ")
    return n + (".L" if i % 3 == 0 else ".001" if i % 3 == 1 else " part")


def fmt(x):
    return "%.6f" % x


def build(model, urdf_path, out, sloppy, rng):
    clear()
    MESH_CACHE.clear()
    name, links, order, joints, world, parent_joint = parse(urdf_path)
    segs, with_geom, jplan, skipped, skipped_links, notes = plan(links, order, joints, world, parent_joint, urdf_path)
    keys = [k for k in segs if k in with_geom]
    # masses
    nz = [segs[k]["mass"] for k in keys if segs[k]["mass"] and segs[k]["mass"] > 0]
    fallback = 0.1 * statistics.median(nz) if nz else 0.1
    for k in keys:
        s = segs[k]
        if not s["mass"] or s["mass"] <= 0:
            s["mass"] = fallback
            s["mass-note"] = "URDF mass 0 or none: given %.4g kg (10%% of the median segment mass)" % fallback
    record = {"model": model, "urdf": urdf_path, "sloppy": sloppy, "segments": [], "joints": [],
              "skipped-joints": skipped, "skipped-links": skipped_links, "notes": notes}
    objs = {}
    sizes = []
    for i, k in enumerate(keys):
        s = segs[k]
        verts, faces = [], []
        for v, f in s["pieces"]:
            o = len(verts)
            verts += v
            faces += [tuple(x + o for x in face) for face in f]
        lo = Vector([min(v[c] for v in verts) for c in range(3)])
        hi = Vector([max(v[c] for v in verts) for c in range(3)])
        centre = (lo + hi) / 2
        sizes.append(max(hi - lo))
        oname = sloppy_name(k, i) if sloppy else k
        if sloppy and rng.random() < 0.6:
            rot = Quaternion(Vector((rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))).normalized(),
                             rng.uniform(0.3, 2.5))
            scale = Vector((rng.uniform(0.6, 1.6), rng.uniform(0.6, 1.6), rng.uniform(0.6, 1.6)))
        else:
            rot, scale = Quaternion(), Vector((1, 1, 1))
        mw = Matrix.Translation(centre) @ rot.to_matrix().to_4x4() @ Matrix.Diagonal(scale.to_4d())
        inv = mw.inverted()
        me = bpy.data.meshes.new(oname)
        me.from_pydata([tuple(inv @ v) for v in verts], [], faces)
        me.validate()
        me.update()
        ob = bpy.data.objects.new(oname, me)
        bpy.context.scene.collection.objects.link(ob)
        ob.location = centre
        ob.rotation_mode = "QUATERNION"
        ob.rotation_quaternion = rot
        ob.scale = scale
        ob["mass"] = float(s["mass"])
        objs[k] = (ob, centre, hi - lo)
        record["segments"].append({"name": ob.name, "urdf-links": s["links"], "mass": r6(s["mass"]),
                                   "mass-note": s["mass-note"],
                                   "bounds": [[r6(c) for c in lo], [r6(c) for c in hi]],
                                   "size": [r6(c) for c in hi - lo],
                                   "rotation": [r6(c) for c in rot], "scale": [r6(c) for c in scale]})
    bpy.context.view_layer.update()
    median_size = statistics.median(sizes) if sizes else 1.0
    record["median-segment-size"] = r6(median_size)
    root = bpy.data.objects.new("joints", None)
    bpy.context.scene.collection.objects.link(root)
    one = Vector((1, 1, 1)).normalized()
    flip = Quaternion(Vector((1, -1, 0)).normalized(), math.pi)
    for p in jplan:
        j = p["j"]
        pc, cc = objs[p["parent"]][1], objs[p["child"]][1]
        d = cc - pc
        anchor = j["world"].to_translation()
        axis_w = (j["world"].to_3x3() @ Vector(j["axis"])).normalized() if Vector(j["axis"]).length > 0 else Vector((1, 0, 0))
        if sloppy:
            R = Quaternion(Vector((rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))).normalized(),
                           rng.uniform(0, math.pi))
            if (R @ one).dot(d) < 0:
                R = R @ flip
            off = Vector((rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))).normalized() * 0.04 * median_size
            pos = anchor + off
        else:
            R = one.rotation_difference(d.normalized()) if d.length > 1e-9 else Quaternion()
            pos = anchor
        ax = R.inverted() @ axis_w
        jnotes = []
        kind = MOVABLE[j["type"]]
        if kind == "point":
            spec = "{:type :point}"
        else:
            lo, hi = j["lower"], j["upper"]
            full = False
            if j["type"] == "continuous":
                full = True
            elif lo is None or hi is None:
                full = True
                jnotes.append("revolute without lower/upper: written as a full turn")
            elif lo >= hi:
                full = True
                jnotes.append("revolute with lower %g >= upper %g: written as a full turn" % (lo, hi))
            else:
                if lo < -math.pi or hi > math.pi:
                    jnotes.append("limits [%g %g] clamped into [-pi, pi]" % (lo, hi))
                    lo, hi = max(lo, -math.pi), min(hi, math.pi)
            if full or (lo <= -math.pi and hi >= math.pi):
                lim = "[(- Math/PI) Math/PI]"
            else:
                lim = "[%s %s]" % (fmt(lo), fmt(hi))
            spec = "{:type :hinge :limit %s :axis [%s %s %s]}" % (lim, fmt(ax.x), fmt(ax.y), fmt(ax.z))
        jname = (j["name"].replace("_", " ") + ".j") if sloppy else j["name"]
        e = bpy.data.objects.new(jname, None)
        e.empty_display_type = "ARROWS"
        e.empty_display_size = 0.05
        bpy.context.scene.collection.objects.link(e)
        e.parent = root
        e.location = pos
        e.rotation_mode = "QUATERNION"
        e.rotation_quaternion = R
        e["joint"] = spec
        if p["dropped"]:
            jnotes.append("URDF joints %s on the way through geometry-less links dropped" % p["dropped"])
        record["joints"].append({"name": e.name, "urdf-joints": [j["name"]], "urdf-type": j["type"],
                                 "dropped-urdf-joints": p["dropped"],
                                 "segments": [objs[p["parent"]][0].name, objs[p["child"]][0].name],
                                 "anchor": [r6(c) for c in anchor], "position": [r6(c) for c in pos],
                                 "axis-world": [r6(c) for c in axis_w], "spec": spec, "notes": jnotes})
    bpy.context.view_layer.update()
    path = os.path.join(out, model + ("-sloppy" if sloppy else "") + ".blend")
    bpy.ops.wm.save_as_mainfile(filepath=path, compress=False)
    record["meshes"] = list(MESH_NOTES)
    MESH_NOTES.clear()
    with open(path[:-6] + ".json", "w") as f:
        json.dump(record, f, indent=1)
    print("wrote", path, len(keys), "segments", len(record["joints"]), "joints",
          len(skipped), "skipped joints", len(skipped_links), "skipped groups")


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    out, files = argv[0], argv[1:]
    os.makedirs(out, exist_ok=True)
    for f in files:
        model = os.path.splitext(os.path.basename(f))[0]
        if model == "model":   # kuka_iiwa/model.urdf
            model = os.path.basename(os.path.dirname(os.path.abspath(f)))
        for sloppy in (False, True):
            build(model, f, out, sloppy, random.Random(sum(map(ord, model))))


main()
