#!/usr/bin/env python3
"""Measure cortex's exported creatures in MuJoCo and PyBullet (org/export.org).

    $CORTEX_PYTHON scripts/export/check_export.py MANIFEST.json OUT.json

A Python script, outside cortex's Clojure code; cortex's test
(cortex.export-test) writes MANIFEST.json, runs this once for every
fixture, and asserts on OUT.json.  The script measures, it does not
judge: every figure it reports is compared with cortex's by the test.

MANIFEST.json: {"fixtures": [{"name", "mjcf" (path), "mjcf_inscribed" (path
or absent), "mjx_seconds" (or absent), "urdf" (path or null),
"seconds" (drop length), "joints": [{"name", "type", "segments": [a, b],
"axis" (hinge: Z-up world), "frame" (cone: 3x3 rows, Z-up world, columns the
engine's axes), "dofs": [{"joint" (MuJoCo joint), "actuator", "range"}]}],
"pairs": [[a, b], ...] (joined segments), "base": {"link", "pos", "quat"
[x y z w]} (where the URDF's root link is), "camera": {"name", "width",
"height"} or null, "tab_limits": [{"name", "type" ("GENERIC"
or "HINGE"), "segments": [a, b], "frame" (3x3 rows, Z-up world: the
constraint's frame, columns its X, Y, Z), "limits": [[lo, hi] or null] x 3
(Bullet's angles)}] or absent, "loops": [{"name", "segments": [a, b],
"points": [[x, y, z], ...] (Z-up world: where the two bodies are held
together), "weld": true or false}] or absent, "track": [seconds, ...] or
absent, "compile_only": true or absent (then only "mujoco", "bodies" and
the URDF's check and masses are measured, and where "mjx_seconds" is
given, "held" and "mjx" that long: nothing else is simulated), "limp_only":
true or absent (then only "mujoco" and the limp "drop" are measured),
"up_body": a segment or absent (the drop also reports its "up")}]}.

OUT.json, by fixture name:
- "mujoco": {"error": text or null, "warnings": [text]}.
- "bodies": {segment: {"mass", "com" (world), "inertia" (3x3 world, about
  the centre of mass)}} as MuJoCo compiled them.
- "drives": one per (hinge degree of freedom, end of its range): gravity
  off, the dof's position servo told to go 1 rad past that end (so it
  pushes at the muscle's strength), the others told to hold 0, contacts
  off, 5 s; then, at the step of the last 2 s where the dof is farthest
  towards that end (where the limit stops it: a pushed joint may bounce
  off its limit, the hand's first finger joints for seconds), the joint's
  angles as cortex reads them, measured from the two bodies'
  orientations (not from MuJoCo's joint coordinates): a hinge's turn of
  its second segment about its axis, a cone's three engine angles (the
  Euler angles of the inverse relative rotation in the engine's frame,
  m^-1 = Rx Ry Rz, see cortex.projection/euler-angles).
- "drop": MuJoCo with a floor at z = 0 (friction 0: MuJoCo takes the larger
  of two, so each geom's own friction rules), actuation off (limp, as
  cortex's creature is when its muscles are sent nothing), "seconds" long,
  read every 1/60 s (cortex's step; MuJoCo's own is the MJCF's): the centre of
  mass height every step, "across": where it is across the floor, [x, y],
  every step, the fastest body speed over the last 0.5 s, and
  "warnings": what MuJoCo warned of while simulating ({warning: times});
  where "up_body" is given, "up": that body's up axis (cortex's y, MuJoCo's
  z) against the world's at the end, 1 upright, 0 on its side.
- "held" (where the fixture asks, "held": true): the same drop with
  actuation on and every control 0, so that each position servo holds
  its joint at 0, the pose as built.
- "held_inscribed" (where the fixture gives "mjcf_inscribed", the same
  creature written with :cone-strength :inscribed): its held drop.
- "mjx" (where the fixture gives "mjx_seconds"): the held drop's first
  "mjx_seconds" in MJX, MuJoCo's JAX port, on the CPU: {"heights", "jax",
  "chain" (the longest chain of rotations), "fusion" (false where that
  chain is too long for XLA's fusion pass, which is then left out)},
  {"error": what mjx.put_model or the compiler said, or where MJX
  diverged, with "heights" until then}, or {"skipped": why}.
- "random" (where the fixture gives "random_seconds"): the limp drop's
  model with actuation on, every control drawn at random within its
  ctrlrange every 1/60 s (a learner's first exploration), three seeds:
  {"unlimited": actuators without a ctrlrange, "runs": [{"warnings",
  "fastest" (the fastest joint speed, rad/s or m/s)}]}.
- "urdf": check_urdf's exit code and output; PyBullet's link masses, and
  their centres of mass and inertias as it loaded them ({link: {"com",
  "inertia"}}, the world's axes, `inertial`); and the
  same drop in PyBullet (1/60 s step in four substeps, floor friction 1:
  Bullet multiplies).
- "tab_limits" (a Physics-tab creature's): the drop again, and over its
  last "seconds" - 1 s how far each angle Bullet limits went past its limit
  ({constraint: [x, y, z]}, radians, 0 within), read from the bodies as
  Bullet reads them: a 6-DOF joint's Euler angles of the inverse relative
  turn of its frames (m^-1 = Rx Ry Rz), a hinge's -(turn of b about Z).
- "loops" (a Physics-tab creature's loops): the drop again, and over all of
  it how far each closing constraint lets its two bodies part: {constraint:
  {"apart": metres, the largest distance between the two bodies' points
  that started at one of its "points", "turn": radians, for a weld the
  largest angle of the two bodies' relative rotation since the start,
  "apart_after_1s", "turn_after_1s": the same over the drop's last
  "seconds" - 1 s}}.
- "track": where each body is (its frame's origin, world) at each of
  "track"'s times, {seconds: {body: [x, y, z]}}, simulated with gravity,
  no floor and actuation off.
- "render": the camera's segmentation (a body name per pixel, "" for
  none) from MuJoCo's renderer (MUJOCO_GL=egl), or {"skipped": why}.
"""

