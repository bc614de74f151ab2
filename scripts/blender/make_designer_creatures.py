"""Build a four-legged creature and ten copies of it with one designer mistake each.

    blender -b --factory-startup --python-exit-code 1 \
        --python scripts/blender/make_designer_creatures.py -- [OUTDIR]

OUTDIR defaults to test/fixtures/designer in the repo.  It writes
quadruped.blend (a correct creature), one <mistake>.blend per entry of
VARIANTS, dump.py's JSON beside each, and expected.json: what this script
knows about every file (segments, joints, distances from the joints to the
segments, the mistake), computed from the numbers below and not read back
from Blender.  check_designer_creatures.py compares the saved files with it.

The quadruped follows the creature conventions of make_creatures.py: Z up,
head toward +X, its left side toward +Y; every segment an axis-aligned box
(origin at its centre, float "mass"); one EMPTY per joint under the EMPTY
"joints", in the middle of the 0.03 gap between its two segments, every
other segment >= 0.33 away (Euclidean and L-infinity); the joint empties
are rotated so that cortex's rule (the target with the smaller
(1,1,1) . position-in-the-joint's-frame first) puts the proximal segment
(torso side) first:

- front hips and knees: rotation (0, pi/2, 0): local X down the leg (the
  hip cone's twist axis), local Y = world +Y, local Z = world +X;
- back hips and knees: rotation (0, pi/2, pi): local X down the leg, local
  Y = world -Y, local Z = world -X;
- tail joints: turned pi about Z (local X points away from the torso);
- neck-joint and head-joint: unrotated (local X points away from the torso).

Knees are hinges about local Y with :limit [0 pi/2]: a standing leg rests at
0, on its lower limit (on purpose).  Positive angles fold the front feet
backward (-X) and the back feet forward (+X), like a horse's knee and hock.
The neck nods about Y (+-pi/4; positive lowers the head), the head turns
in a cone, the tail joints are points.
"""

import json
import math
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402
from check_creatures import read_joint  # noqa: E402
from make_creatures import GAP, HALF_GAP, hinge, joint_empty, joints_root, segment  # noqa: E402
from make_fixtures import box_mesh, empty_file, material, save, update  # noqa: E402

# ------------------------------------------------------------------ design

TORSO_HALF = (1.0, 0.4, 0.25)       # 2 x 0.8 x 0.5
LEG_HALF = (0.1, 0.1, 0.25)         # 0.2 x 0.2 x 0.5, upper and lower
NECK_HALF = (0.2, 0.1, 0.1)         # 0.4 x 0.2 x 0.2
HEAD_HALF = (0.2, 0.15, 0.15)       # 0.4 x 0.3 x 0.3
TAIL_HALF = (0.2, 0.06, 0.06)       # 0.4 x 0.12 x 0.12
ROCK_HALF = (0.2, 0.2, 0.2)         # overlap.blend only

LEGS = [  # suffix, x, y of the leg's axis
    ("front-r", 0.7, -0.3),
    ("front-l", 0.7, 0.3),
    ("back-r", -0.7, -0.3),
    ("back-l", -0.7, 0.3),
]
LOWER_Z = LEG_HALF[2]                        # feet at z = 0
KNEE_Z = 2 * LEG_HALF[2] + HALF_GAP          # 0.515
UPPER_Z = KNEE_Z + HALF_GAP + LEG_HALF[2]    # 0.78
HIP_Z = UPPER_Z + LEG_HALF[2] + HALF_GAP     # 1.045
TORSO_Z = HIP_Z + HALF_GAP + TORSO_HALF[2]   # 1.31
SPINE_Z = TORSO_Z + 0.1                      # neck, head and tail axis: 1.41

MASSES = {"torso": 4.0, "upper": 0.5, "lower": 0.3, "neck": 0.4, "head": 0.6,
          "tail": 0.2, "rock": 1.0}

FRONT_LEG_ROT = (0.0, math.pi / 2, 0.0)
BACK_LEG_ROT = (0.0, math.pi / 2, math.pi)
TURNED = (0.0, 0.0, math.pi)
NO_ROT = (0.0, 0.0, 0.0)

