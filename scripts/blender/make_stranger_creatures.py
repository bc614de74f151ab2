"""Build creatures the way other people make them: test/fixtures/strangers/.

    /work/venvs/bpy45/bin/python scripts/blender/make_stranger_creatures.py [OUTDIR] [NAME ...]
    /work/venvs/bpy52/bin/python scripts/blender/make_stranger_creatures.py [OUTDIR] [NAME ...]
    blender -b --factory-startup --python-exit-code 1 \
        --python scripts/blender/make_stranger_creatures.py -- [OUTDIR] [NAME ...]

OUTDIR defaults to test/fixtures/strangers in the repo.  NAMEs choose the
files (without .blend); by default Blender 4.x builds every file below but
`hand-b52`, and Blender 5.x builds only `hand-b52`.  Every run writes the
same expected.json (it is made from this script's numbers only), then
re-opens each file it saved, checks objects, parents, properties and
positions against it, measures gaps and joint distances with Blender's own
geometry (BVHTree) and prints a table (exit 1 when a check fails).

The files (saved uncompressed, no dump beside them):

- hand.blend (Blender 4.5) and hand-b52.blend (the same code in Blender 5.2):
  a right hand lying palm down, fingers along +Y, thumb along -X, made with
  Blender's primitive operators the way a hobbyist would: `palm` a cube
  primitive scaled in object mode (scale unapplied, 0.9 x 1.0 x 0.25), the
  fingers `index`, `middle`, `ring`, `pinky`, three boxes each (`index-1`
  .. `-3`; index a 1 m cube scaled in object mode, middle by setting its
  dimensions, both left unapplied; ring and pinky with their scale applied),
  the thumb two 8-sided cylinder primitives laid along X (`thumb-1`,
  `thumb-2`, radius 0.1; thumb-1's rotation left unapplied, thumb-2's applied).  Gaps between finger segments (and between the
  palm and a finger) from 0.02 to 0.06, each joint empty in its gap's
  middle but up to 0.01 off sideways.  The thumb starts 0.1 from the palm,
  `thumb-palm` in the middle of that gap.  Finger joints (`index-palm`,
  `index-1-2`, `index-2-3`, ...) are hinges about -X curling toward the
  palm side (-Z); `thumb-palm` a cone and `thumb-1-2` a hinge, both empties
  turned 180 degrees about Z (local X along the thumb).
- humanoid.blend: MuJoCo's humanoid (make_humanoid.py's tables) NOT clipped:
  every capsule and sphere a closed 12-sided mesh piece at MuJoCo's exact
  size (vertices on the true surface), the pieces of one segment in one mesh
  object, overlapping at the joints as MuJoCo's geoms do; joint empties at
  MuJoCo's anchors, oriented and described by make_humanoid.joint_design();
  MuJoCo's masses (feet merged into the shins), origins at the centres of
  mass, feet's lowest points at z = 0.
- worm-eye.blend: a three-segment worm (`tail`, `middle`, `head`, 12-sided
  cylinders along X with bevelled ends, the head toward +X in its own
  colour), hinges `tail-middle` and `middle-head` (axis Y) in gaps of 0.045
  and 0.035, and `eye`, a camera 0.1 in front of the head's front face
  looking along +X (up +Z) under an empty `eyes`, `eye` = {:resolution [64 48]}.
- NAME-0.01.blend and NAME-100.blend for hand, humanoid and worm-eye: the
  same creature built at 0.01x and 100x (every location, size, gap, display
  size and the camera's clip range scaled; masses unchanged).
- expected.json: per file its scale, segments (name, mass, origin), joints
  (name, type, spec, world position, the designer's gap, the two segments
  the joint is meant to join in cortex's order: smaller
  (1,1,1) . (segment origin in the empty's frame) first) and eyes (name,
  segment, distance to that segment's surface).  The files store float32.
"""

import json
import math
import os
import sys

import bpy
from mathutils import Matrix, Vector
from mathutils.bvhtree import BVHTree

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402
import make_humanoid as mh  # noqa: E402  (module level only computes tables)
from make_fixtures import empty_file, material, mesh_from, update  # noqa: E402

SCALES = {"": 1.0, "-0.01": 0.01, "-100": 100.0}


def r6(x, s=1.0):
    """x rounded to 1e-6 of the scale s (1e-8 in the 0.01 files, 1e-4 in the 100 ones)."""
    return round(float(x), 6 - int(round(math.log10(s)))) + 0.0


def v6(v, s=1.0):
    return [r6(c, s) for c in v]


# ------------------------------------------------------------ bpy helpers


def deselect_all():
    for o in bpy.context.view_layer.objects:
        o.select_set(False)