import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
import mujoco


def euler_inverse(m):
    """cortex.projection/euler-angles of the relative rotation matrix m
    already in the engine's frame: angles of m^-1 = Rx Ry Rz."""
    return [math.atan2(-m[2][1], m[2][2]),
            math.asin(max(-1.0, min(1.0, m[2][0]))),
            math.atan2(-m[1][0], m[0][0])]


def hinge_angle(d, axis):
    """The turn of rotation matrix d about the unit axis (quaternion twist)."""
    q = np.zeros(4)
    mujoco.mju_mat2Quat(q, np.asarray(d, float).flatten())
    w, v = q[0], q[1:]
    a = 2 * math.atan2(float(np.dot(v, axis)), w)
    return (a + math.pi) % (2 * math.pi) - math.pi


def relative(m, d, d0, a, b):
    """Rotation of body b relative to body a since the start, in the
    world's rest axes: (Ra Ra0^T)^T (Rb Rb0^T)."""
    ia, ib = m.body(a).id, m.body(b).id
    ra = d.xmat[ia].reshape(3, 3) @ d0[ia].reshape(3, 3).T
    rb = d.xmat[ib].reshape(3, 3) @ d0[ib].reshape(3, 3).T
    return ra.T @ rb


def joint_angles(m, d, x0, j):
    a, b = j["segments"]
    r = relative(m, d, x0, a, b)
    if j["type"] == "hinge":
        return [hinge_angle(r, np.asarray(j["axis"]))]
    g = np.asarray(j["frame"], float)
    return euler_inverse(g.T @ r @ g)


def add_floor(xml_path, friction):
    """A copy of the MJCF beside it with a floor plane at z = 0."""
    text = open(xml_path).read()
    text = text.replace("<worldbody>", '<worldbody>\n    <geom name="floor" type="plane" size="0 0 1"'
                        f' friction="{friction} 0.005 0.0001"/>', 1)
    fd, path = tempfile.mkstemp(suffix=".xml", dir=os.path.dirname(os.path.abspath(xml_path)))
    with os.fdopen(fd, "w") as fh:
        fh.write(text)
    return path


def load_on_floor(path):
    """MuJoCo's model of the MJCF at `path` with `add_floor`'s floor of
    friction 0 (MuJoCo takes the larger of two): (model or None, error)."""
    floored = add_floor(path, 0)
    m, err, _ = load(floored)
    os.remove(floored)
    return m, err


