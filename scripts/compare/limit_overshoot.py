#!/usr/bin/env python3
"""How far MuJoCo's own humanoid passes its joint ranges in cortex's drop test.

A Python script, outside cortex's Clojure code (see scripts/compare/README.md
for the venv; without mujoco or gymnasium it says so and exits 0).  It drops
Gymnasium's humanoid.xml as cortex's physics-trust chapter drops its
humanoid: lifted so that its lowest point is 1 m above the floor, at rest,
onto floors of friction 0.25, 0.5 and 1.0 (every geom's: MuJoCo takes
the larger of two), for 10 s, and prints, for each
floor, the largest amount any hinge went past its range (radians, and as a
multiple of the 0.05 rad a hinge may go past in cortex's test), which
hinge, and when.  Twice: at cortex's step (1/60 s, implicitfast, as
humanoid_compare.py runs it) and with the file's own options (RK4 at
0.003 s, the step Gymnasium trains at).

    /work/venvs/compare/bin/python scripts/compare/limit_overshoot.py
"""

import os
import sys

HINGE_ALLOWANCE = 0.05
SECONDS = 10.0


def humanoid_xml():
    try:
        import gymnasium
    except ImportError:
        return None
    p = os.path.join(os.path.dirname(gymnasium.__file__), "envs", "mujoco", "assets", "humanoid.xml")
    return p if os.path.exists(p) else None


def lowest_point(mujoco, m, d):
    """The lowest z of any geom but the floor (capsules and spheres)."""
    low = float("inf")
    for g in range(m.ngeom):
        if m.geom_bodyid[g] == 0:
            continue
        c, size = d.geom_xpos[g], m.geom_size[g]
        if m.geom_type[g] == mujoco.mjtGeom.mjGEOM_CAPSULE:
            axis = d.geom_xmat[g].reshape(3, 3)[:, 2]
            low = min(low, c[2] - abs(axis[2]) * size[1] - size[0])
        else:
            low = min(low, c[2] - size[0])
    return low


def drop(mujoco, xml, friction, step):
    m = mujoco.MjModel.from_xml_path(xml)
    if step is not None:
        m.opt.timestep = step
        m.opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    # MuJoCo takes the larger of two geoms' frictions, so every geom gets it
    for g in range(m.ngeom):
        m.geom_friction[g][0] = friction
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    d.qpos[2] += 1.0 - lowest_point(mujoco, m, d)
    mujoco.mj_forward(m, d)
    hinges = [j for j in range(m.njnt)
              if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE and m.jnt_limited[j]]
    start = {j: 0.0 for j in hinges}
    worst = (0.0, None, 0.0)
    steps = int(round(SECONDS / m.opt.timestep))
    for i in range(steps + 1):
        for j in hinges:
            q = d.qpos[m.jnt_qposadr[j]]
            lo, hi = m.jnt_range[j]
            past = max(0.0, lo - q, q - hi)
            if i == 0:
                start[j] = past
            elif past - start[j] > worst[0]:
                worst = (past - start[j], mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j),
                         i * m.opt.timestep)
        if i < steps:
            mujoco.mj_step(m, d)
    return worst


def main():
    try:
        import mujoco
    except ImportError:
        print("limit_overshoot.py: the mujoco package is not installed (see scripts/compare/README.md)")
        return 0
    xml = humanoid_xml()
    if xml is None:
        print("limit_overshoot.py: gymnasium's humanoid.xml is not installed (see scripts/compare/README.md)")
        return 0
    print("MuJoCo %s, %s" % (mujoco.__version__, xml))
    print("%-28s %8s %9s %9s  %-16s %6s" % ("step", "friction", "past rad", "x 0.05", "hinge", "at s"))
    for label, step in (("1/60 s, implicitfast", 1.0 / 60.0), ("file: RK4, 0.003 s", None)):
        for friction in (0.25, 0.5, 1.0):
            past, joint, t = drop(mujoco, xml, friction, step)
            print("%-28s %8.2f %9.4f %9.2f  %-16s %6.2f" % (label, friction, past, past / HINGE_ALLOWANCE,
                                                           joint or "-", t))
    return 0


if __name__ == "__main__":
    sys.exit(main())
