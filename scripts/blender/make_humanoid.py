"""Build MuJoCo's standard humanoid (Gymnasium's humanoid.xml) as a cortex creature.

    blender -b --factory-startup --python-exit-code 1 \
        --python scripts/blender/make_humanoid.py -- [OUTDIR]

OUTDIR defaults to test/fixtures/humanoid in the repo.  It writes

- humanoid.blend: the humanoid, MuJoCo's masses, standing with its feet at z = 0;
- humanoid-heavy-hands.blend: the same with lower arms 10 times as heavy as the
  upper arms (mass ratio 10 between joined segments);
- dump.py's JSON beside each (humanoid.json, humanoid-heavy-hands.json);
- expected.json: what this script knows, from its own numbers (segments,
  masses, MuJoCo's mass properties, joints with axes, ranges and the MuJoCo
  degrees of freedom each one stands for, distances from every joint to the
  nearest segments).  check_humanoid.py compares the saved files with it.

Where the numbers come from: the MuJoCo model below is transcribed from
gymnasium/envs/mujoco/assets/humanoid.xml (Gymnasium 1.x; the same file since
gym 0.x): bodies with pos/quat, geoms (capsules by fromto, spheres), hinge
joints with pos/axis/range.  Masses are MuJoCo's model.body_mass (density
1000, inertiafromgeom), pasted from MuJoCo 4.0.0 and re-derived here from the
geoms (the script stops if the two disagree by more than 1e-9).
scripts/compare/humanoid_compare.py --check-fixture compares expected.json
with MuJoCo itself.

The creature (Blender axes, Z up; the humanoid faces +X, its left is +Y):

- 11 segments, one per MuJoCo body, named as MuJoCo names them; the feet are
  merged into the shins (their masses added).  torso holds MuJoCo's torso
  body (chest capsule, head sphere, upper-waist capsule).  Each segment is
  the convex hull of low-poly versions of its body's geoms (10-sided
  capsules and spheres with their vertices on the true surface), clipped
  near its joints (below).  Its origin is the MuJoCo body's centre of mass
  (so cortex's rule, centre of mass at the origin, holds), float "mass".
- Every joint empty sits at MuJoCo's joint anchor.  MuJoCo lets joined geoms
  overlap (a hip anchor lies inside both the pelvis and the thigh); cortex
  needs a gap.  So each of the two segments is clipped by a plane 0.015 from
  the anchor (normal `out`, pointing from the segment to the anchor) and, when
  it does not reach that plane (the torso at the shoulders), extended to the
  point anchor - 0.015 * out: both segments are then exactly 0.015 from the
  anchor (Euclidean), every other segment much further.
- The whole MuJoCo pose is moved down by FOOT_LIFT (0.10703) so that the
  lowest points, the poles of the foot spheres, are at z = 0.  MuJoCo's
  initial pose (torso at z = 1.4) has the feet FOOT_LIFT above its floor.
- Joints: MuJoCo's single hinges (abdomen_x, knees, elbows) become cortex
  hinges with MuJoCo's axes and ranges; its groups of hinges at one anchor
  (abdomen_z + abdomen_y, the hips' x/z/y, the shoulders' 1/2) become cones
  whose twist axis (the empty's local X) runs along the distal bone, whose
  local Y and Z are MuJoCo's hinge axes, and whose limits are the larger
  magnitude of each MuJoCo range (cortex's cones are symmetric: every pose
  MuJoCo allows is inside the cone, and its mirror image too).  A swing that
  MuJoCo does not allow gets 0.1 rad (jBullet ignores swing limits under
  0.05 rad, leaving the swing free); a twist it does not allow gets 0 (jBullet
  locks a twist limit of 0).
- Every joint empty's local X runs along the distal segment's bone, turned
  about it so that cortex's rule (the segment with the smaller
  (1,1,1) . position-in-the-joint-frame first) puts the proximal segment
  first.
"""

import math
import os
import sys

import bmesh
import bpy
from mathutils.bvhtree import BVHTree

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402
from make_creatures import joint_empty, joints_root, segment  # noqa: E402
from make_designer_creatures import compact  # noqa: E402
from make_fixtures import empty_file, material, mesh_from, save, update  # noqa: E402

# ------------------------------------------------------- the MuJoCo model

