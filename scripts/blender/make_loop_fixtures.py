"""Make test/fixtures/loops/: Physics-tab creatures whose last constraint
closes a loop, for the export chapter's check that MuJoCo holds each loop
as cortex's engine does (org/export.org, *Loops.*).

    blender -b --factory-startup --python-exit-code 1 --python scripts/blender/make_loop_fixtures.py -- test/fixtures/loops

Writes, in the folder given, NAME.blend and NAME.json (dump_physics.py of
the re-opened file) for each NAME below, made with the helpers of
make_sim_fixtures.py (Blender axes, Z up, a passive box `ground` whose top
is at z = 0).  No Blender oracle: these are compared with MuJoCo, not
with Blender.

four-bar     a four-bar linkage (a drag link) hanging under a passive beam
             `anchor`: `crank` (0.8 m) hangs from the beam at A, `coupler`
             (1.0 m) from the crank's end, `rocker` (0.9 m) from the beam at
             D, 0.5 m from A; every constraint a HINGE about the world's Y
             (the constraint turned 90 degrees about X), no limits, Disable
             Collisions on.  `joint-1` (anchor, crank), `joint-2` (crank,
             coupler), `joint-3` (anchor, rocker) are the tree; `ring`
             (coupler, rocker, at the rocker's end) closes the loop: two
             connects in MJCF.  The crank starts 0.5 rad off the vertical
             (the loop closed there), so the linkage swings.
welded-ring  a square ring of four bars (0.8 m a side), its centre 1 m up,
             tilted so that a corner (0.77 m up) lands first on the ground: each
             corner but the first a GENERIC constraint at the corner,
             turned as the bar it carries, translation locked, every angle
             limited to [-0.3, 0.3]; `ring`, at the first corner (bar-4's
             end, bar-1's start), is FIXED and closes the loop: a weld in
             MJCF.  Disable Collisions on every constraint.
"""

import math
import os
import sys

import bpy
from mathutils import Euler, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_sim_fixtures  # noqa: E402
from make_sim_fixtures import (box, constraint, ground, limit_angles,  # noqa: E402
                               lock_translation, reset)


def link(name, p, q, thick=0.04):
    """A box from p to q (both in the XZ plane), its X along the link."""
    v = q - p
    rot = Vector((1, 0, 0)).rotation_difference(v.normalized()).to_euler()
    return box(name, (v.length / 2 - 0.03, thick, thick), tuple((p + q) / 2), rotation=rot)


def hinge(name, a, b, at):
    # a hinge turns about the constraint's Z: turned 90 degrees about X, -Y
    c = constraint(name, "HINGE", a, b, tuple(at), rotation=(math.pi / 2, 0, 0))
    c.disable_collisions = True
    return c


def four_bar():
    ground()
    anchor = box("anchor", (0.45, 0.1, 0.1), (0.25, 0, 3.1), kind="PASSIVE")
    A, D = Vector((0.0, 0, 3.0)), Vector((0.5, 0, 3.0))
    crank, coupler, rocker = 0.8, 1.0, 0.9
    t = 0.5
    B = A + crank * Vector((math.sin(t), 0, -math.cos(t)))
    # C: coupler from B, rocker from D, the lower of the circles' two crossings
    d = (D - B).length
    along = (coupler ** 2 - rocker ** 2 + d * d) / (2 * d)
    h = math.sqrt(coupler ** 2 - along ** 2)
    u = (D - B).normalized()
    n = Vector((-u.z, 0, u.x))
    C = min((B + along * u + h * n, B + along * u - h * n), key=lambda p: p.z)
    assert abs((C - B).length - coupler) < 1e-5 and abs((C - D).length - rocker) < 1e-5
    b1 = link("crank", A, B)
    b2 = link("coupler", B, C)
    b3 = link("rocker", D, C)
    hinge("joint-1", anchor, b1, A)
    hinge("joint-2", b1, b2, B)
    hinge("joint-3", anchor, b3, D)
    hinge("ring", b2, b3, C)


def welded_ring():
    ground()
    side = 0.8
    tilt = Euler((0.35, 0.25, 0.1)).to_matrix()
    centre = Vector((0, 0, 1.0))
    corners = [centre + tilt @ Vector(p) for p in
               [(-side / 2, -side / 2, 0), (side / 2, -side / 2, 0),
                (side / 2, side / 2, 0), (-side / 2, side / 2, 0)]]
    bars = []
    for i in range(4):
        p, q = corners[i], corners[(i + 1) % 4]
        v = q - p
        rot = Vector((1, 0, 0)).rotation_difference(v.normalized()).to_euler()
        bars.append((box("bar-%d" % (i + 1), (side / 2 - 0.03, 0.04, 0.04), tuple((p + q) / 2),
                         rotation=rot), rot))
    for i in range(1, 4):
        (a, _), (b, rot) = bars[i - 1], bars[i]
        c = constraint("joint-%d" % i, "GENERIC", a, b, tuple(corners[i]), rotation=rot)
        lock_translation(c)
        limit_angles(c, [(-0.3, 0.3)] * 3)
        c.disable_collisions = True
    c = constraint("ring", "FIXED", bars[3][0], bars[0][0], tuple(corners[0]), rotation=bars[0][1])
    c.disable_collisions = True


CASES = [("four-bar", four_bar), ("welded-ring", welded_ring)]


if __name__ == "__main__":
    make_sim_fixtures.main(CASES, "test/fixtures/loops")