HIP = "{:type :cone :limit-xz 0.6 :limit-xy 0.6 :twist 0.3}"
KNEE = hinge(0, "(/ Math/PI 2)", "0 1 0")
NECK = hinge("(- (/ Math/PI 4))", "(/ Math/PI 4)", "0 1 0")
HEAD = "{:type :cone :limit-xz 0.5 :limit-xy 0.5 :twist 0.3}"
POINT = "{:type :point}"

COLORS = {"fur": (0.55, 0.40, 0.25, 1.0), "hoof": (0.20, 0.15, 0.10, 1.0),
          "face": (0.65, 0.50, 0.35, 1.0), "rock": (0.45, 0.45, 0.45, 1.0)}


def quadruped():
    """The correct creature as data: segments, joints, and other objects."""
    segs = []

    def seg(name, half, center, mass, mat="fur"):
        segs.append({"name": name, "half": tuple(half), "center": tuple(center),
                     "mass": mass, "material": mat})

    joints = []

    def joint(name, position, rotation, spec, pair):
        joints.append({"name": name, "position": tuple(position), "rotation": rotation,
                       "spec": spec, "intended": pair, "parent": "joints"})

    seg("torso", TORSO_HALF, (0.0, 0.0, TORSO_Z), MASSES["torso"])
    for suffix, x, y in LEGS:
        rot = FRONT_LEG_ROT if suffix.startswith("front") else BACK_LEG_ROT
        upper, lower = "upper-leg-" + suffix, "lower-leg-" + suffix
        seg(upper, LEG_HALF, (x, y, UPPER_Z), MASSES["upper"])
        seg(lower, LEG_HALF, (x, y, LOWER_Z), MASSES["lower"], "hoof")
        joint("hip-" + suffix, (x, y, HIP_Z), rot, HIP, ("torso", upper))
        joint("knee-" + suffix, (x, y, KNEE_Z), rot, KNEE, (upper, lower))

    front = TORSO_HALF[0]                            # torso's +X face
    neck_x = front + GAP + NECK_HALF[0]
    head_x = neck_x + NECK_HALF[0] + GAP + HEAD_HALF[0]
    seg("neck", NECK_HALF, (neck_x, 0.0, SPINE_Z), MASSES["neck"])
    seg("head", HEAD_HALF, (head_x, 0.0, SPINE_Z), MASSES["head"], "face")
    joint("neck-joint", (front + HALF_GAP, 0.0, SPINE_Z), NO_ROT, NECK, ("torso", "neck"))
    joint("head-joint", (neck_x + NECK_HALF[0] + HALF_GAP, 0.0, SPINE_Z), NO_ROT, HEAD,
          ("neck", "head"))

    x = -TORSO_HALF[0]                               # torso's -X face
    previous = "torso"
    for n in (1, 2, 3):
        name = "tail-%d" % n
        joint("tail-joint-%d" % n, (x - HALF_GAP, 0.0, SPINE_Z), TURNED, POINT,
              (previous, name))
        x -= GAP
        seg(name, TAIL_HALF, (x - TAIL_HALF[0], 0.0, SPINE_Z), MASSES["tail"])
        x -= 2 * TAIL_HALF[0]
        previous = name
    return {"segments": segs, "joints": joints, "joints_name": "joints", "others": [],
            "mistake": None}


def find(items, name):
    return next(i for i in items if i["name"] == name)


def moved(name, position, why):
    def change(d):
        find(d["joints"], name)["position"] = tuple(position)
        return {"object": name, "what": why}
    return change


def ambiguous(d):
    # Above tail-1, 0.21 from it, 0.22 from tail-2's +X face and 0.24 from
    # the torso's -X face (L-infinity): three segments about equally near.
    find(d["joints"], "tail-joint-2")["position"] = (-TORSO_HALF[0] - 0.24, 0.0,
                                                     SPINE_Z + TAIL_HALF[2] + 0.21)
    return {"object": "tail-joint-2", "near": ["tail-1", "tail-2", "torso"],
            "what": "moved above tail-1: tail-1, tail-2 and the torso are "
                    "0.21, 0.22, 0.24 away (cube), none in a gap"}