# body: (parent, pos, quat (w x y z, as written; MuJoCo normalises it))
BODIES = {
    "torso": (None, (0, 0, 1.4), (1, 0, 0, 0)),
    "lwaist": ("torso", (-0.01, 0, -0.26), (1, 0, -0.002, 0)),
    "pelvis": ("lwaist", (0, 0, -0.165), (1, 0, -0.002, 0)),
    "right_thigh": ("pelvis", (0, -0.1, -0.04), (1, 0, 0, 0)),
    "right_shin": ("right_thigh", (0, 0.01, -0.403), (1, 0, 0, 0)),
    "right_foot": ("right_shin", (0, 0, -0.45), (1, 0, 0, 0)),
    "left_thigh": ("pelvis", (0, 0.1, -0.04), (1, 0, 0, 0)),
    "left_shin": ("left_thigh", (0, -0.01, -0.403), (1, 0, 0, 0)),
    "left_foot": ("left_shin", (0, 0, -0.45), (1, 0, 0, 0)),
    "right_upper_arm": ("torso", (0, -0.17, 0.06), (1, 0, 0, 0)),
    "right_lower_arm": ("right_upper_arm", (0.18, -0.18, -0.18), (1, 0, 0, 0)),
    "left_upper_arm": ("torso", (0, 0.17, 0.06), (1, 0, 0, 0)),
    "left_lower_arm": ("left_upper_arm", (0.18, 0.18, -0.18), (1, 0, 0, 0)),
}

# body: [(geom name, "capsule", from, to, radius) or (name, "sphere", pos, radius)]
GEOMS = {
    "torso": [("torso1", "capsule", (0, -0.07, 0), (0, 0.07, 0), 0.07),
              ("head", "sphere", (0, 0, 0.19), 0.09),
              ("uwaist", "capsule", (-0.01, -0.06, -0.12), (-0.01, 0.06, -0.12), 0.06)],
    "lwaist": [("lwaist", "capsule", (0, -0.06, 0), (0, 0.06, 0), 0.06)],
    "pelvis": [("butt", "capsule", (-0.02, -0.07, 0), (-0.02, 0.07, 0), 0.09)],
    "right_thigh": [("right_thigh1", "capsule", (0, 0, 0), (0, 0.01, -0.34), 0.06)],
    "right_shin": [("right_shin1", "capsule", (0, 0, 0), (0, 0, -0.3), 0.049)],
    "right_foot": [("right_foot", "sphere", (0, 0, 0.1), 0.075)],
    "left_thigh": [("left_thigh1", "capsule", (0, 0, 0), (0, -0.01, -0.34), 0.06)],
    "left_shin": [("left_shin1", "capsule", (0, 0, 0), (0, 0, -0.3), 0.049)],
    "left_foot": [("left_foot", "sphere", (0, 0, 0.1), 0.075)],
    "right_upper_arm": [("right_uarm1", "capsule", (0, 0, 0), (0.16, -0.16, -0.16), 0.04)],
    "right_lower_arm": [("right_larm", "capsule", (0.01, 0.01, 0.01), (0.17, 0.17, 0.17), 0.031),
                        ("right_hand", "sphere", (0.18, 0.18, 0.18), 0.04)],
    "left_upper_arm": [("left_uarm1", "capsule", (0, 0, 0), (0.16, 0.16, -0.16), 0.04)],
    "left_lower_arm": [("left_larm", "capsule", (0.01, -0.01, 0.01), (0.17, -0.17, 0.17), 0.031),
                       ("left_hand", "sphere", (0.18, -0.18, 0.18), 0.04)],
}

# MuJoCo hinge joints: name -> (body, pos in body, axis in body, range in degrees)
HINGES = {
    "abdomen_z": ("lwaist", (0, 0, 0.065), (0, 0, 1), (-45, 45)),
    "abdomen_y": ("lwaist", (0, 0, 0.065), (0, 1, 0), (-75, 30)),
    "abdomen_x": ("pelvis", (0, 0, 0.1), (1, 0, 0), (-35, 35)),
    "right_hip_x": ("right_thigh", (0, 0, 0), (1, 0, 0), (-25, 5)),
    "right_hip_z": ("right_thigh", (0, 0, 0), (0, 0, 1), (-60, 35)),
    "right_hip_y": ("right_thigh", (0, 0, 0), (0, 1, 0), (-110, 20)),
    "right_knee": ("right_shin", (0, 0, 0.02), (0, -1, 0), (-160, -2)),
    "left_hip_x": ("left_thigh", (0, 0, 0), (-1, 0, 0), (-25, 5)),
    "left_hip_z": ("left_thigh", (0, 0, 0), (0, 0, -1), (-60, 35)),
    "left_hip_y": ("left_thigh", (0, 0, 0), (0, 1, 0), (-110, 20)),
    "left_knee": ("left_shin", (0, 0, 0.02), (0, -1, 0), (-160, -2)),
    "right_shoulder1": ("right_upper_arm", (0, 0, 0), (2, 1, 1), (-85, 60)),
    "right_shoulder2": ("right_upper_arm", (0, 0, 0), (0, -1, 1), (-85, 60)),
    "right_elbow": ("right_lower_arm", (0, 0, 0), (0, -1, 1), (-90, 50)),
    "left_shoulder1": ("left_upper_arm", (0, 0, 0), (2, -1, 1), (-60, 85)),
    "left_shoulder2": ("left_upper_arm", (0, 0, 0), (0, 1, 1), (-60, 85)),
    "left_elbow": ("left_lower_arm", (0, 0, 0), (0, -1, -1), (-90, 50)),
}

