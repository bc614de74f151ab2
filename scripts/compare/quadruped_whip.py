#!/usr/bin/env python3
"""A cortex creature's drop in MuJoCo: each body's peak speed (the whipping tail).

A Python script, outside cortex's Clojure code (see scripts/compare/README.md
for the venv; it needs only `mujoco` and numpy, and without them it says so
and exits 0).

    /work/venvs/compare/bin/python scripts/compare/quadruped_whip.py EXPORT.json OUT.json
    ... --frictions 0.25,0.5,1.0   # one drop per friction (the default)
    ... --dt 0.001 --seconds 3     # MuJoCo's step and how long each drop runs

Why: cortex's physics-trust drop test says no body may move faster than
sqrt(2 g H) + 1 m/s, H the drop of the creature's highest point to the floor.
A whipping chain's tip beats that bound honestly (the energy of the heavy
bodies flows into the light tip), and MuJoCo's does too.  This script gives
the reference figure the test compares the four-legged creature (torso,
legs, neck, head and a three-segment tail) with.

What it runs: the creature of EXPORT.json, as cortex exports it (jME axes,
Y up, floor at y = 0; each segment's mass, centre of mass, principal frame
quat [x y z w], principal moments and world vertices; each joint's parent
and child segments, pivot, type and limits, and world axis for hinges),
turned into MuJoCo's Z-up axes (x, y, z) -> (x, -z, y).  The body that is no
joint's child is the root and gets a free joint; nothing is named in the
code, so any tree (a hand, a chain) works.  Every body starts at rest where
the export puts it and falls onto the floor, for each friction: friction on
every geom and the floor (torsional and rolling MuJoCo's defaults),
implicitfast, time step --dt, MuJoCo's other defaults (pyramidal cones,
Newton solver, default contact softness); a body's contacts with its parent
are off (MuJoCo's rule), all other pairs on.  A body's speed is the finite
difference of its centre of mass (xipos) over one step; its peak and the
time at the end of that step are recorded.  Printed: per friction the
fastest body, its peak speed, when, and the test's bound sqrt(2 g H) + 1
with H = 1 + (highest vertex - lowest vertex) of the export (the test drops
the creature with its lowest point 1 m above the floor; g = 9.81).

OUT.json: {"source", "command", "export", "frictions": {"0.25": {"fastest",
"body", "time", "speeds": {body: peak m/s}}, ...}}, numbers rounded to 3
decimals and keys sorted: reruns write the same bytes.

Assumptions:
- joints: hinge -> MuJoCo hinge about the world axis with the export's limit
  [lo, hi]; cone -> ball joint limited to max(limit-xz, limit-xy) (MuJoCo's
  ball limit is one cone angle; the twist limit is not modelled); point ->
  unlimited ball joint.
- bodies: every segment is a box; each geom is the box of its vertices'
  extents in the body's principal frame (the segment itself for a box).
- friction: MuJoCo takes the larger of a contact pair's two frictions,
  Bullet (cortex) their product.  Here the floor's friction is set equal to
  the bodies', so every MuJoCo pair has exactly the friction named (the
  larger of two equal values); in Bullet the same pair would have the
  product of the floor's and the body's coefficients.
"""

import argparse
import json
import math
import os
import shlex
import sys

try:
    import mujoco
    import numpy as np
except ImportError:  # main() says so
    mujoco = np = None

G = 9.81


def cv(p):
    """jME (x, y, z), Y up -> MuJoCo (x, -z, y), Z up."""
    return np.array([p[0], -p[2], p[1]], float)


C = ((1.0, 0, 0), (0, 0, -1), (0, 1, 0))  # the same as a matrix


def quat_matrix(q):
    """Rotation matrix of a jME quaternion [x y z w] (principal -> world)."""
    x, y, z, w = np.asarray(q, float) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def f3(v):
    return " ".join("%.9g" % x for x in v)