def frames(m, seconds):
    """How `seconds` are read, once per cortex step (1/60 s) however many
    of the model's steps that is: (steps a frame, a frame's length, frames)."""
    sub = max(1, int(round((1 / 60) / m.opt.timestep)))
    frame = sub * m.opt.timestep
    return sub, frame, int(round(seconds / frame))


def com_height(m, xipos):
    """The height of the centre of mass of `m`'s bodies at `xipos`."""
    mass = m.body_mass[1:]
    return float((mass * xipos[1:, 2]).sum() / mass.sum())


def com_across(m, xipos):
    """Where the centre of mass of `m`'s bodies at `xipos` is across the
    floor: [x, y] (Z up)."""
    mass = m.body_mass[1:]
    return [float(v) for v in (mass[:, None] * xipos[1:, :2]).sum(axis=0) / mass.sum()]


def load(path):
    warnings = []
    mujoco.set_mju_user_warning(lambda s: warnings.append(s))
    try:
        return mujoco.MjModel.from_xml_path(path), None, warnings
    except Exception as e:  # what MuJoCo's compiler says
        return None, str(e), warnings


def bodies(m):
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    out = {}
    for i in range(1, m.nbody):
        r = d.ximat[i].reshape(3, 3)
        out[m.body(i).name] = {"mass": float(m.body_mass[i]), "com": d.xipos[i].tolist(),
                               "inertia": (r @ np.diag(m.body_inertia[i]) @ r.T).tolist()}
    return out


def drives(m, fixture):
    out = []
    for j in fixture["joints"]:
        for dof in j["dofs"]:
            if dof.get("actuator") is None:
                continue
            lo, hi = dof["range"]
            for end, target in (("low", lo - 1.0), ("high", hi + 1.0)):
                d = mujoco.MjData(m)
                m.opt.gravity[:] = 0
                # told past its range, beyond its controls' range, so
                # that the servo pushes at the muscle's strength
                m.actuator_ctrllimited[:] = 0
                # the joint alone: no segment may stop another on the way
                m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
                mujoco.mj_forward(m, d)
                x0 = d.xmat.copy()
                d.ctrl[:] = 0
                d.ctrl[m.actuator(dof["actuator"]).id] = target
                adr = m.jnt_qposadr[m.joint(dof["joint"]).id]
                sign = -1 if end == "low" else 1
                best = None
                steps = int(round(5.0 / m.opt.timestep))
                for i in range(steps):
                    mujoco.mj_step(m, d)
                    if i >= steps * 3 // 5 and (best is None or sign * d.qpos[adr] > sign * best[0]):
                        best = (float(d.qpos[adr]), joint_angles(m, d, x0, j))
                out.append({"joint": j["name"], "dof": dof["joint"], "end": end,
                            "qpos": best[0], "angles": best[1]})
    return out


def random_controls(path, seconds, seeds=3):
    """Random controls within each actuator's ctrlrange, redrawn every
    1/60 s for `seconds`, from the creature's pose as written (floor at
    z = 0): MuJoCo's warnings and the fastest joint, per seed."""
    m, _ = load_on_floor(path)
    lo, hi = m.actuator_ctrlrange[:, 0], m.actuator_ctrlrange[:, 1]
    every = max(1, int(round((1.0 / 60) / m.opt.timestep)))
    # the joints' own speeds: every dof but a free joint's
    joints = [int(m.jnt_dofadr[j]) + k for j in range(m.njnt)
            if m.jnt_type[j] != mujoco.mjtJoint.mjJNT_FREE
            for k in range(3 if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_BALL else 1)]
    runs = []
    for seed in range(seeds):
        d = mujoco.MjData(m)
        rng = np.random.default_rng(seed)
        fastest = 0.0
        for i in range(int(round(seconds / m.opt.timestep))):
            if i % every == 0:
                d.ctrl[:] = rng.uniform(lo, hi)
            mujoco.mj_step(m, d)
            if joints:
                fastest = max(fastest, float(np.abs(d.qvel[joints]).max()))
        runs.append({"warnings": sim_warnings(d), "fastest": fastest})
    return {"unlimited": [m.actuator(a).name for a in range(m.nu)
                          if not m.actuator_ctrllimited[a]],
            "runs": runs}