# MuJoCo 4.0.0's model.body_mass for humanoid.xml (kg).
MUJOCO_MASS = {
    "torso": 8.907462370478262,
    "lwaist": 2.261946710584651,
    "pelvis": 6.616194128460103,
    "right_thigh": 4.751750928806242,
    "right_shin": 2.7556961671836424,
    "right_foot": 1.7671458676442586,
    "left_thigh": 4.751750928806242,
    "left_shin": 2.7556961671836424,
    "left_foot": 1.7671458676442586,
    "right_upper_arm": 1.6610804848382084,
    "right_lower_arm": 1.2295401928310803,
    "left_upper_arm": 1.6610804848382084,
    "left_lower_arm": 1.2295401928310803,
}
DENSITY = 1000.0

# ------------------------------------------------------- the creature

# segment: the MuJoCo bodies it is made of
SEGMENTS = {
    "torso": ["torso"],
    "lwaist": ["lwaist"],
    "pelvis": ["pelvis"],
    "right_thigh": ["right_thigh"],
    "right_shin": ["right_shin", "right_foot"],
    "left_thigh": ["left_thigh"],
    "left_shin": ["left_shin", "left_foot"],
    "right_upper_arm": ["right_upper_arm"],
    "right_lower_arm": ["right_lower_arm"],
    "left_upper_arm": ["left_upper_arm"],
    "left_lower_arm": ["left_lower_arm"],
}

GAP_HALF = 0.015      # each segment's distance from its joint's anchor
SIDES = 10            # of every low-poly capsule and sphere
MISSING_SWING = 0.1   # a swing MuJoCo does not allow (jBullet ignores < 0.05)
MISSING_TWIST = 0.0   # a twist MuJoCo does not allow (jBullet locks 0)
HEAVY_HAND_RATIO = 10.0

SQ2 = math.sqrt(0.5)
SQ3 = 1.0 / math.sqrt(3.0)

# joint: (type, proximal, distal, MuJoCo hinges, anchor body,
#         out of the proximal segment and out of the distal one, in the anchor
#         body's frame ("bone": minus the distal bone direction), bone direction,
#         cone: hinge standing for [twist, xz swing, xy swing] (None: not allowed))
JOINTS = [
    ("abdomen", "cone", "torso", "lwaist", ["abdomen_z", "abdomen_y"],
     (0, 0, -1), (0, 0, 1), (0, 0, -1), ["abdomen_z", "abdomen_y", None]),
    ("abdomen_x", "hinge", "lwaist", "pelvis", ["abdomen_x"],
     (0, 0, -1), (0, 0, 1), (0, 0, -1), None),
    ("right_hip", "cone", "pelvis", "right_thigh", ["right_hip_x", "right_hip_z", "right_hip_y"],
     (0, -SQ2, -SQ2), (0, SQ2, SQ2), (0, 0, -1), ["right_hip_z", "right_hip_y", "right_hip_x"]),
    ("left_hip", "cone", "pelvis", "left_thigh", ["left_hip_x", "left_hip_z", "left_hip_y"],
     (0, SQ2, -SQ2), (0, -SQ2, SQ2), (0, 0, -1), ["left_hip_z", "left_hip_y", "left_hip_x"]),
    ("right_knee", "hinge", "right_thigh", "right_shin", ["right_knee"],
     (0, 0, -1), (0, 0, 1), (0, 0, -1), None),
    ("left_knee", "hinge", "left_thigh", "left_shin", ["left_knee"],
     (0, 0, -1), (0, 0, 1), (0, 0, -1), None),
    ("right_shoulder", "cone", "torso", "right_upper_arm", ["right_shoulder1", "right_shoulder2"],
     (0, -1, 0), "bone", (SQ3, -SQ3, -SQ3), [None, "right_shoulder1", "right_shoulder2"]),
    ("left_shoulder", "cone", "torso", "left_upper_arm", ["left_shoulder1", "left_shoulder2"],
     (0, 1, 0), "bone", (SQ3, SQ3, -SQ3), [None, "left_shoulder1", "left_shoulder2"]),
    ("right_elbow", "hinge", "right_upper_arm", "right_lower_arm", ["right_elbow"],
     (1, 0, 0), (-1, 0, 0), (SQ3, SQ3, SQ3), None),
    ("left_elbow", "hinge", "left_upper_arm", "left_lower_arm", ["left_elbow"],
     (1, 0, 0), (-1, 0, 0), (SQ3, -SQ3, SQ3), None),
]

SKIN = (0.8, 0.6, 0.4, 1.0)   # MuJoCo's geom rgba

# ------------------------------------------------------- double-precision math


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def scale(k, a):
    return [k * x for x in a]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    n = norm(a)
    return [x / n for x in a]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(m, v):
    return [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]


def transpose(m):
    return [list(r) for r in zip(*m)]


def columns(x, y, z):
    return [[x[i], y[i], z[i]] for i in range(3)]