def duplicate(d):
    knee = find(d["joints"], "knee-front-r")
    extra = dict(knee, name="knee-front-r-2",
                 position=(knee["position"][0] + 0.05,) + knee["position"][1:])
    d["joints"].append(extra)
    return {"object": "knee-front-r-2", "duplicates": "knee-front-r",
            "what": "a second joint in knee-front-r's gap, 0.05 along +X: two joints "
                    "join upper-leg-front-r and lower-leg-front-r"}


def misnamed(d):
    d["joints_name"] = "Joints"
    for j in d["joints"]:
        j["parent"] = "Joints"
    return {"object": "Joints", "what": "the joints' parent empty is named Joints, not joints"}


def stray(d):
    head = find(d["joints"], "head-joint")
    d["others"].append({"name": "stray", "position": (head["position"][0], 0.05,
                                                      head["position"][2]),
                        "rotation": NO_ROT, "spec": POINT, "intended": ("neck", "head"),
                        "parent": None})
    return {"object": "stray",
            "what": "an empty with a joint property, in head-joint's gap (0.05 along +Y), "
                    "parented to nothing instead of joints"}


def respec(name, spec, why):
    def change(d):
        find(d["joints"], name)["spec"] = spec
        return {"object": name, "what": why}
    return change


def rock(d):
    # On the torso's back, sunk 0.1 into it; no joint anywhere near it.
    d["segments"].append({"name": "rock", "half": ROCK_HALF, "mass": MASSES["rock"],
                          "center": (0.0, 0.0, TORSO_Z + TORSO_HALF[2] + ROCK_HALF[2] - 0.1),
                          "material": "rock"})
    return {"object": "rock", "what": "an unjoined segment overlapping the torso by 0.1"}


VARIANTS = [
    ("misplaced-joint", moved("knee-front-r", (0.7, -0.6, KNEE_Z),
                              "moved 0.3 along -Y (outward): 0.2 from both its segments")),
    ("far-joint", moved("knee-back-l", (-0.7, 4.4, KNEE_Z),
                        "moved 4.1 along +Y: 4.0 from its two segments (Euclidean), the cube "
                        "meets five segments at 4.0")),
    ("inside-joint", moved("knee-front-l", (0.0, 0.0, TORSO_Z),
                           "moved to the torso's centre, 0.25 inside it")),
    ("ambiguous-joint", ambiguous),
    ("duplicate-joint", duplicate),
    ("misnamed-joints", misnamed),
    ("stray-joint", stray),
    ("typo-key", respec("knee-front-r",
                        "{:type :hinge :limit [0 (/ Math/PI 2)] :axs (Vector3f. 0 1 0)}",
                        ":axs instead of :axis (a hinge without :axis turns about X)")),
    ("degree-limit", respec("knee-front-r", hinge(0, 90, "0 1 0"),
                            ":limit [0 90]: degrees where radians are meant")),
    ("overlap", rock),
]


def design(variant=None):
    d = quadruped()
    if variant is not None:
        name, change = variant
        d["mistake"] = dict({"kind": name}, **change(d))
    return d


# ------------------------------------------------------- geometry (exact)

def r9(x):
    return round(float(x), 9) + 0.0   # + 0.0: no -0.0 in the JSON


def vec9(v):
    return [r9(c) for c in v]


def box_distances(p, s):
    """(Euclidean distance to the surface, cube half-size, inside?) from p to box s.

    The cube is the smallest axis-aligned cube centred on p that meets the
    box's surface: what cortex's growing cube measures."""
    d = [abs(p[i] - s["center"][i]) - s["half"][i] for i in range(3)]
    m = max(d)
    if m <= 0:
        return -m, -m, True
    return math.sqrt(sum(max(x, 0.0) ** 2 for x in d)), m, False