def build_xml(export, friction, dt):
    """MJCF of the creature: bodies world-aligned at their centres of mass,
    inertia and box geom turned into each body's principal frame."""
    seg = {s["name"]: s for s in export["segments"]}
    joint_of, children = {}, {}
    for j in export["joints"]:
        parent, child = j["segments"]
        assert child not in joint_of, f"{child} is the child of two joints"
        joint_of[child] = j
        children.setdefault(parent, []).append(child)
    roots = [n for n in seg if n not in joint_of]

    def body(name, parent_com, ind):
        s = seg[name]
        com = cv(s["com"])
        rot_j = quat_matrix(s["quat"])   # principal -> world, jME axes
        rot = np.array(C) @ rot_j        # principal (jME) -> world, MuJoCo axes
        q = np.zeros(4)
        mujoco.mju_mat2Quat(q, rot.flatten())
        local = (np.array(s["vertices"], float) - np.array(s["com"], float)) @ rot_j
        lo, hi = local.min(0), local.max(0)
        out = [f'{ind}<body name="{name}" pos="{f3(com - parent_com)}">']
        j = joint_of.get(name)
        if j is None:
            out.append(f'{ind}  <freejoint name="root-{name}"/>')
        else:
            desc, pos = j["description"], f3(cv(j["pivot"]) - com)
            if desc["type"] == "point":
                out.append(f'{ind}  <joint name="{j["name"]}" type="ball" pos="{pos}"/>')
            elif desc["type"] == "cone":
                r = max(desc["limit-xz"], desc["limit-xy"])
                out.append(f'{ind}  <joint name="{j["name"]}" type="ball" pos="{pos}"'
                           f' limited="true" range="0 {r!r}"/>')
            elif desc["type"] == "hinge":
                lo_h, hi_h = desc["limit"]
                out.append(f'{ind}  <joint name="{j["name"]}" type="hinge" pos="{pos}"'
                           f' axis="{f3(cv(j["world-axis"]))}" limited="true"'
                           f' range="{lo_h!r} {hi_h!r}"/>')
            else:
                raise ValueError(f'joint {j["name"]}: unknown type {desc["type"]}')
        out.append(f'{ind}  <inertial pos="0 0 0" quat="{f3(q)}" mass="{s["mass"]!r}"'
                   f' diaginertia="{f3(s["moments"])}"/>')
        out.append(f'{ind}  <geom name="g-{name}" type="box" pos="{f3(rot @ ((lo + hi) / 2))}"'
                   f' quat="{f3(q)}" size="{f3((hi - lo) / 2)}"/>')
        for ch in children.get(name, []):
            out += body(ch, com, ind + "  ")
        out.append(f"{ind}</body>")
        return out

    lines = []
    for r in roots:
        lines += body(r, np.zeros(3), "    ")
    return f"""<mujoco model="creature">
  <compiler angle="radian"/>
  <option timestep="{dt!r}" integrator="implicitfast" gravity="0 0 {-G}"/>
  <default><geom friction="{friction!r} 0.005 0.0001"/></default>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1"/>
{chr(10).join(lines)}
  </worldbody>
</mujoco>"""


def drop(xml, seconds):
    """Peak finite-difference speed of every body's centre of mass, and when."""
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    dt = m.opt.timestep
    prev = d.xipos.copy()
    peak, when = np.zeros(m.nbody), np.zeros(m.nbody)
    for _ in range(int(round(seconds / dt))):
        mujoco.mj_step(m, d)
        v = np.linalg.norm(d.xipos - prev, axis=1) / dt
        prev[:] = d.xipos
        faster = v > peak
        peak[faster], when[faster] = v[faster], d.time
    return {m.body(b).name: (float(peak[b]), float(when[b])) for b in range(1, m.nbody)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("export")
    ap.add_argument("out")
    ap.add_argument("--frictions", default="0.25,0.5,1.0")
    ap.add_argument("--dt", type=float, default=0.001)
    ap.add_argument("--seconds", type=float, default=3.0)
    a = ap.parse_args()
    if mujoco is None:
        print("quadruped_whip.py needs the mujoco package and numpy (see scripts/compare/README.md); skipped")
        return 0
    export = json.load(open(a.export))
    ys = [v[1] for s in export["segments"] for v in s["vertices"]]
    limit = math.sqrt(2 * G * (1 + max(ys) - min(ys))) + 1
    result = {}
    print(f"{'friction':>8}  {'fastest body':<18} {'peak m/s':>8} {'time s':>7}  {'limit m/s':>9}")
    for f in [float(x) for x in a.frictions.split(",")]:
        res = drop(build_xml(export, f, a.dt), a.seconds)
        body = max(sorted(res), key=lambda n: res[n][0])
        speed, t = res[body]
        print(f"{f:>8g}  {body:<18} {speed:>8.3f} {t:>7.3f}  {limit:>9.3f}")
        result[repr(f)] = {"fastest": round(speed, 3), "body": body, "time": round(t, 3),
                           "speeds": {n: round(v[0], 3) for n, v in res.items()}}
    doc = {"source": f"MuJoCo {mujoco.__version__}, implicitfast, dt {a.dt:g} s, {a.seconds:g} s,"
                     " friction on every geom and the floor, parent-child contacts off",
           "command": shlex.join([sys.executable] + sys.argv),
           "export": os.path.basename(a.export),
           "frictions": result}
    with open(a.out, "w") as fh:
        json.dump(doc, fh, indent=1, sort_keys=True)
        fh.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