def sim_warnings(d):
    """What MuJoCo warned of while simulating `d` (too many contacts or
    constraints, an unstable step, a bad inertia): {warning: times}."""
    return {mujoco.mjtWarning(i).name: int(d.warning[i].number)
            for i in range(len(d.warning)) if d.warning[i].number > 0}


def run_frames(m, d, seconds):
    """Step `d` for `seconds`, reading it every 1/60 s (see `frames`):
    (the centre of mass's heights, where it is across the floor, the
    fastest body's speeds, a frame's length)."""
    heights, across, speeds = [], [], []
    prev = d.xipos.copy()
    sub, frame, n = frames(m, seconds)
    for i in range(n):
        for _ in range(sub):
            mujoco.mj_step(m, d)
        heights.append(com_height(m, d.xipos))
        across.append(com_across(m, d.xipos))
        speeds.append(float(np.linalg.norm(d.xipos[1:] - prev[1:], axis=1).max() / frame))
        prev[:] = d.xipos
    return heights, across, speeds, frame


def push_sideways(m, d, speed):
    """Add `speed` (m/s) along the world's y to the whole creature: to the
    linear velocity of its root's free joint, which every body below it
    shares."""
    free = [j for j in range(m.njnt) if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
    d.qvel[m.jnt_dofadr[free[0]] + 1] += speed


def mj_drop(path, seconds, held=False, up_body=None, push=None):
    """The drop of the MJCF at `path` for `seconds`: the centre of mass
    height every 1/60 s, the fastest body over the last half second and
    MuJoCo's warnings; with `up_body`, also "up", how far that body's own
    up (cortex's y, MuJoCo's z) points up at the end (1 upright, 0 on
    its side); with `push` ({"at": s, "speed": m/s}), the creature pushed
    sideways (`push_sideways`) that many seconds in."""
    m, err = load_on_floor(path)
    if m is None:
        return {"error": err}
    # cortex's drop sends its muscles no action, and they pull nothing; an
    # exported position servo told nothing (ctrl 0) would hold its joint at
    # 0, so the drop turns actuation off: the creature falls limp in both.
    # Held (cortex's muscles told to hold every hinge and cone at 0), the
    # controls stay 0 and the servos hold the pose as the file has it.
    if not held:
        m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    heights, across, speeds, frame = run_frames(m, d, push["at"] if push else seconds)
    if push:
        push_sideways(m, d, push["speed"])
        more = run_frames(m, d, seconds - push["at"])
        heights, across, speeds = heights + more[0], across + more[1], speeds + more[2]
    out = {"heights": heights, "across": across, "rest_speed": max(speeds[-30:]),
           "step": m.opt.timestep, "frame": frame, "warnings": sim_warnings(d)}
    if up_body:
        out["up"] = float(d.xmat[m.body(up_body).id][8])
    return out


def rotation_chain(m):
    """The longest chain of rotations MJX's kinematics composes one after
    another from the world or a free joint to a body: one per body frame
    and one per hinge or ball joint on the way (a free joint starts
    afresh)."""
    chain = [0] * m.nbody
    for b in range(1, m.nbody):
        types = [int(m.jnt_type[j]) for j in range(m.njnt) if m.jnt_bodyid[j] == b]
        if int(mujoco.mjtJoint.mjJNT_FREE) in types:
            chain[b] = 0
        else:
            chain[b] = chain[m.body_parentid[b]] + 1 + sum(
                t in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_BALL)) for t in types)
    return max(chain)


# On the CPU, XLA's fusion pass takes time that grows steeply with the
# chain (measured with JAX 0.10.2: a chain of 14 compiled in 34 s, the
# rig chain's 21 not within 200 s, and 14 s with the pass off); a chain
# of 11 or less compiles in seconds with it on, and runs faster so.
LONGEST_FUSED_CHAIN = 11


