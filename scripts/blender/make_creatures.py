"""Build the reference creatures assets/Models/test-creature/{worm,hand,worm-eyes}.blend.

    blender -b --factory-startup --python scripts/blender/make_creatures.py -- [OUTDIR [NAME ...]]

OUTDIR defaults to assets/Models/test-creature in the repo; NAMEs (worm,
hand, worm-eyes) choose which creatures to build, all by default.  Each
.blend is saved uncompressed, and dump.py's JSON is written beside it
(worm.json, hand.json, worm-eyes.json).  Everything is built from numbers in this file; never edit the
.blend files by hand.

Conventions (what the Clojure body code reads):
- every body segment is a MESH object, origin at its centre, with a float
  custom property "mass";
- an EMPTY named "joints" (at the origin, unrotated) is the parent of one
  EMPTY per joint, placed at the middle of the 0.03-unit gap between the two
  segments it connects (0.015 from each; every other segment is >= 0.3 away);
- each joint empty has a string property "joint" with a Clojure map, e.g.
  {:type :hinge :limit [0 (/ Math/PI 2)] :axis (Vector3f. -1 0 0)}.
  The hinge axis is given in the joint empty's own frame (Blender
  coordinates, Z up).  Positive angles rotate the distal segment by the
  right-hand rule about the axis; the limits are chosen so that positive
  angles bend fingers toward the palm side (-Z: the hand lies palm down,
  fingers along +Y, thumb along -X, so it is a right hand); the worm's hinge
  (axis Y) is symmetric, +-pi/4, bending it up and down.
- joint empties are rotated so that, in the joint's own frame, the proximal
  segment (palm side) lies on the negative side of (1,1,1): the thumb joints
  are turned 180 degrees about Z (their X axis then points along the thumb,
  which is the twist axis of the thumb's cone joint).
"""

import math
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402
from make_fixtures import (box_mesh, empty_file, material, mesh_from,  # noqa: E402
                           new_object, save, update)

GAP = 0.03            # space between two jointed segments
HALF_GAP = GAP / 2.0  # joint empty sits in the middle of the gap

HINGE_TEMPLATE = "{:type :hinge :limit [%s %s] :axis (Vector3f. %s)}"


def hinge(low, high, axis):
    return HINGE_TEMPLATE % (low, high, axis)


def chamfered_prism_x(name, half_length, radius, end_radius, chamfer, sides=8):
    """Convex, rounded-ish worm segment along X, centred at the origin.

    Four rings of `sides` vertices: the end caps (radius end_radius) at
    x = +-half_length, the full radius at x = +-(half_length - chamfer).
    A flat side faces -Z so the segment rests flat on a floor.
    """
    rings = [(-half_length, end_radius), (-half_length + chamfer, radius),
             (half_length - chamfer, radius), (half_length, end_radius)]
    verts = []
    for x, r in rings:
        for i in range(sides):
            a = 2.0 * math.pi * (i + 0.5) / sides - math.pi / 2.0
            verts.append((x, r * math.cos(a), r * math.sin(a)))
    faces = []
    for k in range(len(rings) - 1):
        for i in range(sides):
            j = (i + 1) % sides
            faces.append((k * sides + i, k * sides + j, (k + 1) * sides + j, (k + 1) * sides + i))
    faces.append(tuple(reversed(range(sides))))                    # cap at -X
    last = (len(rings) - 1) * sides
    faces.append(tuple(range(last, last + sides)))                  # cap at +X
    return mesh_from(name, verts, faces)   # winding gives outward normals


def joints_root():
    root = new_object("joints", None)
    root.empty_display_type = "PLAIN_AXES"
    return root


def joint_empty(name, root, location, spec, rotation=(0.0, 0.0, 0.0)):
    j = new_object(name, None, parent=root, location=location, rotation=rotation)
    j.empty_display_type = "ARROWS"
    j.empty_display_size = 0.25
    j["joint"] = spec
    return j