def quat_matrix(q):
    w, x, y, z = unit(q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def euler_xyz(m):
    """Blender's XYZ Euler angles (R = Rz Ry Rx) of rotation matrix m."""
    sy = -m[2][0]
    beta = math.asin(max(-1.0, min(1.0, sy)))
    if math.hypot(m[2][1], m[2][2]) < 1e-12:     # gimbal lock: put it all in z
        return [0.0, beta, math.atan2(-m[0][1], m[1][1])]
    return [math.atan2(m[2][1], m[2][2]), beta, math.atan2(m[1][0], m[0][0])]


def euler_matrix(e):
    (cx, cy, cz), (sx, sy, sz) = [math.cos(a) for a in e], [math.sin(a) for a in e]
    rx = [[1, 0, 0], [0, cx, -sx], [0, sx, cx]]
    ry = [[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]]
    rz = [[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]
    return matmul(rz, matmul(ry, rx))


def jacobi_eigenvalues(a):
    """Eigenvalues of a symmetric 3x3 matrix, ascending."""
    a = [list(r) for r in a]
    for _ in range(100):
        off = max((abs(a[i][j]), i, j) for i in range(3) for j in range(3) if i < j)
        if off[0] < 1e-18:
            break
        _, p, q = off
        theta = (a[q][q] - a[p][p]) / (2 * a[p][q])
        t = (1 if theta >= 0 else -1) / (abs(theta) + math.sqrt(theta * theta + 1))
        c = 1 / math.sqrt(t * t + 1)
        s = t * c
        rot = [[1.0 if i == j else 0.0 for j in range(3)] for i in range(3)]
        rot[p][p] = rot[q][q] = c
        rot[p][q], rot[q][p] = s, -s
        a = matmul(transpose(rot), matmul(a, rot))
    return sorted(a[i][i] for i in range(3))


def r9(x):
    return round(float(x), 9) + 0.0


def vec9(v):
    return [r9(c) for c in v]


# ------------------------------------------------------- MuJoCo kinematics


def world_frames():
    """{body: (position, rotation)} in MuJoCo's world at qpos0."""
    out = {}
    for name, (parent, pos, quat) in BODIES.items():   # parents come first
        p, r = ([0.0, 0.0, 0.0], [[1, 0, 0], [0, 1, 0], [0, 0, 1]]) if parent is None \
            else out[parent]
        out[name] = (add(p, apply(r, pos)), matmul(r, quat_matrix(quat)))
    return out


FRAMES = world_frames()


def to_world(body, v):
    p, r = FRAMES[body]
    return add(p, apply(r, v))


def dir_world(body, v):
    return apply(FRAMES[body][1], unit(v))


def geom_mass_properties(g):
    """(mass, centre, inertia about the centre in the body frame) as MuJoCo computes them."""
    if g[1] == "sphere":
        _, _, pos, r = g
        m = DENSITY * 4.0 / 3.0 * math.pi * r ** 3
        i = 0.4 * m * r * r
        return m, list(pos), [[i, 0, 0], [0, i, 0], [0, 0, i]]
    _, _, a, b, r = g
    h = norm(sub(b, a))
    vol = math.pi * r * r * h + 4.0 / 3.0 * math.pi * r ** 3
    m = DENSITY * vol
    ms = m * (4.0 / 3.0 * math.pi * r ** 3) / vol
    mc = m - ms
    i_perp = mc * (3 * r * r + h * h) / 12 + 0.4 * ms * r * r + ms * h * (3 * r + 2 * h) / 8
    i_axis = mc * r * r / 2 + 0.4 * ms * r * r
    u = unit(sub(b, a))
    # i_perp * identity + (i_axis - i_perp) * u u^T
    tensor = [[i_perp * (1 if i == j else 0) + (i_axis - i_perp) * u[i] * u[j]
               for j in range(3)] for i in range(3)]
    return m, scale(0.5, add(a, b)), tensor


def combine(parts):
    """Mass, centre and inertia tensor (about the centre) of [(m, c, I)] in one frame."""
    mass = sum(m for m, _, _ in parts)
    c = scale(1.0 / mass, [sum(m * ci[k] for m, ci, _ in parts) for k in range(3)])
    total = [[0.0] * 3 for _ in range(3)]
    for m, ci, t in parts:
        d = sub(ci, c)
        for i in range(3):
            for j in range(3):
                total[i][j] += t[i][j] + m * ((dot(d, d) if i == j else 0) - d[i] * d[j])
    return mass, c, total


def body_mass_properties(body):
    """The body's mass properties in the world frame (MuJoCo's qpos0)."""
    _, rot = FRAMES[body]
    parts = []
    for g in GEOMS[body]:
        m, c, t = geom_mass_properties(g)
        parts.append((m, to_world(body, c), matmul(rot, matmul(t, transpose(rot)))))
    return combine(parts)


def check_masses():
    for body, want in MUJOCO_MASS.items():
        got = body_mass_properties(body)[0]
        if abs(got - want) > 1e-9 * want:
            raise SystemExit("mass of %s: geoms give %r, MuJoCo %r: the transcription "
                             "of humanoid.xml is wrong" % (body, got, want))


def foot_lift():
    """How high MuJoCo's lowest point (the foot spheres' bottom) is at qpos0."""
    low = []
    for body in ("right_foot", "left_foot"):
        for g in GEOMS[body]:
            low.append(to_world(body, g[2])[2] - g[3])
    return min(low)


FOOT_LIFT = foot_lift()


def blender(p):
    """A MuJoCo world point in the Blender file (moved down by FOOT_LIFT)."""
    return [p[0], p[1], p[2] - FOOT_LIFT]


# ------------------------------------------------------- low-poly shapes


def perpendicular(u):
    """A unit vector perpendicular to u, chosen the same way every time."""
    ref = [0, 0, 1] if abs(u[2]) < 0.9 else [1, 0, 0]
    return unit(cross(u, ref))


def sphere_points(c, r, axis=(0, 0, 1), rings=(-54, -18, 18, 54)):
    """Rings of SIDES vertices at the given latitudes and the two poles, on the sphere."""
    u = unit(list(axis))
    e1 = perpendicular(u)
    e2 = cross(u, e1)
    pts = [add(c, scale(r, u)), add(c, scale(-r, u))]
    for lat in rings:
        la = math.radians(lat)
        for i in range(SIDES):
            a = 2 * math.pi * (i + 0.5) / SIDES
            d = add(scale(math.cos(la) * math.cos(a), e1), scale(math.cos(la) * math.sin(a), e2))
            pts.append(add(c, scale(r, add(d, scale(math.sin(la), u)))))
    return pts


def capsule_points(a, b, r):
    """A 10-sided capsule: equator and 50-degree rings at each end, and the poles."""
    u = unit(sub(b, a))
    e1 = perpendicular(u)
    e2 = cross(u, e1)
    pts = []
    for c, s in ((a, -1.0), (b, 1.0)):
        pts.append(add(c, scale(s * r, u)))
        for lat in (0.0, 50.0):
            la = math.radians(lat)
            for i in range(SIDES):
                ang = 2 * math.pi * (i + 0.5) / SIDES
                d = add(scale(math.cos(ang), e1), scale(math.sin(ang), e2))
                pts.append(add(c, scale(r, add(scale(math.cos(la), d), scale(s * math.sin(la), u)))))
    return pts


def geom_points(body, g):
    if g[1] == "sphere":
        return sphere_points(to_world(body, g[2]), g[3])
    return capsule_points(to_world(body, g[2]), to_world(body, g[3]), g[4])


def hull(points):
    """The convex hull of points: (vertices, faces), outward, coplanar faces merged."""
    unique = []
    for p in points:      # near-duplicates (clipping makes some) give sliver faces
        if all(norm(sub(p, q)) > 1e-6 for q in unique):
            unique.append(p)
    bm = bmesh.new()
    verts = [bm.verts.new(p) for p in unique]
    res = bmesh.ops.convex_hull(bm, input=verts)
    unused = {v for v in res["geom_interior"] + res["geom_unused"]
              if isinstance(v, bmesh.types.BMVert)}
    bmesh.ops.delete(bm, geom=list(unused), context="VERTS")
    bmesh.ops.dissolve_degenerate(bm, dist=1e-6, edges=list(bm.edges))
    bmesh.ops.dissolve_limit(bm, angle_limit=1e-5, verts=list(bm.verts), edges=list(bm.edges))
    bmesh.ops.recalc_face_normals(bm, faces=bm.faces)
    bm.verts.index_update()
    vs = [list(v.co) for v in bm.verts]
    fs = [[v.index for v in f.verts] for f in bm.faces]
    bm.free()
    return vs, fs


def clip(vs, fs, anchor, out, g):
    """The hull of vs cut to (x - anchor) . out <= -g."""
    def s(p):
        return dot(sub(p, anchor), out) + g
    eps = 1e-7      # the vertices are float32
    keep = [v for v in vs if s(v) <= eps]
    edges = {tuple(sorted((f[i], f[(i + 1) % len(f)]))) for f in fs for i in range(len(f))}
    for i, j in edges:
        si, sj = s(vs[i]), s(vs[j])
        if (si < -eps and sj > eps) or (si > eps and sj < -eps):
            t = si / (si - sj)
            keep.append(add(vs[i], scale(t, sub(vs[j], vs[i]))))
    return hull(keep)


# ------------------------------------------------------- design


def segment_mass_properties(name):
    parts = [body_mass_properties(b) for b in SEGMENTS[name]]
    return combine(parts)


def joint_design():
    """Per joint: anchor (MuJoCo world), frame, out directions, spec and MuJoCo's dofs."""
    out = []
    coms = {s: segment_mass_properties(s)[1] for s in SEGMENTS}
    for name, kind, prox, dist, dofs, out_p, out_d, bone, cone_map in JOINTS:
        body, pos = HINGES[dofs[0]][0], HINGES[dofs[0]][1]
        anchor = to_world(body, pos)
        x = dir_world(body, bone)
        op = dir_world(body, out_p)
        od = scale(-1, x) if out_d == "bone" else dir_world(body, out_d)
        axes = {d: dir_world(HINGES[d][0], HINGES[d][2]) for d in dofs}
        if kind == "hinge":
            y = axes[dofs[0]]
        else:
            y = axes[cone_map[1]]
        y = unit(sub(y, scale(dot(y, x), x)))
        z = cross(x, y)
        frame = columns(x, y, z)

        def key(seg, f):
            return sum(apply(transpose(f), sub(coms[seg], anchor)))
        flipped = columns(x, scale(-1, y), scale(-1, z))
        if key(prox, frame) - key(dist, frame) > key(prox, flipped) - key(dist, flipped):
            frame = flipped
        euler = euler_xyz(frame)
        frame = euler_matrix(euler)      # exactly what Blender will build
        j = {"name": name, "type": kind, "segments": [prox, dist], "anchor": anchor,
             "rotation": euler, "frame": frame, "out": {prox: op, dist: od},
             "order_keys": [key(prox, frame), key(dist, frame)],
             "mujoco": [{"joint": d, "axis_world": axes[d], "range_deg": list(HINGES[d][3])}
                        for d in dofs]}
        if kind == "hinge":
            lo, hi = HINGES[dofs[0]][3]
            local = apply(transpose(frame), axes[dofs[0]])
            local = [float(round(c)) if abs(c - round(c)) < 1e-9 else c for c in local]
            j["axis"] = local
            j["axis_world"] = axes[dofs[0]]
            j["limit"] = [math.radians(lo), math.radians(hi)]
            j["spec"] = "{:type :hinge :limit [%s %s] :axis [%s]}" % (
                degrees_text(lo), degrees_text(hi), " ".join(number_text(c) for c in local))
        else:
            limits = {}
            texts = {}
            for key_name, dof in zip(("twist", "limit-xz", "limit-xy"), cone_map):
                if dof is None:
                    v = MISSING_TWIST if key_name == "twist" else MISSING_SWING
                    limits[key_name], texts[key_name] = v, number_text(v)
                else:
                    deg = max(abs(a) for a in HINGES[dof][3])
                    limits[key_name], texts[key_name] = math.radians(deg), degrees_text(deg)
            j.update(limits)
            j["cone_dofs"] = {"twist": cone_map[0], "limit-xz": cone_map[1],
                              "limit-xy": cone_map[2]}
            j["spec"] = "{:type :cone :limit-xz %s :limit-xy %s :twist %s}" % (
                texts["limit-xz"], texts["limit-xy"], texts["twist"])
        out.append(j)
    return out


def number_text(x):
    if x == int(x):
        return str(int(x))
    return repr(float(x))


def degrees_text(deg):
    if deg == 0:
        return "0"
    return "(/ (* %d Math/PI) 180)" % deg


def segment_shapes(joints):
    """{segment: (vertices, faces)} in MuJoCo's world frame."""
    shapes = {}
    for name, bodies in SEGMENTS.items():
        pts = []
        for b in bodies:
            for g in GEOMS[b]:
                pts += geom_points(b, g)
        cuts = [(j["anchor"], j["out"][name]) for j in joints if name in j["segments"]]
        for anchor, out in cuts:
            pts.append(sub(anchor, scale(GAP_HALF, out)))
        vs, fs = hull(pts)
        for anchor, out in cuts:
            vs, fs = clip(vs, fs, anchor, out, GAP_HALF)
        shapes[name] = (vs, fs)
    return shapes


# ------------------------------------------------------- measuring (shared with the check)


def tri_box_overlap(center, h, tri):
    """Does the triangle meet the axis-aligned cube (centre, half-size h)? (Akenine-Moller)"""
    v = [sub(p, center) for p in tri]
    for k in range(3):
        if min(p[k] for p in v) > h or max(p[k] for p in v) < -h:
            return False
    e = [sub(v[1], v[0]), sub(v[2], v[1]), sub(v[0], v[2])]
    n = cross(e[0], e[1])
    if abs(dot(n, v[0])) > h * (abs(n[0]) + abs(n[1]) + abs(n[2])):
        return False
    for k in range(3):
        ak = [1 if i == k else 0 for i in range(3)]
        for ed in e:
            axis = cross(ak, ed)
            if dot(axis, axis) < 1e-30:
                continue
            ps = [dot(axis, p) for p in v]
            rad = h * (abs(axis[0]) + abs(axis[1]) + abs(axis[2]))
            if min(ps) > rad or max(ps) < -rad:
                return False
    return True


def triangles(vs, fs):
    return [(vs[f[0]], vs[f[i]], vs[f[i + 1]]) for f in fs for i in range(1, len(f) - 1)]


def cube_distance(p, tris, hi=10.0, steps=48):
    """Half-size of the smallest cube centred on p that meets the triangles (what
    cortex's growing cube measures), by bisection."""
    def meets(h):
        return any(tri_box_overlap(p, h, t) for t in tris)
    if not meets(hi):
        return float("inf")
    lo = 0.0
    for _ in range(steps):
        mid = (lo + hi) / 2
        if meets(mid):
            hi = mid
        else:
            lo = mid
    return hi


def inside_convex(p, vs, fs):
    """Is p strictly inside the closed convex mesh?"""
    for f in fs:
        a, b, c = vs[f[0]], vs[f[1]], vs[f[2]]
        n = cross(sub(b, a), sub(c, a))
        if dot(n, sub(p, a)) >= 0:
            return False
    return True


def euclid_distance(p, vs, fs):
    tree = BVHTree.FromPolygons([tuple(v) for v in vs], [tuple(f) for f in fs])
    loc, _, _, d = tree.find_nearest(tuple(p))
    return d


def measure(p, shapes):
    """{segment: (cube, euclid, inside)} from point p."""
    out = {}
    for name, (vs, fs) in shapes.items():
        inside = inside_convex(p, vs, fs)
        out[name] = (0.0 if inside else cube_distance(p, triangles(vs, fs)),
                     euclid_distance(p, vs, fs), inside)
    return out


def size_of(vs):
    return max(max(v[k] for v in vs) - min(v[k] for v in vs) for k in range(3))


def tolerance(shapes):
    sizes = sorted(size_of(vs) for vs, _ in shapes.values())
    return 0.1 * sizes[len(sizes) // 2]


def volume_properties(vs, fs):
    """Volume, centroid and inertia tensor per unit density (about the centroid) of a
    closed mesh, from its triangles (signed tetrahedra from the origin)."""
    vol = 0.0
    first = [0.0, 0.0, 0.0]
    second = [[0.0] * 3 for _ in range(3)]
    for a, b, c in triangles(vs, fs):
        d = dot(a, cross(b, c)) / 6.0
        vol += d
        for k in range(3):
            first[k] += d * (a[k] + b[k] + c[k]) / 4.0
        for i in range(3):
            for j in range(3):
                second[i][j] += d / 20.0 * (
                    a[i] * a[j] + b[i] * b[j] + c[i] * c[j]
                    + (a[i] + b[i] + c[i]) * (a[j] + b[j] + c[j]))
    cen = scale(1.0 / vol, first)
    cov = [[second[i][j] - vol * cen[i] * cen[j] for j in range(3)] for i in range(3)]
    tr = cov[0][0] + cov[1][1] + cov[2][2]
    inertia = [[(tr if i == j else 0) - cov[i][j] for j in range(3)] for i in range(3)]
    return vol, cen, inertia


# ------------------------------------------------------- build


def design():
    check_masses()
    joints = joint_design()
    shapes = segment_shapes(joints)
    return joints, shapes


def masses(heavy_hands):
    out = {s: sum(MUJOCO_MASS[b] for b in bodies) for s, bodies in SEGMENTS.items()}
    if heavy_hands:
        for side in ("right", "left"):
            out[side + "_lower_arm"] = HEAVY_HAND_RATIO * out[side + "_upper_arm"]
    return out


def build(joints, shapes, mass):
    empty_file()
    skin = material("skin", SKIN)
    for name in SEGMENTS:
        vs, fs = shapes[name]
        origin = blender(segment_mass_properties(name)[1])
        local = [sub(blender(v), origin) for v in vs]
        segment(name, mesh_from(name, local, fs), origin, mass[name], skin)
    root = joints_root()
    for j in joints:
        joint_empty(j["name"], root, blender(j["anchor"]), j["spec"], rotation=j["rotation"])
    update()


def expected(joints, shapes, mass):
    blender_shapes = {n: ([blender(v) for v in vs], fs) for n, (vs, fs) in shapes.items()}
    tol = tolerance(blender_shapes)
    segs = []
    for name in sorted(SEGMENTS):
        vs, fs = blender_shapes[name]
        m, com, inertia = segment_mass_properties(name)
        vol, cen, unit_inertia = volume_properties(vs, fs)
        mesh_inertia = [[mass[name] / vol * x for x in row] for row in unit_inertia]
        segs.append({
            "name": name, "mass": mass[name], "mujoco_bodies": SEGMENTS[name],
            "origin": vec9(blender(com)),
            "vertices": len(vs), "faces": len(fs),
            "size": r9(size_of(vs)),
            "bounds": [vec9([min(v[k] for v in vs) for k in range(3)]),
                       vec9([max(v[k] for v in vs) for k in range(3)])],
            "volume": r9(vol), "centroid": vec9(cen),
            "mesh_inertia": [vec9(r) for r in mesh_inertia],
            "mesh_principal_inertia": vec9(jacobi_eigenvalues(mesh_inertia)),
            "mujoco": {"mass": r9(m), "com": vec9(blender(com)),
                       "inertia": [vec9(r) for r in inertia],
                       "principal_inertia": vec9(jacobi_eigenvalues(inertia))}})
    js = []
    for j in sorted(joints, key=lambda j: j["name"]):
        p = blender(j["anchor"])
        dist = measure(p, blender_shapes)
        near = sorted((r9(c), r9(e), n, ins) for n, (c, e, ins) in dist.items())
        entry = {"name": j["name"], "parent": "joints", "type": j["type"],
                 "segments": j["segments"], "position": vec9(p),
                 "rotation_euler": vec9(j["rotation"]),
                 "frame_axes": [vec9(c) for c in transpose(j["frame"])],
                 "spec": j["spec"],
                 "order_keys": vec9(j["order_keys"]),
                 "out": {k: vec9(v) for k, v in j["out"].items()},
                 "mujoco": [{"joint": d["joint"], "axis_world": vec9(d["axis_world"]),
                             "range_deg": d["range_deg"]} for d in j["mujoco"]]}
        if j["type"] == "hinge":
            entry["limit"] = vec9(j["limit"])
            entry["axis"] = vec9(j["axis"])
            entry["axis_world"] = vec9(j["axis_world"])
        else:
            for k in ("limit-xz", "limit-xy", "twist"):
                entry[k] = r9(j[k])
            entry["cone_dofs"] = j["cone_dofs"]
        entry["nearest"] = [{"segment": n, "cube": c, "distance": e, "inside": ins}
                            for c, e, n, ins in near[:4]]
        js.append(entry)
    ratios = []
    for j in joints:
        a, b = j["segments"]
        ratios.append(max(mass[a], mass[b]) / min(mass[a], mass[b]))
    return {"segments": segs, "joints": js, "tolerance": r9(tol),
            "total_mass": r9(sum(mass.values())),
            "max_joined_mass_ratio": r9(max(ratios)),
            "lowest_z": r9(min(v[2] for vs, _ in blender_shapes.values() for v in vs))}


NOTES = [
    "Written by scripts/blender/make_humanoid.py from its own numbers (MuJoCo's humanoid.xml "
    "transcribed, low-poly hulls computed in Blender before saving): the .blend files store "
    "float32, so compare with a tolerance (1e-5).",
    "Blender coordinates, Z up, the humanoid faces +X, its left is +Y.  mujoco_z_offset: "
    "Blender z = MuJoCo z + mujoco_z_offset (MuJoCo's initial pose, torso body at z = 1.4, "
    "has its feet 0.10703 above the floor; here they are at z = 0).",
    "segments[].origin: the object's origin = the MuJoCo body's centre of mass (feet merged "
    "into the shins).  mujoco: MuJoCo's mass, centre of mass and inertia tensor about it "
    "(world axes, from the geoms as MuJoCo computes them); mesh_*: the saved mesh's own "
    "volume, centroid and inertia tensor about the centroid at uniform density scaled to "
    "the segment's mass (world axes).",
    "joints[].segments: the two segments in the order cortex puts them (smaller "
    "(1,1,1) . position-in-the-joint-frame of the segment's origin first; order_keys are those "
    "sums): proximal first.  frame_axes: the empty's local X, Y, Z in the world.",
    "Hinges: MuJoCo's axis (axis in the empty's frame, axis_world in the world) and range "
    "(limit, radians; the knees' MuJoCo range [-160, -2] degrees does not include the "
    "straight leg of the initial pose, so the knees start 2 degrees past their upper "
    "limit, as in MuJoCo).  Cones: cone_dofs names the MuJoCo hinge each limit stands "
    "for (null: MuJoCo does not allow that motion: swing 0.1, twist 0); each limit is the "
    "larger magnitude of that hinge's range.",
    "nearest: the four segments nearest to the empty by cube (half-size of the smallest "
    "axis-aligned cube centred on the empty that meets the segment's triangles: what "
    "cortex's growing cube measures), with the Euclidean distance; out: for each of the two "
    "segments, the normal of the plane 0.015 from the anchor that cuts it.",
    "tolerance: a tenth of the median segment size (longest side of the bounds), cortex's "
    "default; every joint's two segments are within it and every other segment is further "
    "than the second nearest plus the tolerance.",
]


def main():
    args = dump.script_args()
    out = os.path.normpath(os.path.abspath(args[0]) if args else os.path.join(
        HERE, "..", "..", "test", "fixtures", "humanoid"))
    os.makedirs(out, exist_ok=True)
    print("Blender", bpy.app.version_string, "->", out)
    joints, shapes = design()
    files = {}
    for name, heavy in (("humanoid", False), ("humanoid-heavy-hands", True)):
        mass = masses(heavy)
        build(joints, shapes, mass)
        save(os.path.join(out, name + ".blend"))
        files[name + ".blend"] = expected(joints, shapes, mass)
    text = compact({"notes": NOTES, "source": "gymnasium/envs/mujoco/assets/humanoid.xml",
                    "mujoco_z_offset": r9(-FOOT_LIFT), "gap_half": GAP_HALF,
                    "files": files}) + "\n"
    path = os.path.join(out, "expected.json")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    print("wrote", path)


if __name__ == "__main__":
    main()
