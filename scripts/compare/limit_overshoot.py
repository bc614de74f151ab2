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
0.003 s, the step Gymnasium trains at); then PyBullet at 1/60 s, the
humanoid built as humanoid_compare.py builds it (its floor's friction is
multiplied with the bodies' 1.0).

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


def drop_pybullet(xml, friction):
    """The same drop in PyBullet, the humanoid built by humanoid_compare.py
    (Featherstone multibody, 1/60 s); friction: the floor's (PyBullet
    multiplies it with the bodies' 1.0)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from humanoid_compare import PybulletRun
    run = PybulletRun("humanoid", xml, 0)
    p, cid, body = run.p, run.cid, run.body
    low = min(p.getAABB(body, link, physicsClientId=cid)[0][2]
              for link in range(-1, p.getNumJoints(body, physicsClientId=cid)))
    pos, orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
    p.resetBasePositionAndOrientation(body, [pos[0], pos[1], pos[2] + 1.0 - low], orn, physicsClientId=cid)
    p.changeDynamics(run.floor, -1, lateralFriction=friction, physicsClientId=cid)
    # PyBullet's links in the order humanoid_compare.py makes them: for each
    # MuJoCo body after the root, one link per hinge (or one fixed link);
    # each hinge's range from MuJoCo's model (the limits were given through
    # changeDynamics, which getJointInfo does not show)
    import mujoco
    m = mujoco.MjModel.from_xml_path(xml)
    limited, index = [], 0
    for b in range(2, m.nbody):
        hinges = [j for j in range(m.body_jntadr[b], m.body_jntadr[b] + m.body_jntnum[b])
                  if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE]
        for j in hinges or [None]:
            if j is not None and m.jnt_limited[j]:
                lo, hi = m.jnt_range[j]
                limited.append((index, mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j), lo, hi))
            index += 1
    if index != p.getNumJoints(body, physicsClientId=cid):
        raise RuntimeError("PyBullet's humanoid has %d links, expected %d"
                           % (p.getNumJoints(body, physicsClientId=cid), index))
    def pasts():
        return {name: max(0.0, lo - p.getJointState(body, j, physicsClientId=cid)[0],
                          p.getJointState(body, j, physicsClientId=cid)[0] - hi)
                for j, name, lo, hi in limited}
    start = pasts()
    worst = (0.0, None, 0.0)
    steps = int(round(SECONDS * 60))
    for i in range(1, steps + 1):
        run.step(1)
        for name, past in pasts().items():
            if past - start[name] > worst[0]:
                worst = (past - start[name], name, i / 60.0)
    run.close()
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
    try:
        import pybullet  # noqa: F401
    except ImportError:
        print("limit_overshoot.py: pybullet is not installed; its rows are left out")
        return 0
    for friction in (0.25, 0.5, 1.0):
        past, joint, t = drop_pybullet(xml, friction)
        print("%-28s %8.2f %9.4f %9.2f  %-16s %6.2f" % ("PyBullet, 1/60 s", friction, past,
                                                       past / HINGE_ALLOWANCE, joint or "-", t))
    return 0


if __name__ == "__main__":
    sys.exit(main())