def mjx_held(path, seconds):
    """The held drop (as mj_drop's) in MJX, MuJoCo's JAX port, on the CPU:
    whether mjx.put_model takes the model, and the centre of mass height
    every 1/60 s; "chain" (see rotation_chain) and "fusion" (whether
    XLA's fusion pass compiled it: not for a chain over
    LONGEST_FUSED_CHAIN); {"skipped": why} where MJX or JAX is not
    installed."""
    try:
        from mujoco import mjx
        import jax
    except ImportError as e:
        return {"skipped": f"MJX is not installed ({e})"}
    m, err = load_on_floor(path)
    if m is None:
        return {"error": err}
    try:
        mx = mjx.put_model(m)
    except Exception as e:  # what MJX does not support, by name
        return {"error": str(e)}
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    dx = mjx.put_data(m, d)
    chain = rotation_chain(m)
    fusion = chain <= LONGEST_FUSED_CHAIN
    lowered = jax.jit(mjx.step).lower(mx, dx)
    step = (lowered.compile() if fusion
            else lowered.compile(compiler_options={"xla_disable_hlo_passes": "fusion"}))
    sub, _, n = frames(m, seconds)
    heights = []
    for i in range(n):
        for _ in range(sub):
            dx = step(mx, dx)
        h = com_height(m, np.asarray(dx.xipos))
        if not math.isfinite(h):  # JSON has no NaN: say where it diverged
            return {"error": f"MJX diverged: the centre of mass is {h} after {(i + 1) / 60:.3f} s",
                    "heights": heights}
        heights.append(h)
    return {"heights": heights, "jax": jax.__version__, "chain": chain, "fusion": fusion}


def tab_limits(path, fixture):
    """How far a Physics-tab creature's limited angles pass their limits
    in MuJoCo, dropped onto the floor (see the docstring)."""
    m, err = load_on_floor(path)
    if m is None:
        return {"error": err}
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    x0 = d.xmat.copy()
    cons = fixture["tab_limits"]
    worst = {c["name"]: [0.0, 0.0, 0.0] for c in cons}
    steps = int(round(fixture["seconds"] / m.opt.timestep))
    settle = int(round(1.0 / m.opt.timestep))
    for i in range(steps):
        mujoco.mj_step(m, d)
        if i < settle:
            continue
        for c in cons:
            f = np.asarray(c["frame"], float)
            a, b = c["segments"]
            ia, ib = m.body(a).id, m.body(b).id
            fa = d.xmat[ia].reshape(3, 3) @ x0[ia].reshape(3, 3).T @ f
            fb = d.xmat[ib].reshape(3, 3) @ x0[ib].reshape(3, 3).T @ f
            r = fa.T @ fb
            if c["type"] == "HINGE":
                angles = [0.0, 0.0, -hinge_angle(r, np.array([0.0, 0.0, 1.0]))]
            else:
                angles = euler_inverse(r)
            for k, lim in enumerate(c["limits"]):
                if lim is not None:
                    past = max(lim[0] - angles[k], angles[k] - lim[1], 0.0)
                    worst[c["name"]][k] = max(worst[c["name"]][k], past)
    return worst


def loops(path, fixture):
    """How far each loop's two bodies part in MuJoCo, dropped onto the
    floor (see the docstring)."""
    m, err = load_on_floor(path)
    if m is None:
        return {"error": err}
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    x0 = d.xmat.copy()
    held = []
    for c in fixture["loops"]:
        ia, ib = (m.body(s).id for s in c["segments"])
        # each point in each body's own frame, where the file placed them
        local = [(d.xmat[i].reshape(3, 3).T @ (np.asarray(p, float) - d.xpos[i]))
                 for p in c["points"] for i in (ia, ib)]
        held.append((c, ia, ib, local))
    worst = {c["name"]: {"apart": 0.0, "turn": 0.0, "apart_after_1s": 0.0, "turn_after_1s": 0.0}
             for c in fixture["loops"]}
    settle = int(round(1.0 / m.opt.timestep))
    for i in range(int(round(fixture["seconds"] / m.opt.timestep))):
        mujoco.mj_step(m, d)
        for c, ia, ib, local in held:
            w = worst[c["name"]]
            ra, rb = d.xmat[ia].reshape(3, 3), d.xmat[ib].reshape(3, 3)
            apart = max(float(np.linalg.norm(d.xpos[ia] + ra @ pa - d.xpos[ib] - rb @ pb))
                        for pa, pb in zip(local[0::2], local[1::2]))
            turn = 0.0
            if c["weld"]:
                r = relative(m, d, x0, c["segments"][0], c["segments"][1])
                turn = math.acos(max(-1.0, min(1.0, (np.trace(r) - 1) / 2)))
            for k, v in (("apart", apart), ("turn", turn)):
                w[k] = max(w[k], v)
                if i >= settle:
                    w[k + "_after_1s"] = max(w[k + "_after_1s"], v)
    return worst