def segment(name, mesh, location, mass, mat=None):
    if mat is not None:
        mesh.materials.append(mat)
    obj = new_object(name, mesh, location=location)
    obj["mass"] = float(mass)
    return obj


# ------------------------------------------------------------------ worm

def build_worm():
    empty_file()
    z = 0.5
    half = 1.0
    c = half + HALF_GAP      # segment centres at x = -+1.015
    skin_a = material("worm-skin-1", (0.55, 0.75, 0.35, 1.0))
    skin_b = material("worm-skin-2", (0.45, 0.65, 0.30, 1.0))
    # Different friction on the two ends (a gripping head, a sliding
    # tail): a worm symmetric in everything cannot crawl, since its one
    # hinge pushes both halves alike.  cortex reads "friction" per segment.
    # The segments are half again as wide as they are tall (object scale
    # 1.5 in Y): a round worm rolls over as it arches and crawls by
    # chance; a flat one crawls every time (see org/sim.org).
    head = segment("worm-1", chamfered_prism_x("worm-1", half, 0.3, 0.2, 0.15),
                   (-c, 0.0, z), 1.0, skin_a)
    head["friction"] = 1.0
    head.scale = (1.0, 1.5, 1.0)
    tail = segment("worm-2", chamfered_prism_x("worm-2", half, 0.3, 0.2, 0.15),
                   (c, 0.0, z), 1.0, skin_b)
    tail["friction"] = 0.1
    tail.scale = (1.0, 1.5, 1.0)
    root = joints_root()
    # Bends up/down: axis Y.  With the right-hand rule a positive angle about
    # +Y turns +X toward -Z, so the second segment dips for positive angles.
    joint_empty("worm-joint", root, (0.0, 0.0, z),
                hinge("(- (/ Math/PI 4))", "(/ Math/PI 4)", "0 1 0"))
    update()


# ------------------------------------------------------------- worm-eyes

def build_worm_eyes():
    """The worm with two eyes at the front of its head (worm-1, the end at
    x = -2.015), looking ahead along -X, up +Z, under an empty "eyes":
    `left-eye` a Blender camera (lens 20 mm on a 36 x 24 mm sensor, fit
    AUTO: 83.97 degrees across a 64 x 48 image, clip 0.05 to 50), and
    `right-eye` an empty with an `eye` property.  Each sits 0.035 in front
    of the head's end cap, 2 units from worm-2."""
    build_worm()
    z = 0.55
    root = new_object("eyes", None)
    root.empty_display_type = "PLAIN_AXES"
    ahead = (math.pi / 2, 0.0, math.pi / 2)   # a camera's -Z along world -X, its +Y up
    cam = bpy.data.cameras.new("left-eye")
    cam.lens = 20.0
    cam.sensor_width = 36.0
    cam.sensor_height = 24.0
    cam.sensor_fit = "AUTO"
    cam.clip_start = 0.05
    cam.clip_end = 50.0
    left = new_object("left-eye", cam, parent=root, location=(-2.05, 0.12, z), rotation=ahead)
    left["eye"] = "{:resolution [64 48]}"
    right = new_object("right-eye", None, parent=root, location=(-2.05, -0.12, z), rotation=ahead)
    right.empty_display_type = "CONE"
    right.empty_display_size = 0.1
    right["eye"] = "{:fov 84 :resolution [64 48] :near 0.05 :far 50}"
    update()


# ------------------------------------------------------------------ hand