def nearest(p, segs, count):
    rows = []
    for s in segs:
        dist, cube, inside = box_distances(p, s)
        rows.append((r9(cube), r9(dist), s["name"], inside))
    rows.sort()
    return [{"segment": n, "distance": dist, "cube": cube, "inside": inside}
            for cube, dist, n, inside in rows[:count]]


def frame(rotation):
    """The rotation matrix of Blender's XYZ Euler angles (Rz Ry Rx), in doubles.

    (mathutils works in single precision; these numbers go into expected.json.)"""
    def mul(a, b):
        return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    (cx, cy, cz), (sx, sy, sz) = ([math.cos(a) for a in rotation],
                                  [math.sin(a) for a in rotation])
    rx = [[1, 0, 0], [0, cx, -sx], [0, sx, cx]]
    ry = [[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]]
    rz = [[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]
    return mul(rz, mul(ry, rx))


def apply(m, v):
    return [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]


def transpose(m):
    return [list(row) for row in zip(*m)]


def cortex_order(j, segs):
    """The joint's two intended segments as cortex orders them: by
    (1,1,1) . (centre - joint) in the joint's frame, smaller first."""
    rot_inv = transpose(frame(j["rotation"]))
    p = j["position"]
    key = {n: sum(apply(rot_inv, [c - q for c, q in zip(find(segs, n)["center"], p)]))
           for n in j["intended"]}
    return sorted(j["intended"], key=lambda n: (key[n], n))


def overlap(a, b):
    """How far boxes a and b overlap along each axis (negative: apart)."""
    return [min(a["center"][k] + a["half"][k], b["center"][k] + b["half"][k])
            - max(a["center"][k] - a["half"][k], b["center"][k] - b["half"][k])
            for k in range(3)]


def overlaps(segs):
    out = []
    for i, a in enumerate(segs):
        for b in segs[i + 1:]:
            ext = overlap(a, b)
            if min(ext) > 1e-9:
                out.append({"segments": sorted([a["name"], b["name"]]), "depth": r9(min(ext)),
                            "volume": r9(ext[0] * ext[1] * ext[2])})
    return out


def joint_entry(j, segs):
    spec = read_joint(j["spec"])
    entry = {"name": j["name"], "parent": j["parent"], "type": spec[":type"][1:],
             "segments": cortex_order(j, segs), "position": vec9(j["position"]),
             "rotation_euler": vec9(j["rotation"]),
             "frame_axes": [vec9(c) for c in transpose(frame(j["rotation"]))],
             "spec": j["spec"], "keys": sorted(k[1:] for k in spec)}
    if spec[":type"] == ":hinge":
        entry["limit"] = vec9(spec[":limit"])
        axis = spec.get(":axis")
        entry["axis"] = vec9(axis) if axis is not None else None
        if axis is not None:
            length = math.sqrt(sum(c * c for c in axis))
            entry["axis_world"] = vec9(apply(frame(j["rotation"]), [c / length for c in axis]))
        else:
            entry["axis_world"] = None
    elif spec[":type"] == ":cone":
        for k in ("limit-xz", "limit-xy", "twist"):
            entry[k] = r9(spec[":" + k])
    entry["nearest"] = nearest(j["position"], segs, 4)
    return entry


def expected(d):
    segs = d["segments"]
    out = {"joints_parent": d["joints_name"],
           "segments": [{"name": s["name"], "mass": s["mass"], "vertices": 8,
                         "volume": r9(8 * s["half"][0] * s["half"][1] * s["half"][2]),
                         "center": vec9(s["center"]), "half_extents": vec9(s["half"])}
                        for s in sorted(segs, key=lambda s: s["name"])],
           "joints": [joint_entry(j, segs) for j in sorted(d["joints"], key=lambda j: j["name"])],
           "overlaps": overlaps(segs),
           "mistake": None}
    m = d["mistake"]
    if m is not None:
        m = dict(m)
        name = m["object"]
        j = next((j for j in d["joints"] + d["others"] if j["name"] == name), None)
        if j is not None:
            m["position"] = vec9(j["position"])
            m["intended"] = cortex_order(j, segs)
            m["nearest"] = nearest(j["position"], segs, 6)
        if name == "stray":
            m["entry"] = joint_entry(j, segs)
        if name == "Joints":
            m["expected_name"] = "joints"
        if name == "rock":
            r = find(segs, name)
            m["center"], m["half_extents"] = vec9(r["center"]), vec9(r["half"])
            m["overlaps"] = [o for o in overlaps(segs) if name in o["segments"]]
            near = sorted((r9(cube), r9(dist), j["name"])
                          for j in d["joints"]
                          for dist, cube, _ in [box_distances(j["position"], r)])
            m["joints_near"] = [{"joint": n, "distance": dist, "cube": cube}
                                for cube, dist, n in near[:3]]
        out["mistake"] = m
    return out


# ------------------------------------------------------------------ build

def build(d):
    empty_file()
    mats = {k: material(k, c) for k, c in sorted(COLORS.items())}
    for s in d["segments"]:
        segment(s["name"], box_mesh(s["name"], *s["half"]), s["center"], s["mass"],
                mats[s["material"]])
    root = joints_root()
    root.name = d["joints_name"]
    for j in d["joints"]:
        joint_empty(j["name"], root, j["position"], j["spec"], rotation=j["rotation"])
    for o in d["others"]:
        joint_empty(o["name"], None, o["position"], o["spec"], rotation=o["rotation"])
    update()


def compact(v, indent=0):
    """JSON with flat objects and lists of scalars on one line when short."""
    flat = json.dumps(v, ensure_ascii=False)

    def leaf(x):
        return not isinstance(x, (dict, list)) or (
            isinstance(x, list) and all(not isinstance(y, (dict, list)) for y in x))

    if not isinstance(v, (dict, list)):
        return flat
    if len(flat) + indent <= 150 and (
            all(leaf(x) for x in (v.values() if isinstance(v, dict) else v))):
        return flat
    pad = " " * (indent + 1)
    if isinstance(v, dict):
        items = ["%s%s: %s" % (pad, json.dumps(k), compact(x, indent + 1)) for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"
    items = [pad + compact(x, indent + 1) for x in v]
    return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"


NOTES = [
    "Written by scripts/blender/make_designer_creatures.py from its own numbers, not "
    "read back from Blender: the .blend files store float32, so compare with a "
    "tolerance (1e-5).",
    "Blender coordinates, Z up; every segment is an axis-aligned box (8 vertices, "
    "6 quads) with its origin at its centre; volume = 8 * product of half_extents.",
    "joints[].segments: the two segments the joint is meant to join, in the order "
    "cortex puts them (smaller (1,1,1) . position-in-the-joint-frame first): proximal first.",
    "frame_axes: the joint empty's local X, Y, Z in world coordinates; axis_world: the "
    "hinge axis in world coordinates (null when the spec has no :axis).",
    "nearest: segments sorted by cube, then distance, then name. distance: Euclidean "
    "distance from the empty to the segment's surface; cube: half-size of the smallest "
    "axis-aligned cube centred on the empty that meets the surface (what cortex's "
    "growing cube measures); inside: the empty is inside the segment.",
    "overlaps: pairs of segments whose boxes intersect (depth: smallest overlap along "
    "an axis).",
]


def main():
    args = dump.script_args()
    out = os.path.normpath(os.path.abspath(args[0]) if args else os.path.join(
        HERE, "..", "..", "test", "fixtures", "designer"))
    os.makedirs(out, exist_ok=True)
    print("Blender", bpy.app.version_string, "->", out)
    files = {}
    for name, variant in [("quadruped", None)] + [(v[0], v) for v in VARIANTS]:
        d = design(variant)
        build(d)
        save(os.path.join(out, name + ".blend"))
        files[name + ".blend"] = expected(d)
    text = compact({"notes": NOTES, "files": files}) + "\n"
    path = os.path.join(out, "expected.json")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    print("wrote", path)


if __name__ == "__main__":
    main()