def track(path, times):
    """Each body's position at each of `times` (see the docstring)."""
    m, err, _ = load(path)
    if m is None:
        return {"error": err}
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    d = mujoco.MjData(m)
    out = {}
    for t in sorted(times):
        while d.time < t - m.opt.timestep / 2:
            mujoco.mj_step(m, d)
        out[str(t)] = {m.body(i).name: d.xpos[i].tolist() for i in range(1, m.nbody)}
    return out


def link_pose(pb, c, body, i, kinematics=False):
    """Where link `i` of PyBullet's `body` has its centre of mass, and how
    its principal axes are turned: (position, quaternion); the base (-1)
    is posed by its centre of mass. With `kinematics`, the link's pose is
    worked out from the joints first (needed before the first step)."""
    if i == -1:
        return pb.getBasePositionAndOrientation(body, physicsClientId=c)
    return pb.getLinkState(body, i, computeForwardKinematics=int(kinematics), physicsClientId=c)[:2]


def inertial(pb, c, body, i):
    """Link `i` of PyBullet's `body` as loaded, in the world's axes: its
    centre of mass ("com") and its inertia about it ("inertia", 3 x 3),
    turned from the principal axes PyBullet keeps."""
    pos, orn = link_pose(pb, c, body, i, kinematics=True)
    r = np.array(pb.getMatrixFromQuaternion(orn)).reshape(3, 3)
    moments = pb.getDynamicsInfo(body, i, physicsClientId=c)[2]
    return {"com": [float(v) for v in pos], "inertia": (r @ np.diag(moments) @ r.T).tolist()}


def urdf(fixture, drop=True):
    path = fixture["urdf"]
    out = {}
    tool = shutil.which("check_urdf")
    if tool:
        p = subprocess.run([tool, path], capture_output=True, text=True)
        out["check_urdf"] = {"code": p.returncode, "output": p.stdout + p.stderr}
    else:
        out["check_urdf"] = {"skipped": "check_urdf is not installed (Debian: liburdfdom-tools)"}
    import pybullet as pb
    c = pb.connect(pb.DIRECT)
    try:
        pb.setGravity(0, 0, -9.81, physicsClientId=c)
        pb.setTimeStep(1 / 60, physicsClientId=c)
        # PyBullet's multibodies (Featherstone) at cortex's 1/60 s throw the
        # four-legged creature about on landing; four substeps hold it
        pb.setPhysicsEngineParameter(numSubSteps=4, physicsClientId=c)
        base = fixture.get("base", {"pos": [0, 0, 0], "quat": [0, 0, 0, 1]})
        flags = pb.URDF_USE_INERTIA_FROM_FILE | pb.URDF_USE_SELF_COLLISION
        body = pb.loadURDF(path, base["pos"], base["quat"], flags=flags, physicsClientId=c)
        names = {-1: pb.getBodyInfo(body, physicsClientId=c)[0].decode()}
        for i in range(pb.getNumJoints(body, physicsClientId=c)):
            names[i] = pb.getJointInfo(body, i, physicsClientId=c)[12].decode()
        index = {n: i for i, n in names.items()}
        out["masses"] = {n: pb.getDynamicsInfo(body, i, physicsClientId=c)[0] for i, n in names.items()}
        out["inertias"] = {n: inertial(pb, c, body, i) for i, n in names.items()}
        if not drop:
            return out
        for a, b in fixture["pairs"]:
            pb.setCollisionFilterPair(body, body, index[a], index[b], 0, physicsClientId=c)
        # the joints move freely (PyBullet's default velocity motors off)
        for i in range(pb.getNumJoints(body, physicsClientId=c)):
            pb.setJointMotorControl2(body, i, pb.VELOCITY_CONTROL, force=0, physicsClientId=c)
        plane = pb.createCollisionShape(pb.GEOM_PLANE, physicsClientId=c)
        floor = pb.createMultiBody(0, plane, physicsClientId=c)
        pb.changeDynamics(floor, -1, lateralFriction=1.0, physicsClientId=c)
        real = [i for i, n in names.items() if not n.startswith("_")]
        masses = np.array([out["masses"][names[i]] for i in real])

        def coms():
            return np.array([link_pose(pb, c, body, i)[0] for i in real])

        prev = coms()
        heights, across, speeds = [], [], []
        for _ in range(int(round(fixture["seconds"] * 60))):
            pb.stepSimulation(physicsClientId=c)
            p = coms()
            heights.append(float((masses * p[:, 2]).sum() / masses.sum()))
            across.append([float(v) for v in (masses[:, None] * p[:, :2]).sum(axis=0) / masses.sum()])
            speeds.append(float(np.linalg.norm(p - prev, axis=1).max() * 60))
            prev = p
        out["drop"] = {"heights": heights, "across": across, "rest_speed": max(speeds[-30:]),
                       "step": 1 / 60}
    finally:
        pb.disconnect(c)
    return out