def named(obj, name):
    obj.name = name
    if obj.data is not None:
        obj.data.name = name
    return obj


def apply_transform(obj, rotation=False, scale=False):
    deselect_all()
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.transform_apply(location=False, rotation=rotation, scale=scale)


def add_empty(name, kind, size, location=(0, 0, 0), rotation=(0, 0, 0), parent=None):
    bpy.ops.object.empty_add(type=kind, radius=size, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    if parent is not None:
        obj.parent = parent
    return obj

def add_joints(joints, root_size, size):
    """The `joints` empty (display size root_size) and under it one
    empty per joint, displayed at `size`, with its `joint` property."""
    root = add_empty("joints", "PLAIN_AXES", root_size)
    for j in joints:
        e = add_empty(j["name"], "ARROWS", size, j["position"], j["rotation"], root)
        e["joint"] = j["spec"]



def frame_of(euler):
    return mh.euler_matrix(list(euler))


def cortex_order(a, b, position, euler, origins):
    """The two segments in the order cortex puts them: smaller
    (1,1,1) . (origin in the joint empty's frame) first."""
    rt = mh.transpose(frame_of(euler))

    def key(seg):
        return sum(mh.apply(rt, mh.sub(origins[seg], position)))
    return sorted([a, b], key=key)


# ------------------------------------------------------------ hand

HAND_Z = 0.4
PALM = (0.9, 1.0, 0.25)            # x, y, z sizes; centre (0, 0, HAND_Z)
# name, x of the finger axis, width (x), thickness (z), lengths,
# gaps (palm-1, 1-2, 2-3), sideways slop of the joint empties (dx, dz),
# how the boxes are made
FINGERS = [
    ("index", -0.3375, 0.19, 0.20, (0.35, 0.28, 0.22), (0.030, 0.045, 0.020),
     ((0.004, 0.0), (-0.006, 0.003), (0.0, -0.008)), "scaled"),
    ("middle", -0.1125, 0.20, 0.20, (0.38, 0.30, 0.23), (0.050, 0.025, 0.035),
     ((-0.003, -0.004), (0.007, 0.0), (0.002, 0.006)), "dimensions"),
    ("ring", 0.1125, 0.19, 0.19, (0.36, 0.28, 0.22), (0.040, 0.060, 0.030),
     ((0.0, 0.009), (-0.005, -0.005), (0.008, 0.0)), "applied"),
    ("pinky", 0.3375, 0.18, 0.18, (0.30, 0.23, 0.19), (0.020, 0.035, 0.055),
     ((0.006, 0.002), (0.0, 0.0), (-0.004, 0.007)), "applied"),
]
FINGER_MASSES = (0.1, 0.07, 0.05)
FINGER_LIMITS = ("[0 1.5]", "[0 1.7]", "[0 1.2]")
THUMB_Y = -0.25
THUMB_R = 0.1
THUMB_LENGTHS = (0.32, 0.26)
THUMB_GAPS = (0.1, 0.04)           # palm to thumb-1, thumb-1 to thumb-2
THUMB_SLOP = ((0.0, 0.0), (0.0, 0.005))   # (dy, dz) off the gap's middle
THUMB_MASSES = (0.15, 0.1)
PALM_MASS = 1.0
THUMB_TURN = (0.0, 0.0, math.pi)
THUMB_SPECS = ("{:type :cone :limit-xz 0.7 :limit-xy 0.5 :twist 0.3}",
               "{:type :hinge :limit [0 1.3] :axis [0 1 0]}")


def hand_design(s):
    """Segments (name, mass, centre, size, how) and joints, at scale s."""
    segs, joints = [], []
    segs.append({"name": "palm", "mass": PALM_MASS, "origin": [0.0, 0.0, HAND_Z * s],
                 "size": [c * s for c in PALM], "how": "palm"})
    for fname, x, w, t, lengths, gaps, slop, how in FINGERS:
        y = PALM[1] / 2
        prev = "palm"
        for k in range(3):
            n = k + 1
            seg = "%s-%d" % (fname, n)
            jname = "%s-palm" % fname if n == 1 else "%s-%d-%d" % (fname, k, n)
            dx, dz = slop[k]
            joints.append({"name": jname, "type": "hinge",
                           "spec": "{:type :hinge :limit %s :axis [-1 0 0]}" % FINGER_LIMITS[k],
                           "position": [(x + dx) * s, (y + gaps[k] / 2) * s, (HAND_Z + dz) * s],
                           "rotation": [0.0, 0.0, 0.0], "joins": [prev, seg],
                           "gap": gaps[k] * s})
            y0 = y + gaps[k]
            segs.append({"name": seg, "mass": FINGER_MASSES[k],
                         "origin": [x * s, (y0 + lengths[k] / 2) * s, HAND_Z * s],
                         "size": [w * s, lengths[k] * s, t * s], "how": how})
            y = y0 + lengths[k]
            prev = seg
    x = -PALM[0] / 2
    prev = "palm"
    for k in range(2):
        n = k + 1
        seg = "thumb-%d" % n
        jname = "thumb-palm" if n == 1 else "thumb-1-2"
        dy, dz = THUMB_SLOP[k]
        joints.append({"name": jname, "type": "cone" if n == 1 else "hinge",
                       "spec": THUMB_SPECS[k],
                       "position": [(x - THUMB_GAPS[k] / 2) * s, (THUMB_Y + dy) * s,
                                    (HAND_Z + dz) * s],
                       "rotation": list(THUMB_TURN), "joins": [prev, seg],
                       "gap": THUMB_GAPS[k] * s})
        x0 = x - THUMB_GAPS[k]
        segs.append({"name": seg, "mass": THUMB_MASSES[k],
                     "origin": [(x0 - THUMB_LENGTHS[k] / 2) * s, THUMB_Y * s, HAND_Z * s],
                     "size": [THUMB_LENGTHS[k] * s, 2 * THUMB_R * s, 2 * THUMB_R * s],
                     "how": "thumb-%d" % n})
        x = x0 - THUMB_LENGTHS[k]
        prev = seg
    return segs, joints, []


def build_hand(s):
    segs, joints, _ = hand_design(s)
    empty_file()
    skin = material("skin", (0.86, 0.67, 0.56, 1.0))
    nail = material("nail", (0.93, 0.72, 0.70, 1.0))
    for g in segs:
        loc, size, how = g["origin"], g["size"], g["how"]
        if how == "palm":            # a 2 m cube, scaled in object mode
            bpy.ops.mesh.primitive_cube_add(size=2.0 * s, location=loc)
            obj = bpy.context.active_object
            obj.scale = (PALM[0] / 2, PALM[1] / 2, PALM[2] / 2)
        elif how == "scaled":        # a 1 m cube, scaled (S) in object mode
            bpy.ops.mesh.primitive_cube_add(size=1.0 * s, location=loc)
            obj = bpy.context.active_object
            obj.scale = tuple(c / s for c in size)
        elif how in ("dimensions", "applied"):
            bpy.ops.mesh.primitive_cube_add(size=1.0 * s, location=loc)
            obj = bpy.context.active_object
            update()
            obj.dimensions = size
            update()
            if how == "applied":
                apply_transform(obj, scale=True)
        else:                        # thumb: an 8-sided cylinder laid along X
            bpy.ops.mesh.primitive_cylinder_add(vertices=8, radius=THUMB_R * s,
                                                depth=size[0], location=loc,
                                                rotation=(0.0, math.pi / 2, 0.0))
            obj = bpy.context.active_object
            if how == "thumb-2":
                apply_transform(obj, rotation=True)
        named(obj, g["name"])
        obj["mass"] = float(g["mass"])
        tip = g["name"].endswith("-3") or g["name"] == "thumb-2"
        obj.data.materials.append(nail if tip else skin)
    add_joints(joints, 0.3 * s, 0.08 * s)
    update()


# ------------------------------------------------------------ humanoid

HUMANOID_SIDES = 12


def ring_point(c, r, u, e1, e2, lat, ang):
    la, a = math.radians(lat), ang
    d = mh.add(mh.scale(math.cos(a), e1), mh.scale(math.sin(a), e2))
    return mh.add(c, mh.scale(r, mh.add(mh.scale(math.cos(la), d), mh.scale(math.sin(la), u))))


def rings_mesh(pole_a, rings, pole_b):
    """Closed mesh: pole, rings of HUMANOID_SIDES vertices (counter-clockwise
    about the axis pole_a -> pole_b), pole; outward faces."""
    n = HUMANOID_SIDES
    vs = [pole_a]
    for ring in rings:
        vs += ring
    vs.append(pole_b)
    fs = []
    for i in range(n):
        fs.append((0, 1 + (i + 1) % n, 1 + i))
    for k in range(len(rings) - 1):
        b0, b1 = 1 + k * n, 1 + (k + 1) * n
        for i in range(n):
            j = (i + 1) % n
            fs.append((b0 + i, b0 + j, b1 + j, b1 + i))
    last, top = 1 + (len(rings) - 1) * n, len(vs) - 1
    for i in range(n):
        fs.append((top, last + i, last + (i + 1) % n))
    return vs, fs


def angles():
    return [2 * math.pi * (i + 0.5) / HUMANOID_SIDES for i in range(HUMANOID_SIDES)]


def capsule_piece(a, b, r):
    u = mh.unit(mh.sub(b, a))
    e1 = mh.perpendicular(u)
    e2 = mh.cross(u, e1)
    rings = [[ring_point(c, r, u, e1, e2, lat, t) for t in angles()]
             for c, lat in ((a, -60), (a, -30), (a, 0), (b, 0), (b, 30), (b, 60))]
    return rings_mesh(mh.sub(a, mh.scale(r, u)), rings, mh.add(b, mh.scale(r, u)))


def sphere_piece(c, r):
    u, e1, e2 = [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]
    rings = [[ring_point(c, r, u, e1, e2, lat, t) for t in angles()]
             for lat in (-60, -30, 0, 30, 60)]
    return rings_mesh(mh.sub(c, [0, 0, r]), rings, mh.add(c, [0, 0, r]))


def segment_distance(p1, q1, p2, q2):
    """Smallest distance between the line segments p1q1 and p2q2 (Ericson, 5.1.9)."""
    d1, d2, r = mh.sub(q1, p1), mh.sub(q2, p2), mh.sub(p1, p2)
    a, e, f = mh.dot(d1, d1), mh.dot(d2, d2), mh.dot(d2, r)
    eps = 1e-18
    if a <= eps and e <= eps:
        return mh.norm(r)
    if a <= eps:
        s_, t_ = 0.0, min(1.0, max(0.0, f / e))
    else:
        c = mh.dot(d1, r)
        if e <= eps:
            s_, t_ = min(1.0, max(0.0, -c / a)), 0.0
        else:
            b = mh.dot(d1, d2)
            den = a * e - b * b
            s_ = min(1.0, max(0.0, (b * f - c * e) / den)) if den > eps else 0.0
            t_ = (b * s_ + f) / e
            if t_ < 0.0:
                s_, t_ = min(1.0, max(0.0, -c / a)), 0.0
            elif t_ > 1.0:
                s_, t_ = min(1.0, max(0.0, (b - c) / a)), 1.0
    c1 = mh.add(p1, mh.scale(s_, d1))
    c2 = mh.add(p2, mh.scale(t_, d2))
    return mh.norm(mh.sub(c1, c2))


def piece_axis(p):
    if p["kind"] == "sphere":
        return p["centre"], p["centre"], p["radius"]
    return p["from"], p["to"], p["radius"]


def geom_gap(pieces_a, pieces_b):
    """MuJoCo's signed distance between two sets of geoms (negative: they overlap)."""
    best = float("inf")
    for pa in pieces_a:
        a0, a1, ra = piece_axis(pa)
        for pb in pieces_b:
            b0, b1, rb = piece_axis(pb)
            best = min(best, segment_distance(a0, a1, b0, b1) - ra - rb)
    return best


def humanoid_design(s):
    mh.check_masses()
    joints_mh = mh.joint_design()
    mass = mh.masses(False)
    segs = []
    for name, bodies in mh.SEGMENTS.items():
        pieces = []
        for body in bodies:
            for g in mh.GEOMS[body]:
                if g[1] == "sphere":
                    c, r = mh.blender(mh.to_world(body, g[2])), g[3]
                    pieces.append({"geom": g[0], "kind": "sphere", "centre": mh.scale(s, c),
                                   "radius": r * s})
                else:
                    a = mh.blender(mh.to_world(body, g[2]))
                    b = mh.blender(mh.to_world(body, g[3]))
                    pieces.append({"geom": g[0], "kind": "capsule", "from": mh.scale(s, a),
                                   "to": mh.scale(s, b), "radius": g[4] * s})
        origin = mh.scale(s, mh.blender(mh.segment_mass_properties(name)[1]))
        segs.append({"name": name, "mass": mass[name], "origin": origin, "pieces": pieces})
    pieces = {g["name"]: g["pieces"] for g in segs}
    joints = []
    for j in joints_mh:
        a, b = j["segments"]
        joints.append({"name": j["name"], "type": j["type"], "spec": j["spec"],
                       "position": mh.scale(s, mh.blender(j["anchor"])),
                       "rotation": list(j["rotation"]), "joins": [a, b],
                       "gap": geom_gap(pieces[a], pieces[b])})
    return segs, joints, []


def build_humanoid(s):
    segs, joints, _ = humanoid_design(s)
    empty_file()
    skin = material("skin", mh.SKIN)
    for g in segs:
        vs, fs = [], []
        for p in g["pieces"]:
            pv, pf = (sphere_piece(p["centre"], p["radius"]) if p["kind"] == "sphere"
                      else capsule_piece(p["from"], p["to"], p["radius"]))
            off = len(vs)
            vs += pv
            fs += [tuple(off + i for i in f) for f in pf]
        origin = g["origin"]
        me = mesh_from(g["name"], [mh.sub(v, origin) for v in vs], fs)
        me.materials.append(skin)
        obj = bpy.data.objects.new(g["name"], me)
        bpy.context.scene.collection.objects.link(obj)
        obj.location = origin
        obj["mass"] = float(g["mass"])
    add_joints(joints, 0.2 * s, 0.05 * s)
    update()


# ------------------------------------------------------------ worm with an eye

WORM_Z = 0.3
WORM_R = 0.2
WORM_SIDES = 12
WORM_BEVEL = 0.05
WORM = [("tail", 0.8, 0.5), ("middle", 1.0, 0.8), ("head", 0.9, 0.6)]   # name, length, mass
WORM_GAPS = (0.045, 0.035)
WORM_START = -1.3                  # the tail's back end
WORM_SPECS = ("{:type :hinge :limit [-0.7 0.7] :axis [0 1 0]}",
              "{:type :hinge :limit [-0.6 0.6] :axis [0 1 0]}")
EYE_AHEAD = 0.1
EYE_ROT = (math.pi / 2, 0.0, -math.pi / 2)   # camera -Z along world +X, +Y up
EYE_CLIP = (0.05, 30.0)


def worm_design(s):
    segs, joints = [], []
    x = WORM_START
    for k, (name, length, mass) in enumerate(WORM):
        if k > 0:
            gap = WORM_GAPS[k - 1]
            joints.append({"name": "%s-%s" % (WORM[k - 1][0], name), "type": "hinge",
                           "spec": WORM_SPECS[k - 1],
                           "position": [(x + gap / 2) * s, 0.0, WORM_Z * s],
                           "rotation": [0.0, 0.0, 0.0], "joins": [WORM[k - 1][0], name],
                           "gap": gap * s})
            x += gap
        segs.append({"name": name, "mass": mass, "origin": [(x + length / 2) * s, 0.0, WORM_Z * s],
                     "length": length * s})
        x += length
    eyes = [{"name": "eye", "segment": "head", "distance": EYE_AHEAD * s,
             "position": [(x + EYE_AHEAD) * s, 0.0, WORM_Z * s], "rotation": list(EYE_ROT),
             "spec": "{:resolution [64 48]}", "clip": [EYE_CLIP[0] * s, EYE_CLIP[1] * s]}]
    return segs, joints, eyes


def bevel_ends(obj, offset):
    import bmesh
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    # the rim edges: both ends on a cap (|z| = half depth in the primitive's frame)
    zmax = max(abs(v.co.z) for v in bm.verts)
    rims = [e for e in bm.edges
            if all(abs(abs(v.co.z) - zmax) < 1e-6 * zmax for v in e.verts)
            and abs(e.verts[0].co.z - e.verts[1].co.z) < 1e-9 * zmax + 1e-12]
    bmesh.ops.bevel(bm, geom=rims, offset=offset, segments=2, profile=0.5,
                    affect="EDGES", clamp_overlap=True)
    bm.to_mesh(obj.data)
    bm.free()
    obj.data.update()


def build_worm_eye(s):
    segs, joints, eyes = worm_design(s)
    empty_file()
    body = material("worm-body", (0.55, 0.45, 0.35, 1.0))
    head = material("worm-head", (0.85, 0.25, 0.20, 1.0))
    for g in segs:
        # made at unit scale and then scaled: Blender's bevel has fixed
        # epsilons, and bevelled at 0.01 its volume came out 4e-4 smaller
        bpy.ops.mesh.primitive_cylinder_add(vertices=WORM_SIDES, radius=WORM_R,
                                            depth=g["length"] / s, location=g["origin"],
                                            rotation=(0.0, math.pi / 2, 0.0))
        obj = named(bpy.context.active_object, g["name"])
        bevel_ends(obj, WORM_BEVEL)
        obj.data.transform(Matrix.Scale(s, 4))
        obj["mass"] = float(g["mass"])
        obj.data.materials.append(head if g["name"] == "head" else body)
    add_joints(joints, 0.3 * s, 0.1 * s)
    eye_root = add_empty("eyes", "PLAIN_AXES", 0.2 * s)
    for e in eyes:
        bpy.ops.object.camera_add(location=e["position"], rotation=e["rotation"])
        cam = named(bpy.context.active_object, e["name"])
        cam.data.lens = 24.0
        cam.data.sensor_width = 36.0
        cam.data.clip_start, cam.data.clip_end = e["clip"]
        cam.data.display_size = 0.2 * s
        cam.parent = eye_root
        cam["eye"] = e["spec"]
    update()


# ------------------------------------------------------------ files

CREATURES = {"hand": (hand_design, build_hand), "humanoid": (humanoid_design, build_humanoid),
             "worm-eye": (worm_design, build_worm_eye)}


def all_files():
    """{file name: (creature, scale, blender)}"""
    out = {}
    for creature in ("hand", "humanoid", "worm-eye"):
        for suffix, s in SCALES.items():
            out[creature + suffix] = (creature, s, "4.5")
    out["hand-b52"] = ("hand", 1.0, "5.2")
    return out


def expected_entry(creature, s, blender):
    segs, joints, eyes = CREATURES[creature][0](s)
    origins = {g["name"]: g["origin"] for g in segs}
    js = []
    for j in joints:
        order = cortex_order(j["joins"][0], j["joins"][1], j["position"], j["rotation"],
                             origins)
        if order != j["joins"]:
            raise SystemExit("%s: cortex would order %s, the designer meant %s"
                             % (j["name"], order, j["joins"]))
        js.append({"name": j["name"], "type": j["type"], "spec": j["spec"],
                   "position": v6(j["position"], s), "rotation_euler": v6(j["rotation"]),
                   "segments": order, "gap": r6(j["gap"], s)})
    entry = {"creature": creature, "scale": s, "blender": blender,
             "segments": [{"name": g["name"], "mass": r6(g["mass"]), "origin": v6(g["origin"], s)}
                          for g in segs],
             "joints": js,
             "eyes": [{"name": e["name"], "segment": e["segment"], "distance": r6(e["distance"], s),
                       "position": v6(e["position"], s), "spec": e["spec"],
                       "clip": v6(e["clip"], s)} for e in eyes]}
    return entry


NOTES = [
    "Written by scripts/blender/make_stranger_creatures.py from its own numbers, not read "
    "back from Blender; lengths are rounded to 1e-6 of the file's scale; the .blend files "
    "store float32 (compare with a tolerance of about 1e-5 of the scale).",
    "Blender coordinates, Z up.  segments[].origin: the object's origin (world).  "
    "joints[].position: the joint empty's world position; rotation_euler its XYZ Euler "
    "rotation (its parent `joints` sits at the origin, unrotated); segments: the two "
    "segments the designer meant it to join, in cortex's order (smaller (1,1,1) . "
    "(segment origin in the empty's frame) first); gap: the designer's gap between the "
    "two segments along the bone; for the humanoid MuJoCo's own signed distance between "
    "the two segments' capsules and spheres (negative: they overlap that deep; the "
    "12-sided meshes lie inside the true shapes, so their gaps are a little larger).",
    "eyes[].distance: from the eye to the nearest point of its segment's surface.",
]


def compact(v, indent=0, width=400):
    """JSON with every object or list whose members are scalars or short lists on one
    line (each segment, joint and eye one line)."""
    flat = json.dumps(v, ensure_ascii=False)

    def leaf(x):
        return not isinstance(x, (dict, list)) or (
            isinstance(x, list) and all(not isinstance(y, (dict, list)) for y in x))

    if not isinstance(v, (dict, list)) or (
            len(flat) + indent <= width
            and all(leaf(x) for x in (v.values() if isinstance(v, dict) else v))):
        return flat
    pad = " " * (indent + 1)
    if isinstance(v, dict):
        items = ["%s%s: %s" % (pad, json.dumps(k), compact(x, indent + 1, width))
                 for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"
    items = [pad + compact(x, indent + 1, width) for x in v]
    return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"


def write_expected(out):
    files = {name + ".blend": expected_entry(*spec) for name, spec in all_files().items()}
    text = compact({"notes": NOTES, "files": files}) + "\n"
    path = os.path.join(out, "expected.json")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    print("wrote", path)
    return files


def save(path):
    update()
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(path), compress=False,
                                check_existing=False)
    print("wrote", path, os.path.getsize(path), "bytes")


# ------------------------------------------------------------ check


def world_mesh(obj):
    mw = obj.matrix_world
    vs = [mw @ v.co for v in obj.data.vertices]
    fs = [tuple(p.vertices) for p in obj.data.polygons]
    return vs, fs


def signed_volume(vs, fs):
    vol = 0.0
    for f in fs:
        for i in range(1, len(f) - 1):
            a, b, c = vs[f[0]], vs[f[i]], vs[f[i + 1]]
            vol += a.dot(b.cross(c)) / 6.0
    return vol


def mesh_gap(a, b, trees):
    """Smallest distance between two meshes' surfaces (0 when they meet)."""
    ta, tb = trees[a][0], trees[b][0]
    if ta.overlap(tb):
        return 0.0
    best = float("inf")
    for p in trees[a][1]:
        best = min(best, tb.find_nearest(p)[3])
    for p in trees[b][1]:
        best = min(best, ta.find_nearest(p)[3])
    return best


def loose_parts(me):
    parent = list(range(len(me.vertices)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    for e in me.edges:
        a, b = find(e.vertices[0]), find(e.vertices[1])
        parent[a] = b
    return len({find(i) for i in range(len(me.vertices))})


def inside(p, tree):
    loc, normal, _, d = tree.find_nearest(p)
    return d > 0 and (p - loc).dot(normal) < 0


def check_file(path, exp, errors):
    bpy.ops.wm.open_mainfile(filepath=os.path.abspath(path), load_ui=False)
    update()
    s = exp["scale"]
    tol = 2e-5 * s
    name = os.path.basename(path)

    def fail(msg):
        errors.append("%s: %s" % (name, msg))

    objs = bpy.data.objects
    want = ({g["name"] for g in exp["segments"]} | {j["name"] for j in exp["joints"]}
            | {e["name"] for e in exp["eyes"]} | {"joints"} | ({"eyes"} if exp["eyes"] else set()))
    if {o.name for o in objs} != want:
        fail("objects %s, expected %s" % (sorted(o.name for o in objs), sorted(want)))
    trees = {}
    seg_rows = []
    for g in exp["segments"]:
        o = objs.get(g["name"])
        if o is None or o.type != "MESH" or o.parent is not None:
            fail("segment %s missing, not a mesh or parented" % g["name"])
            continue
        if abs(o.get("mass", -1) - g["mass"]) > 1e-6:
            fail("mass of %s" % g["name"])
        if (o.matrix_world.translation - Vector(g["origin"])).length > tol:
            fail("origin of %s at %s" % (g["name"], tuple(o.matrix_world.translation)))
        vs, fs = world_mesh(o)
        if signed_volume(vs, fs) <= 0:
            fail("%s is inside out" % g["name"])
        trees[g["name"]] = (BVHTree.FromPolygons(vs, fs), vs)
        seg_rows.append((g["name"], o["mass"], tuple(o.scale), tuple(o.rotation_euler),
                         len(o.data.vertices), loose_parts(o.data), signed_volume(vs, fs)))
    root = objs.get("joints")
    if root is None or root.type != "EMPTY" or root.matrix_world != Matrix.Identity(4):
        fail("no `joints` empty at the origin")
    rows = []
    for j in exp["joints"]:
        o = objs.get(j["name"])
        if o is None or o.type != "EMPTY" or o.parent is None or o.parent.name != "joints":
            fail("joint %s missing or not under `joints`" % j["name"])
            continue
        if o.get("joint") != j["spec"]:
            fail("spec of %s: %r" % (j["name"], o.get("joint")))
        p = o.matrix_world.translation.copy()
        if (p - Vector(j["position"])).length > tol:
            fail("%s at %s" % (j["name"], tuple(p)))
        frame = o.matrix_world.to_3x3().normalized()
        want_frame = Matrix(frame_of(j["rotation_euler"]))
        if max(abs(frame[r][c] - want_frame[r][c]) for r in range(3) for c in range(3)) > 1e-5:
            fail("rotation of %s" % j["name"])
        keys = {}
        for g in exp["segments"]:
            q = frame.transposed() @ (objs[g["name"]].matrix_world.translation - p)
            keys[g["name"]] = q.x + q.y + q.z
        a, b = j["segments"]
        if not keys[a] < keys[b]:
            fail("order of %s" % j["name"])
        dist = {n: t[0].find_nearest(p)[3] for n, t in trees.items()}
        ins = {n: inside(p, t[0]) for n, t in trees.items()}
        others = sorted((d, n) for n, d in dist.items() if n not in (a, b))
        gap = mesh_gap(a, b, trees)
        if exp["creature"] != "humanoid":
            if abs(gap - j["gap"]) > tol:
                fail("gap of %s measured %r" % (j["name"], gap))
        elif (j["gap"] < 0) != (gap == 0.0) or (
                j["gap"] > 0 and not j["gap"] - tol <= gap <= j["gap"] + 0.01 * s):
            fail("gap of %s measured %r, MuJoCo's %r" % (j["name"], gap, j["gap"]))
        rows.append((j["name"], a, b, gap, j["gap"], dist[a], ins[a], dist[b], ins[b],
                     others[0][1], others[0][0]))
    eye_rows = []
    for e in exp["eyes"]:
        o = objs.get(e["name"])
        if o is None or o.type != "CAMERA" or o.parent is None or o.parent.name != "eyes":
            fail("eye %s missing, not a camera or not under `eyes`" % e["name"])
            continue
        if o.get("eye") != e["spec"]:
            fail("spec of %s" % e["name"])
        p = o.matrix_world.translation.copy()
        if (p - Vector(e["position"])).length > tol:
            fail("%s at %s" % (e["name"], tuple(p)))
        look = o.matrix_world.to_3x3() @ Vector((0, 0, -1))
        up = o.matrix_world.to_3x3() @ Vector((0, 1, 0))
        if (look - Vector((1, 0, 0))).length > 1e-5 or (up - Vector((0, 0, 1))).length > 1e-5:
            fail("%s looks along %s, up %s" % (e["name"], tuple(look), tuple(up)))
        if abs(o.data.clip_start - e["clip"][0]) > 1e-6 * e["clip"][0] or \
                abs(o.data.clip_end - e["clip"][1]) > 1e-6 * e["clip"][1]:
            fail("clip of %s" % e["name"])
        d = trees[e["segment"]][0].find_nearest(p)[3]
        if abs(d - e["distance"]) > tol:
            fail("%s is %r from %s" % (e["name"], d, e["segment"]))
        others = sorted((t[0].find_nearest(p)[3], n) for n, t in trees.items()
                        if n != e["segment"])
        eye_rows.append((e["name"], e["segment"], d, others[0][1], others[0][0]))
    lowest = min(v.z for _, vs in trees.values() for v in vs)
    print("%s: lowest vertex z = %.6g" % (name, lowest))
    if exp["creature"] == "humanoid" and abs(lowest) > tol:
        fail("the feet are not at z = 0 (lowest %r)" % lowest)
    return seg_rows, rows, eye_rows


def print_tables(name, s, seg_rows, rows, eye_rows):
    print("\n== %s (scale %g, Blender %s)" % (name, s, bpy.app.version_string))
    print("%-15s %6s %-24s %-20s %5s %6s %10s" % (
        "segment", "mass", "object scale", "object rotation", "verts", "pieces", "volume"))
    for n, m, sc, rot, nv, parts, vol in seg_rows:
        print("%-15s %6.4g %-24s %-20s %5d %6d %10.4g" % (
            n, m, "(%.4g %.4g %.4g)" % sc, "(%.4g %.4g %.4g)" % rot, nv, parts, vol))
    print("%-15s %-15s %-15s %10s %10s %10s %10s %-15s %9s" % (
        "joint", "first", "second", "gap", "designed", "d(first)", "d(second)",
        "nearest other", "d(other)"))

    def d(x, ins):
        return ("-" if ins else "") + "%.6g" % x   # '-': the joint is inside that segment

    for (j, a, b, gap, designed, da, ia, db, ib, o, do) in rows:
        print("%-15s %-15s %-15s %10s %10.6g %10s %10s %-15s %9.6g" % (
            j, a, b, "%.6g" % gap if gap > 0 else "overlap", designed, d(da, ia), d(db, ib),
            o, do))
    for (e, seg, dist, o, do) in eye_rows:
        print("eye %-12s on %-12s distance %.6g; nearest other %s %.6g" % (e, seg, dist, o, do))


def main():
    args = dump.script_args()
    out = os.path.normpath(os.path.abspath(args[0]) if args else os.path.join(
        HERE, "..", "..", "test", "fixtures", "strangers"))
    os.makedirs(out, exist_ok=True)
    files = all_files()
    new = bpy.app.version >= (5, 0, 0)
    names = args[1:] or [n for n, (_, _, b) in files.items() if (b == "5.2") == new]
    unknown = [n for n in names if n not in files]
    if unknown:
        sys.exit("no file called %s; choose from %s" % (unknown, sorted(files)))
    print("Blender", bpy.app.version_string, "->", out)
    expected = write_expected(out)
    for n in names:
        creature, s, _ = files[n]
        CREATURES[creature][1](s)
        save(os.path.join(out, n + ".blend"))
    errors = []
    for n in names:
        exp = expected[n + ".blend"]
        tables = check_file(os.path.join(out, n + ".blend"), exp, errors)
        print_tables(n + ".blend", exp["scale"], *tables)
    if errors:
        print("\nFAILED:\n  " + "\n  ".join(errors))
        sys.exit(1)
    print("\nall %d files check out" % len(names))


if __name__ == "__main__":
    main()