PALM_HALF = (1.0, 1.0, 0.25)      # palm 2 x 2 x 0.5
HAND_Z = 1.0
FINGERS = [
    # name, x of the finger axis, segment lengths (proximal to distal)
    ("index", -0.75, (0.80, 0.50, 0.40)),
    ("middle", -0.25, (0.90, 0.55, 0.45)),
    ("ring", 0.25, (0.85, 0.50, 0.40)),
    ("pinky", 0.75, (0.65, 0.40, 0.35)),
]
FINGER_HALF_W = 0.19              # 0.38 wide, neighbours 0.12 apart
FINGER_HALF_T = 0.18              # 0.36 thick
FINGER_MASSES = (0.3, 0.2, 0.15)
FINGER_LIMITS = ("(/ Math/PI 2)", "(* 0.6 Math/PI)", "(* 0.45 Math/PI)")  # MCP, PIP, DIP
THUMB_Y = -0.3
THUMB_LENGTHS = (0.60, 0.50, 0.40)
THUMB_HALF_W = 0.21
THUMB_HALF_T = 0.20
THUMB_MASSES = (0.4, 0.3, 0.2)
PALM_MASS = 2.0


def build_hand():
    empty_file()
    skin = material("skin", (0.85, 0.65, 0.55, 1.0))
    nail = material("fingertip", (0.90, 0.55, 0.55, 1.0))
    root = joints_root()

    segment("palm", box_mesh("palm", *PALM_HALF), (0.0, 0.0, HAND_Z), PALM_MASS, skin)

    # Fingers: along +Y from the palm's front face (y = +1).  Palm down, so
    # flexion moves the tips toward -Z: a positive rotation about -X.
    for fname, x, lengths in FINGERS:
        y = PALM_HALF[1]                     # distal face of the previous part
        for k, length in enumerate(lengths):
            n = k + 1
            joint_empty("joint-%s-%d" % (fname, n), root, (x, y + HALF_GAP, HAND_Z),
                        hinge(0, FINGER_LIMITS[k], "-1 0 0"))
            start = y + GAP
            me = box_mesh("%s-%d" % (fname, n), FINGER_HALF_W, length / 2.0, FINGER_HALF_T)
            segment("%s-%d" % (fname, n), me, (x, start + length / 2.0, HAND_Z),
                    FINGER_MASSES[k], nail if n == len(lengths) else skin)
            y = start + length

    # Thumb: sticks out along -X from the palm's left face (x = -1), near
    # the wrist, in a spread-hand rest pose.  Its joint empties are turned
    # 180 degrees about Z: their own +X points along the thumb (the twist
    # axis of the cone joint) and their own +Y is world -Y, so a positive
    # angle about the local +Y axis moves the thumb tip toward -Z (palm side).
    x = -PALM_HALF[0]                        # distal face of the previous part
    turned = (0.0, 0.0, math.pi)
    for k, length in enumerate(THUMB_LENGTHS):
        n = k + 1
        if n == 1:
            spec = "{:type :cone :limit-xz 0.6 :limit-xy 0.6 :twist 0.3}"
        else:
            spec = hinge(0, "(/ Math/PI 2)", "0 1 0")
        joint_empty("joint-thumb-%d" % n, root, (x - HALF_GAP, THUMB_Y, HAND_Z), spec,
                    rotation=turned)
        start = x - GAP
        me = box_mesh("thumb-%d" % n, length / 2.0, THUMB_HALF_W, THUMB_HALF_T)
        segment("thumb-%d" % n, me, (start - length / 2.0, THUMB_Y, HAND_Z),
                THUMB_MASSES[k], nail if n == len(THUMB_LENGTHS) else skin)
        x = start - length
    update()


def main():
    args = dump.script_args()
    out = os.path.abspath(args[0]) if args else os.path.join(
        HERE, "..", "..", "assets", "Models", "test-creature")
    out = os.path.normpath(out)
    os.makedirs(out, exist_ok=True)
    names = args[1:] or ["worm", "hand", "worm-eyes"]
    builders = {"worm": build_worm, "hand": build_hand, "worm-eyes": build_worm_eyes}
    unknown = [n for n in names if n not in builders]
    if unknown:
        sys.exit("no creature called %s; choose from %s" % (unknown, sorted(builders)))
    print("Blender", bpy.app.version_string, "->", out)
    for name in names:
        builders[name]()
        save(os.path.join(out, name + ".blend"))


if __name__ == "__main__":
    main()