def render(m, cam):
    os.environ.setdefault("MUJOCO_GL", "egl")
    try:
        r = mujoco.Renderer(m, cam["height"], cam["width"])
    except Exception as e:
        return {"skipped": f"no GL context for MuJoCo's renderer (MUJOCO_GL={os.environ['MUJOCO_GL']}): {e}"}
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    r.enable_segmentation_rendering()
    r.update_scene(d, camera=cam["name"])
    seg = r.render()
    r.close()
    names = []
    for row in seg:
        line = []
        for objid, objtype in row:
            if objtype == mujoco.mjtObj.mjOBJ_GEOM and objid >= 0:
                line.append(m.body(m.geom_bodyid[objid]).name)
            else:
                line.append("")
        names.append(line)
    return {"labels": names}


def main():
    manifest = json.load(open(sys.argv[1]))
    result = {}
    for f in manifest["fixtures"]:
        r = {}
        m, err, warnings = load(f["mjcf"])
        r["mujoco"] = {"error": err, "warnings": warnings, "version": mujoco.__version__}
        if m is not None and f.get("limp_only"):
            r["drop"] = mj_drop(f["mjcf"], f["seconds"], up_body=f.get("up_body"), push=f.get("push"))
        elif m is not None and f.get("compile_only"):
            r["bodies"] = bodies(m)
            if f.get("mjx_seconds"):
                r["held"] = mj_drop(f["mjcf"], f["mjx_seconds"], held=True)
                r["mjx"] = mjx_held(f["mjcf"], f["mjx_seconds"])
        elif m is not None:
            r["bodies"] = bodies(m)
            r["drives"] = drives(m, f)
            m2, _, _ = load(f["mjcf"])
            r["drop"] = mj_drop(f["mjcf"], f["seconds"])
            if f.get("held"):
                r["held"] = mj_drop(f["mjcf"], f["seconds"], held=True)
            if f.get("mjcf_inscribed"):
                r["held_inscribed"] = mj_drop(f["mjcf_inscribed"], f["seconds"], held=True)
            if f.get("mjx_seconds"):
                r["mjx"] = mjx_held(f["mjcf"], f["mjx_seconds"])
            if f.get("random_seconds"):
                r["random"] = random_controls(f["mjcf"], f["random_seconds"])
            if f.get("track"):
                r["track"] = track(f["mjcf"], f["track"])
            if f.get("tab_limits"):
                r["tab_limits"] = tab_limits(f["mjcf"], f)
            if f.get("loops"):
                r["loops"] = loops(f["mjcf"], f)
            if f.get("camera"):
                r["render"] = render(m2, f["camera"])
        if f.get("urdf"):
            r["urdf"] = urdf(f, drop=not f.get("compile_only"))
        result[f["name"]] = r
    with open(sys.argv[2], "w") as fh:
        json.dump(result, fh)
    return 0


if __name__ == "__main__":
    sys.exit(main())
