#!/usr/bin/env python3
"""MuJoCo's humanoid and a 100-capsule hinge chain in MuJoCo and PyBullet, side by side.

This is a Python script (not part of cortex's Clojure code).  It needs the
`mujoco`, `pybullet`, `gymnasium` (for its humanoid.xml), `numpy` and `Pillow`
packages; see scripts/compare/README.md for the venv.  Without mujoco or
pybullet it says so and exits 0.

    /work/venvs/compare/bin/python scripts/compare/humanoid_compare.py
    ... --with-cortex         # start cortex on both engines and interleave its runs too
    ... --cortex-json FILE    # add cortex's own numbers (and picture) to the tables
    ... --quick               # 1 run of 200 + 1,000 steps, to try it out
    ... --check-fixture       # only compare test/fixtures/humanoid/expected.json with MuJoCo

What it runs (one thread, the engines interleaved: run 1 of each case, then
run 2 of each, ...; every run starts from a freshly built world):

- humanoid: Gymnasium's humanoid.xml.  MuJoCo: the file as it is (RK4, PGS,
  50 iterations, its joint springs, damping and armature) with the time step
  set to 1/60 s.  PyBullet: the same bodies built with createMultiBody from
  MuJoCo's compiled model (same capsules and spheres, masses, centres of mass,
  inertia tensors, hinge axes, anchors and ranges; one revolute joint per
  MuJoCo hinge, massless links between the hinges of one body, as pybullet's
  own loadMJCF does), MuJoCo's joint damping, no springs or armature
  (PyBullet has none), its default solver (50 iterations), 1/60 s steps,
  default joint motors off.  Both start from MuJoCo's initial pose (torso at
  z = 1.4, feet 0.107 above the floor) at rest and fall onto a floor of
  friction 1.0 (MuJoCo: the file's floor, friction 1; PyBullet multiplies the
  two bodies' coefficients: floor and body both 1.0).  Contacts between a body
  and its parent are off in both, all other pairs on.  Sleeping is off.
- chain: 100 capsules (radius 0.2, 1.0 long, 1 kg: the size of cortex's
  chain-100 boxes) 1.1 apart along X, hinges in the 0.1 gaps about Y and Z
  in turn, limits +-0.5 rad, dropped with the lowest point 1 m above the
  floor.  MuJoCo's default options; PyBullet built from the same model.

Each run: build, 1,000 warm-up steps (the fall), then 10,000 timed steps;
reported: median steps/s of 5 runs, simulated seconds per second (steps/s
/ 60), the ratio to MuJoCo, the largest body speed during the warm-up (finite
differences of the centres of mass), and the final height of the torso's
centre of mass above the floor (chain: the mean height of the segments').
Then it renders the final poses (MuJoCo offscreen through EGL, PyBullet's
TinyRenderer) side by side into a PNG.

With --with-cortex the script starts cortex itself, one JVM per engine
(`bin/lein [with-profile +native] trampoline run -m cortex.compare serve`,
from the repo root; see CortexServer), and asks it for one run at a time, so
that every run of cortex's (test/fixtures/strangers/humanoid.blend, the
humanoid built as MuJoCo's is; test/fixtures/humanoid/humanoid.blend, the
clipped one; the chain of 100 boxes; each with and without observations)
takes its turn after MuJoCo's and PyBullet's of the same case: run 1 of every
row, then run 2, ...  cortex's steps/s are by the wall clock, as here.

Otherwise cortex's side comes from a JSON file (--cortex-json), written by a
Clojure benchmark that runs test/fixtures/humanoid/humanoid.blend the same way:

    {"engine": "cortex (jBullet)",              optional label
     "settings": "10 solver iterations, ...",   optional
     "humanoid": {"steps_per_s": 6200.0, "final_torso_height": 0.21,
                  "max_speed": 5.1},            max_speed optional
     "chain": {"steps_per_s": 1050.0, "final_height": 0.2},   optional
     "image": "out/bench/humanoid-final.png"}   optional: its final pose

Heights are of the torso's centre of mass above the floor (the fixture's
torso origin is MuJoCo's torso centre of mass); the fixture stands with its
feet at z = 0, so MuJoCo's start is the fixture with its floor at
z = -0.10703 (expected.json: mujoco_z_offset).
"""

import argparse
import json
import math
import os
import queue
import statistics
import subprocess
import sys
import threading
import time

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
os.environ.setdefault("MUJOCO_GL", "egl")
os.environ.setdefault("PYOPENGL_PLATFORM", os.environ["MUJOCO_GL"])

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
FIXTURE = os.path.join(REPO, "test", "fixtures", "humanoid", "expected.json")
DT = 1.0 / 60.0
HUMANOID_INTEGRATOR = "implicitfast"


def missing_packages():
    missing = []
    for name in ("mujoco", "pybullet", "numpy"):
        try:
            __import__(name)
        except ImportError:
            missing.append(name)
    return missing


# ------------------------------------------------------------------ models


def humanoid_xml(path=None):
    if path:
        return path
    try:
        import gymnasium
    except ImportError:
        return None
    p = os.path.join(os.path.dirname(gymnasium.__file__), "envs", "mujoco", "assets",
                     "humanoid.xml")
    return p if os.path.exists(p) else None


def chain_xml(n=100, radius=0.2, length=1.0, gap=0.1, limit=0.5, drop=1.0):
    """MJCF of n capsules along X joined by hinges about Y and Z in turn."""
    half = length / 2 - radius
    pitch = length + gap
    lines = ['<mujoco model="chain-%d">' % n,
             '  <compiler angle="radian"/>',
             '  <option timestep="%r"/>' % DT,
             '  <visual><global offwidth="1280" offheight="960"/></visual>',
             '  <asset><texture name="grid" type="2d" builtin="checker" rgb1=".3 .3 .3" '
             'rgb2=".5 .5 .5" width="64" height="64"/>'
             '<material name="grid" texture="grid" texrepeat="100 100"/></asset>',
             '  <worldbody>',
             '    <light directional="true" pos="0 0 10" dir="0 0 -1"/>',
             '    <geom name="floor" type="plane" size="200 200 0.1" friction="1 0.1 0.1" '
             'condim="3" material="grid"/>']
    indent = "    "
    for i in range(n):
        pos = "0 0 %r" % (drop + radius) if i == 0 else "%r 0 0" % pitch
        lines.append('%s<body name="seg-%d" pos="%s">' % (indent, i, pos))
        if i == 0:
            lines.append('%s  <freejoint name="root"/>' % indent)
        else:
            axis = "0 1 0" if i % 2 else "0 0 1"
            lines.append('%s  <joint name="joint-%d" type="hinge" pos="%r 0 0" axis="%s" '
                         'limited="true" range="%r %r"/>' % (indent, i, -pitch / 2, axis,
                                                             -limit, limit))
        lines.append('%s  <geom type="capsule" fromto="%r 0 0 %r 0 0" size="%r" mass="1" '
                     'rgba="0.8 0.6 0.4 1"/>' % (indent, -half, half, radius))
        indent += "  "
    for i in range(n):
        indent = indent[:-2]
        lines.append("%s</body>" % indent)
    lines += ["  </worldbody>", "</mujoco>"]
    return "\n".join(lines) + "\n"


def load_mujoco(case, xml_path, chain_n, integrator=None):
    """The model at 1/60 s; the humanoid with MuJoCo's implicitfast integrator unless
    `integrator` says otherwise ("file": keep the file's RK4)."""
    import mujoco
    if case == "humanoid":
        m = mujoco.MjModel.from_xml_path(xml_path)
        integrator = integrator or HUMANOID_INTEGRATOR
    else:
        m = mujoco.MjModel.from_xml_string(chain_xml(chain_n))
    if integrator and integrator != "file":
        m.opt.integrator = getattr(mujoco.mjtIntegrator, "mjINT_" + integrator.upper())
    m.opt.timestep = DT
    m.opt.enableflags &= ~int(mujoco.mjtEnableBit.mjENBL_SLEEP)     # sleeping off
    floor = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "floor")
    m.geom_friction[floor][0] = 1.0
    m.vis.global_.offwidth = max(m.vis.global_.offwidth, 1280)
    m.vis.global_.offheight = max(m.vis.global_.offheight, 960)
    return m


# ------------------------------------------------------------------ MuJoCo


def mujoco_settings(m):
    import mujoco
    return "%s, %s, %d iterations, dt 1/60, sleep off" % (
        mujoco.mjtIntegrator(m.opt.integrator).name[len("mjINT_"):],
        mujoco.mjtSolver(m.opt.solver).name[len("mjSOL_"):], m.opt.iterations)


class MujocoRun:
    engine = "MuJoCo"

    def __init__(self, case, xml_path, chain_n, integrator=None):
        import mujoco
        self.mujoco = mujoco
        self.case = case
        self.m = load_mujoco(case, xml_path, chain_n, integrator)
        self.d = mujoco.MjData(self.m)
        mujoco.mj_forward(self.m, self.d)
        self.settings = mujoco_settings(self.m)
        self.bodies = list(range(1, self.m.nbody))
        self.torso = mujoco.mj_name2id(self.m, mujoco.mjtObj.mjOBJ_BODY,
                                       "torso" if case == "humanoid" else "seg-0")

    def coms(self):
        return self.d.xipos[1:].copy()

    def step(self, n):
        mj_step, m, d = self.mujoco.mj_step, self.m, self.d
        for _ in range(n):
            mj_step(m, d)

    def torso_height(self):
        return float(self.d.xipos[self.torso][2])

    def diverged(self):
        """When MuJoCo first found NaN or huge accelerations (it then resets the state)."""
        W = self.mujoco.mjtWarning
        return any(self.d.warning[w].number for w in (W.mjWARN_BADQPOS, W.mjWARN_BADQVEL,
                                                       W.mjWARN_BADQACC))

    def close(self):
        pass


# ------------------------------------------------------------------ PyBullet


def quat_xyzw(q):
    return [float(q[1]), float(q[2]), float(q[3]), float(q[0])]


def rotate(q, v):
    """Rotate v by the unit quaternion q (w, x, y, z)."""
    import numpy as np
    w, x, y, z = q
    u = np.array([x, y, z])
    v = np.asarray(v, dtype=float)
    return v + 2 * np.cross(u, np.cross(u, v) + w * v)


class PybulletRun:
    """The MuJoCo model built again in PyBullet with createMultiBody."""
    engine = "PyBullet"

    def __init__(self, case, xml_path, chain_n, joint_damping=False):
        import numpy as np
        import pybullet as p
        import mujoco
        self.p = p
        self.case = case
        m = load_mujoco(case, xml_path, chain_n)
        self.cid = p.connect(p.DIRECT)
        cid = self.cid
        p.setGravity(*[float(g) for g in m.opt.gravity], physicsClientId=cid)
        p.setPhysicsEngineParameter(fixedTimeStep=DT, numSubSteps=0, physicsClientId=cid)
        floor_shape = p.createCollisionShape(p.GEOM_PLANE, physicsClientId=cid)
        floor_visual = p.createVisualShape(p.GEOM_BOX, halfExtents=[300, 300, 0.001],
                                           visualFramePosition=[0, 0, -0.001],
                                           rgbaColor=[0.55, 0.6, 0.55, 1], physicsClientId=cid)
        self.floor = p.createMultiBody(0, floor_shape, floor_visual, physicsClientId=cid)

        def shapes(b, offset):
            """Collision and visual shapes of MuJoCo body b, relative to its link frame."""
            kinds, radii, lengths, poss, orns, colors = [], [], [], [], [], []
            for g in range(m.body_geomadr[b], m.body_geomadr[b] + m.body_geomnum[b]):
                t = m.geom_type[g]
                if t == mujoco.mjtGeom.mjGEOM_SPHERE:
                    kinds.append(p.GEOM_SPHERE)
                    lengths.append(0.0)
                elif t == mujoco.mjtGeom.mjGEOM_CAPSULE:
                    kinds.append(p.GEOM_CAPSULE)
                    lengths.append(float(2 * m.geom_size[g][1]))
                else:
                    raise ValueError("geom type %d not handled" % t)
                radii.append(float(m.geom_size[g][0]))
                poss.append([float(x) for x in m.geom_pos[g] - offset])
                orns.append(quat_xyzw(m.geom_quat[g]))
                colors.append([float(x) for x in m.geom_rgba[g]])
            if not kinds:
                return -1, -1
            col = p.createCollisionShapeArray(kinds, radii=radii, lengths=lengths,
                                              collisionFramePositions=poss,
                                              collisionFrameOrientations=orns,
                                              physicsClientId=cid)
            vis = p.createVisualShapeArray(kinds, radii=radii, lengths=lengths,
                                           visualFramePositions=poss,
                                           visualFrameOrientations=orns,
                                           rgbaColors=colors, physicsClientId=cid)
            return col, vis

        def anchor(b):
            """Where body b's joints are, in its frame (they must share one point)."""
            js = range(m.body_jntadr[b], m.body_jntadr[b] + m.body_jntnum[b])
            pos = [m.jnt_pos[j] for j in js if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE]
            for q in pos[1:]:
                assert np.allclose(q, pos[0]), "hinges of one body at different points"
            return np.array(pos[0]) if pos else np.zeros(3)

        root = 1
        assert m.body_jntnum[root] == 1 and m.jnt_type[m.body_jntadr[root]] == mujoco.mjtJoint.mjJNT_FREE
        base_col, base_vis = shapes(root, np.zeros(3))
        link = {}          # MuJoCo body -> index of its mass-carrying link
        masses, cols, viss, poss, orns, ipos, iorn, parents, types, axes = ([] for _ in range(10))
        limits, damping, inertias = [], [], []
        for b in range(2, m.nbody):
            par = m.body_parentid[b]
            a_b, a_p = anchor(b), (anchor(par) if par != root else np.zeros(3))
            parent_link = -1 if par == root else link[par]
            first = np.array(m.body_pos[b]) + rotate(m.body_quat[b], a_b) - a_p
            hinges = [j for j in range(m.body_jntadr[b], m.body_jntadr[b] + m.body_jntnum[b])
                      if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE]
            steps = hinges if hinges else [None]
            for k, j in enumerate(steps):
                last = k == len(steps) - 1
                col, vis = shapes(b, a_b) if last else (-1, -1)
                masses.append(float(m.body_mass[b]) if last else 0.0)
                cols.append(col)
                viss.append(vis)
                poss.append([float(x) for x in first] if k == 0 else [0.0, 0.0, 0.0])
                orns.append(quat_xyzw(m.body_quat[b]) if k == 0 else [0, 0, 0, 1])
                ipos.append([float(x) for x in m.body_ipos[b] - a_b] if last else [0, 0, 0])
                iorn.append(quat_xyzw(m.body_iquat[b]) if last else [0, 0, 0, 1])
                parents.append(parent_link + 1)          # createMultiBody counts the base as 0
                types.append(p.JOINT_REVOLUTE if j is not None else p.JOINT_FIXED)
                axes.append([float(x) for x in m.jnt_axis[j]] if j is not None else [0, 0, 1])
                limits.append(tuple(float(x) for x in m.jnt_range[j])
                              if j is not None and m.jnt_limited[j] else None)
                damping.append(float(m.dof_damping[m.jnt_dofadr[j]]) if j is not None else 0.0)
                inertias.append([float(x) for x in m.body_inertia[b]] if last else None)
                parent_link = len(masses) - 1
            link[b] = len(masses) - 1
        self.body_links = [-1] + [link[b] for b in range(2, m.nbody)]
        base_pos = m.body_pos[root]
        self.body = p.createMultiBody(
            baseMass=float(m.body_mass[root]), baseCollisionShapeIndex=base_col,
            baseVisualShapeIndex=base_vis, basePosition=[float(x) for x in base_pos],
            baseOrientation=quat_xyzw(m.body_quat[root]),
            baseInertialFramePosition=[float(x) for x in m.body_ipos[root]],
            baseInertialFrameOrientation=quat_xyzw(m.body_iquat[root]),
            linkMasses=masses, linkCollisionShapeIndices=cols, linkVisualShapeIndices=viss,
            linkPositions=poss, linkOrientations=orns, linkInertialFramePositions=ipos,
            linkInertialFrameOrientations=iorn, linkParentIndices=parents,
            linkJointTypes=types, linkJointAxis=axes, flags=p.URDF_USE_SELF_COLLISION,
            physicsClientId=cid)
        body = self.body
        p.changeDynamics(body, -1, localInertiaDiagonal=[float(x) for x in m.body_inertia[root]],
                         lateralFriction=1.0, restitution=0.0,
                         activationState=p.ACTIVATION_STATE_DISABLE_SLEEPING,
                         physicsClientId=cid)
        p.changeDynamics(self.floor, -1, lateralFriction=1.0, restitution=0.0,
                         physicsClientId=cid)
        revolute = []
        for i in range(len(masses)):
            kw = {"lateralFriction": 1.0, "restitution": 0.0,
                  "jointDamping": damping[i] if joint_damping else 0.0}
            if inertias[i] is not None:
                kw["localInertiaDiagonal"] = inertias[i]
            if limits[i] is not None:
                kw["jointLowerLimit"], kw["jointUpperLimit"] = limits[i]
            p.changeDynamics(body, i, physicsClientId=cid, **kw)
            if types[i] == p.JOINT_REVOLUTE:
                revolute.append(i)
        p.setJointMotorControlArray(body, revolute, p.VELOCITY_CONTROL,
                                    forces=[0.0] * len(revolute), physicsClientId=cid)
        # contacts: every pair of MuJoCo bodies except parent and child (MuJoCo's filterparent)
        for b in range(2, m.nbody):
            par = m.body_parentid[b]
            pl = -1 if par == root else link[par]
            p.setCollisionFilterPair(body, body, link[b], pl, 0, physicsClientId=cid)
        self.solver_iterations = p.getPhysicsEngineParameters(physicsClientId=cid)[
            "numSolverIterations"]
        self.settings = "Featherstone multibody, %d iterations, dt 1/60, sleep off%s" % (
            self.solver_iterations, "" if joint_damping or not any(damping) else
            ", no joint damping")

    def coms(self):
        import numpy as np
        p, cid = self.p, self.cid
        out = [p.getBasePositionAndOrientation(self.body, physicsClientId=cid)[0]]
        states = p.getLinkStates(self.body, self.body_links[1:], physicsClientId=cid)
        out += [s[0] for s in states]
        return np.array(out)

    def step(self, n):
        step, cid = self.p.stepSimulation, self.cid
        for _ in range(n):
            step(physicsClientId=cid)

    def torso_height(self):
        return float(self.p.getBasePositionAndOrientation(self.body, physicsClientId=self.cid)[0][2])

    def close(self):
        self.p.disconnect(physicsClientId=self.cid)


# ------------------------------------------------------------------ running


# ------------------------------------------------------------------ cortex


CORTEX_COMMANDS = {
    "jbullet": ["bin/lein", "trampoline", "run", "-m", "cortex.compare", "serve"],
    "native": ["bin/lein", "with-profile", "+native", "trampoline", "run", "-m",
               "cortex.compare", "serve"],
}
# per case of this script: (cortex.compare/serve-cases name, label)
CORTEX_CASES = {"humanoid": [("humanoid-mujoco", "MuJoCo-shaped"), ("humanoid-clipped", "clipped")],
                "chain": [("chain-100", "chain of boxes")]}
CORTEX_OBSERVE = [("off", ""), ("observed", " +obs")]


class CortexServer:
    """One cortex JVM (`lein trampoline run -m cortex.compare serve`, from the repo root)
    that does one run at a time when asked on its standard input, so that its runs
    interleave with MuJoCo's and PyBullet's.  Its other output goes to a log."""

    def __init__(self, which, log_dir):
        os.makedirs(log_dir, exist_ok=True)
        self.which = which
        self.log_path = os.path.join(log_dir, "cortex-%s.log" % which)
        self.log = open(self.log_path, "w")
        self.proc = subprocess.Popen(CORTEX_COMMANDS[which], cwd=REPO, stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=self.log, text=True,
                                     bufsize=1)
        self.answers = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()
        self.hello = None

    def _read(self):
        for line in self.proc.stdout:
            if line.startswith("@@ "):
                try:
                    self.answers.put(json.loads(line[3:]))
                except ValueError:
                    self.answers.put({"error": "unreadable answer: " + line.strip()})
            else:
                self.log.write(line)
                self.log.flush()
        self.answers.put(None)

    def _answer(self, timeout):
        try:
            a = self.answers.get(timeout=timeout)
        except queue.Empty:
            raise RuntimeError("cortex (%s) gave no answer in %d s; see %s" % (
                self.which, timeout, self.log_path))
        if a is None:
            raise RuntimeError("cortex (%s) stopped; see %s" % (self.which, self.log_path))
        if "error" in a:
            raise RuntimeError("cortex (%s): %s" % (self.which, a["error"]))
        return a

    def ready(self, timeout=1200):
        self.hello = self._answer(timeout)
        return self.hello

    def ask(self, line, timeout=1800):
        self.proc.stdin.write(line + "\n")
        self.proc.stdin.flush()
        return self._answer(timeout)

    @property
    def engine(self):
        return "cortex " + (self.hello or {}).get("engine", self.which)

    def close(self):
        try:
            self.proc.stdin.write("quit\n")
            self.proc.stdin.flush()
            self.proc.wait(60)
        except Exception:
            self.proc.kill()
            self.proc.wait()
        self.log.close()


def cortex_run(server, case, observe, args):
    r = server.ask("run %s %s %d %d" % (case, observe, args.warmup, args.steps))
    return {"steps_per_s": r["steps_per_s"], "cpu_steps_per_s": r["cpu_steps_per_s"],
            "max_speed": r["max_speed"], "final_height": r["final_height"]}


def run_once(cls, case, args):
    """Build, warm up (tracking speeds), time; return the numbers and the live run."""
    import numpy as np
    sim = cls(case, args.xml, args.chain_segments)
    start_top = float(sim.coms()[:, 2].max())
    prev = sim.coms()
    top_speed = 0.0
    for _ in range(args.warmup):
        sim.step(1)
        now = sim.coms()
        top_speed = max(top_speed, float(np.max(np.linalg.norm(now - prev, axis=1))) / DT)
        prev = now
    t0 = time.perf_counter()
    sim.step(args.steps)
    elapsed = time.perf_counter() - t0
    before = sim.coms()
    sim.step(1)
    end_speed = float(np.max(np.linalg.norm(sim.coms() - before, axis=1))) / DT
    coms = sim.coms()
    height = sim.torso_height() if case == "humanoid" else float(np.mean(coms[:, 2]))
    return {"steps_per_s": args.steps / elapsed, "max_speed": top_speed, "end_speed": end_speed,
            "final_height": height, "start_top": start_top,
            "final_top": float(coms[:, 2].max())}, sim


def render_mujoco(sim, target, eye, size):
    import mujoco
    w, h = size
    r = mujoco.Renderer(sim.m, h, w)
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    f = [t - e for t, e in zip(target, eye)]
    dist = math.sqrt(sum(x * x for x in f))
    cam.lookat[:] = target
    cam.distance = dist
    cam.azimuth = math.degrees(math.atan2(f[1], f[0]))
    cam.elevation = math.degrees(math.asin(f[2] / dist))
    r.update_scene(sim.d, camera=cam)
    img = r.render()
    r.close()
    return img


def render_pybullet(sim, target, eye, size):
    import numpy as np
    p = sim.p
    w, h = size
    view = p.computeViewMatrix(eye, target, [0, 0, 1], physicsClientId=sim.cid)
    proj = p.computeProjectionMatrixFOV(45, w / h, 0.05, 500, physicsClientId=sim.cid)
    _, _, rgba, _, _ = p.getCameraImage(w, h, view, proj, renderer=p.ER_TINY_RENDERER,
                                        lightDirection=[0.4, -0.3, 1], shadow=0,
                                        physicsClientId=sim.cid)
    return np.reshape(np.array(rgba, dtype=np.uint8), (h, w, 4))[:, :, :3]


def camera_for(sim, case):
    """The same camera for both engines: beside the final pose, looking at it."""
    coms = sim.coms()
    if case == "humanoid":
        c = coms.mean(axis=0)
        t = [float(c[0]), float(c[1]), 0.15]
        return t, [t[0] + 0.9, t[1] - 2.0, 1.1]
    lo, hi = coms.min(axis=0), coms.max(axis=0)
    t = [float((lo[0] + hi[0]) / 2), float((lo[1] + hi[1]) / 2), 0.0]
    span = float(max(hi[0] - lo[0], hi[1] - lo[1], 5.0))
    return t, [t[0], t[1] - 0.6 * span, 0.9 * span]


def compose(panels, path):
    """panels: [(title, lines, HxWx3 array or PIL image or None)] side by side."""
    from PIL import Image, ImageDraw, ImageFont, ImageOps
    font = ImageFont.load_default()
    w, h = 480, 360
    bar = 44
    out = Image.new("RGB", (w * len(panels), h + bar), (255, 255, 255))
    draw = ImageDraw.Draw(out)
    for i, (title, lines, img) in enumerate(panels):
        if img is not None:
            im = img if isinstance(img, Image.Image) else Image.fromarray(img)
            out.paste(ImageOps.pad(im.convert("RGB"), (w, h), color=(230, 230, 230)),
                      (i * w, bar))
        else:
            draw.rectangle([i * w, bar, (i + 1) * w - 1, bar + h - 1], fill=(230, 230, 230))
        draw.text((i * w + 8, 4), title, fill=(0, 0, 0), font=font)
        for k, line in enumerate(lines):
            draw.text((i * w + 8, 18 + 12 * k), line, fill=(60, 60, 60), font=font)
    out.save(path)
    return out


def stacked(rows, path):
    from PIL import Image
    w = max(r.size[0] for r in rows)
    out = Image.new("RGB", (w, sum(r.size[1] for r in rows)), (255, 255, 255))
    y = 0
    for r in rows:
        out.paste(r, (0, y))
        y += r.size[1]
    out.save(path)


# ------------------------------------------------------------------ fixture check


def check_fixture(xml_path, path=FIXTURE):
    """Compare the Blender fixture's expected.json with MuJoCo's compiled humanoid."""
    import numpy as np
    import mujoco
    with open(path) as f:
        exp = json.load(f)
    m = mujoco.MjModel.from_xml_path(xml_path)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    problems = []
    feet = [g for g in range(m.ngeom) if m.geom(g).name in ("right_foot", "left_foot")]
    lift = min(d.geom_xpos[g][2] - m.geom_size[g][0] for g in feet)
    off = np.array([0, 0, -lift])
    if abs(exp["mujoco_z_offset"] + lift) > 1e-6:
        problems.append("z offset %s, MuJoCo's feet %s above the floor" % (exp["mujoco_z_offset"], lift))
    fx = exp["files"]["humanoid.blend"]
    for s in fx["segments"]:
        ids = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, b) for b in s["mujoco_bodies"]]
        mass = sum(m.body_mass[i] for i in ids)
        com = sum(m.body_mass[i] * d.xipos[i] for i in ids) / mass
        inertia = np.zeros((3, 3))
        for i in ids:
            r = d.ximat[i].reshape(3, 3)
            dv = d.xipos[i] - com
            inertia += r @ np.diag(m.body_inertia[i]) @ r.T + m.body_mass[i] * (
                dv @ dv * np.eye(3) - np.outer(dv, dv))
        if abs(mass - s["mass"]) > 1e-9 or abs(mass - s["mujoco"]["mass"]) > 1e-6:
            problems.append("%s: mass %r, MuJoCo %r" % (s["name"], s["mass"], mass))
        if not np.allclose(com + off, s["origin"], atol=1e-6):
            problems.append("%s: origin %s, MuJoCo's centre of mass %s" % (s["name"], s["origin"], com + off))
        if not np.allclose(inertia, s["mujoco"]["inertia"], atol=1e-6):
            problems.append("%s: inertia differs from MuJoCo's" % s["name"])
    seen = set()
    for j in fx["joints"]:
        for dof in j["mujoco"]:
            jid = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, dof["joint"])
            seen.add(dof["joint"])
            if not np.allclose(d.xanchor[jid] + off, j["position"], atol=1e-6):
                problems.append("%s: %s anchor %s" % (j["name"], dof["joint"], d.xanchor[jid] + off))
            if not np.allclose(d.xaxis[jid], dof["axis_world"], atol=1e-6):
                problems.append("%s: %s axis %s" % (j["name"], dof["joint"], d.xaxis[jid]))
            if not np.allclose(np.degrees(m.jnt_range[jid]), dof["range_deg"], atol=1e-9):
                problems.append("%s: %s range" % (j["name"], dof["joint"]))
    hinges = {m.joint(i).name for i in range(m.njnt) if m.jnt_type[i] == mujoco.mjtJoint.mjJNT_HINGE}
    if seen != hinges:
        problems.append("MuJoCo hinges not in the fixture: %s" % sorted(hinges - seen))
    return problems


# ------------------------------------------------------------------ table


def fmt_row(cols, widths):
    return "  ".join(str(c).ljust(w) if i == 0 else str(c).rjust(w)
                     for i, (c, w) in enumerate(zip(cols, widths)))


def table(case, rows):
    head = ["engine", "steps/s", "sim s/s", "x MuJoCo", "max speed", "end speed",
            "torso height" if case == "humanoid" else "mean height", "settings"]
    widths = [40, 9, 8, 8, 9, 9, 12, 0]
    ref = next((r["steps_per_s"] for r in rows if r["engine"] == "MuJoCo"), None)
    lines = [fmt_row(head, widths), fmt_row(["-" * w for w in widths[:-1]] + ["-" * 8], widths)]

    def num(x, f):
        return "-" if x is None else f % x
    for r in rows:
        sps = r.get("steps_per_s")
        lines.append(fmt_row([
            r["engine"], num(sps, "%.0f"), num(sps and sps * DT, "%.1f"),
            num(sps / ref if sps and ref else None, "%.3f"), num(r.get("max_speed"), "%.2f"),
            num(r.get("end_speed"), "%.3f"), num(r.get("final_height"), "%.3f"),
            r.get("settings", "")], widths))
    return "\n".join(lines)


def summarise(results):
    """Median steps/s, and the last run's heights and speeds."""
    out = dict(results[-1])
    out["steps_per_s"] = statistics.median(r["steps_per_s"] for r in results)
    out["runs_steps_per_s"] = [round(r["steps_per_s"], 1) for r in results]
    out["max_speed"] = max(r["max_speed"] for r in results)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--xml", help="humanoid.xml (default: Gymnasium's)")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--warmup", type=int, default=1000)
    ap.add_argument("--steps", type=int, default=10000)
    ap.add_argument("--chain-segments", type=int, default=100)
    ap.add_argument("--no-chain", action="store_true", help="only the humanoid")
    ap.add_argument("--quick", action="store_true", help="1 run, 200 warm-up, 1,000 timed steps")
    ap.add_argument("--cortex-json", action="append", default=[],
                    help="cortex's numbers (see the docstring for the format); give it once "
                         "per engine to put both in the tables")
    ap.add_argument("--with-cortex", action="store_true",
                    help="start cortex's JVMs (bin/lein trampoline run -m cortex.compare serve, "
                         "on jBullet and with +native) and interleave their runs with the others")
    ap.add_argument("--cortex-engines", default="jbullet,native",
                    help="with --with-cortex: which of jbullet,native (default both)")
    ap.add_argument("--out", default=os.path.join(REPO, "out", "compare"),
                    help="folder for humanoid_compare.png and .json (default out/compare)")
    ap.add_argument("--check-fixture", action="store_true",
                    help="only compare test/fixtures/humanoid/expected.json with MuJoCo")
    args = ap.parse_args()
    if args.quick:
        args.runs, args.warmup, args.steps = 1, 200, 1000

    missing = missing_packages()
    if missing:
        print("humanoid_compare.py is a Python script that needs %s: not importable here, "
              "so nothing was compared. See scripts/compare/README.md for the venv."
              % " and ".join(missing))
        return 0
    args.xml = humanoid_xml(args.xml)
    if args.xml is None:
        print("humanoid_compare.py needs Gymnasium's humanoid.xml: install gymnasium or "
              "give --xml; nothing was compared.")
        return 0
    import mujoco

    fixture_problems = check_fixture(args.xml) if os.path.exists(FIXTURE) else None
    if args.check_fixture:
        if fixture_problems is None:
            print("no fixture at %s" % FIXTURE)
            return 1
        for pr in fixture_problems:
            print("fixture differs from MuJoCo:", pr)
        print("fixture %s MuJoCo's humanoid" % ("differs from" if fixture_problems else
                                               "agrees with"))
        return 1 if fixture_problems else 0

    servers = []
    if args.with_cortex:
        # started one after the other (their first start compiles classes), before the
        # timed runs; each then idles on its standard input between runs
        for which in [w.strip() for w in args.cortex_engines.split(",") if w.strip()]:
            print("starting cortex (%s): %s" % (which, " ".join(CORTEX_COMMANDS[which])),
                  file=sys.stderr, flush=True)
            server = CortexServer(which, args.out)
            servers.append(server)
            try:
                server.ready()
            except RuntimeError as e:
                for sv in servers:
                    sv.close()
                print(e)
                return 1
    notes = divergence_notes(args)
    cortexes = []
    for path in args.cortex_json:
        with open(path) as f:
            cortexes.append(json.load(f))

    cases = ["humanoid"] + ([] if args.no_chain else ["chain"])
    engines = [MujocoRun, PybulletRun]
    results = {(c, e.engine): [] for c in cases for e in engines}
    cortex_rows = {c: [] for c in cases}     # [(label, server, serve case, observe)]
    for case in cases:
        for server in servers:
            for name, shape in CORTEX_CASES[case]:
                for observe, mark in CORTEX_OBSERVE:
                    label = "%s %s%s" % (server.engine, shape, mark)
                    cortex_rows[case].append((label, server, name, observe))
                    results[(case, label)] = []
    last = {}
    t_start = time.time()
    for run in range(args.runs):
        for case in cases:
            for cls in engines:
                r, sim = run_once(cls, case, args)
                results[(case, cls.engine)].append(r)
                if run == args.runs - 1:
                    last[(case, cls.engine)] = sim
                else:
                    sim.close()
                print("run %d/%d %-8s %-40s %8.0f steps/s  height %.3f  max speed %.2f" % (
                    run + 1, args.runs, case, cls.engine, r["steps_per_s"], r["final_height"],
                    r["max_speed"]), file=sys.stderr, flush=True)
            for label, server, name, observe in cortex_rows[case]:
                try:
                    r = cortex_run(server, name, observe, args)
                except RuntimeError as e:
                    for sv in servers:
                        sv.close()
                    print(e)
                    return 1
                results[(case, label)].append(r)
                print("run %d/%d %-8s %-40s %8.0f steps/s  height %.3f  max speed %.2f" % (
                    run + 1, args.runs, case, label, r["steps_per_s"], r["final_height"],
                    r["max_speed"]), file=sys.stderr, flush=True)

    print()
    print("MuJoCo %s, PyBullet %s (numpy %s), Python %s; one thread; %d warm-up + %d timed "
          "steps of 1/60 s, median of %d interleaved runs; %.0f s in all" % (
              mujoco.__version__, pybullet_version(), __import__("numpy").__version__,
              sys.version.split()[0], args.warmup, args.steps, args.runs,
              time.time() - t_start))
    for server in servers:
        h = server.hello
        print("%s: %s, Java %s, in its own JVM (%s): %s, dt 1/60" % (
            server.engine, ", ".join(h.get("jars", [])), h.get("java"),
            " ".join(CORTEX_COMMANDS[server.which]), h.get("settings")))
    if servers:
        print("interleaved: each run is MuJoCo, PyBullet, then every cortex row of the case "
              "in table order (one JVM per engine, each idle while the others run), then the "
              "next case; cortex's steps/s by the wall clock, as the others'; +obs: step! "
              "returns the joints, segments and touch; the others return nothing")
    for n in notes:
        print("note: " + n)
    if fixture_problems is not None:
        print("fixture test/fixtures/humanoid/expected.json: %s" % (
            "agrees with MuJoCo's humanoid (masses, centres of mass, inertia, anchors, axes, "
            "ranges)" if not fixture_problems else "DIFFERS: " + "; ".join(fixture_problems)))
    report = {"mujoco": mujoco.__version__, "pybullet": pybullet_version(), "notes": notes,
              "cortex": [dict(s.hello, command=CORTEX_COMMANDS[s.which]) for s in servers],
              "warmup": args.warmup, "steps": args.steps, "runs": args.runs, "cases": {}}
    for case in cases:
        rows = []
        for cls in engines:
            s = summarise(results[(case, cls.engine)])
            s["engine"] = cls.engine
            s["settings"] = last[(case, cls.engine)].settings
            rows.append(s)
        for label, server, name, observe in cortex_rows[case]:
            s = summarise(results[(case, label)])
            s["engine"] = label
            s["cortex_case"] = name
            s["cpu_steps_per_s"] = statistics.median(r["cpu_steps_per_s"]
                                                     for r in results[(case, label)])
            s["settings"] = ("as above; step! returns joints, segments, touch"
                             if observe == "observed" else "as above; step! returns nothing")
            rows.append(s)
        for cortex in cortexes:
            if case not in cortex:
                continue
            c = cortex[case]
            rows.append({"engine": cortex.get("engine", "cortex"),
                         "steps_per_s": c.get("steps_per_s"), "max_speed": c.get("max_speed"),
                         "end_speed": c.get("end_speed"),
                         "final_height": c.get("final_torso_height", c.get("final_height")),
                         "settings": cortex.get("settings", "")})
        title = ("humanoid (Gymnasium's humanoid.xml, 13 bodies, 17 hinges), dropped from "
                 "MuJoCo's initial pose" + (
                     "; cortex: test/fixtures/strangers/humanoid.blend (MuJoCo-shaped: one "
                     "closed piece per geom, overlapping at the joints) and "
                     "test/fixtures/humanoid/humanoid.blend (clipped)" if servers else "")
                 if case == "humanoid" else
                 "chain of %d capsules with hinges, dropped 1 m" % args.chain_segments + (
                     " (cortex: boxes 1.0 x 0.4 x 0.4, cortex.bench.creatures/chain)"
                     if servers else ""))
        print()
        print(title)
        print(table(case, rows))
        report["cases"][case] = rows

    os.makedirs(args.out, exist_ok=True)
    size = (480, 360)
    picture_rows = []
    for case in cases:
        panels = []
        for cls in engines:
            sim = last[(case, cls.engine)]
            target, eye = camera_for(sim, case)
            try:
                img = (render_mujoco if cls is MujocoRun else render_pybullet)(sim, target, eye, size)
            except Exception as e:       # no EGL, say: keep the numbers
                print("could not render %s %s: %s" % (cls.engine, case, e))
                img = None
            s = next(r for r in report["cases"][case] if r["engine"] == cls.engine)
            panels.append(("%s: %s" % (cls.engine, case),
                           ["%s %.3f m, %.0f steps/s" % (
                               "torso" if case == "humanoid" else "mean height",
                               s["final_height"], s["steps_per_s"]),
                            s["settings"]], img))
        for label, server, name, observe in cortex_rows[case]:
            if observe != "off":
                continue
            path = os.path.join(args.out, "cortex-%s-%s.png" % (server.which, name))
            img = None
            try:
                server.ask("picture %s %s" % (name, path), timeout=300)
                from PIL import Image
                img = Image.open(path)
            except RuntimeError as e:
                print("could not draw %s: %s" % (label, e))
            s = next(r for r in report["cases"][case] if r["engine"] == label)
            panels.append(("%s: %s" % (label, case),
                           ["%s %.3f m, %.0f steps/s" % (
                               "torso" if case == "humanoid" else "mean height",
                               s["final_height"], s["steps_per_s"]),
                            server.hello.get("settings", "")], img))
        for cortex in cortexes:
            if case not in cortex:
                continue
            img = None
            key = "image" if case == "humanoid" else "chain_image"
            if cortex.get(key) and os.path.exists(cortex[key]):
                from PIL import Image
                img = Image.open(cortex[key])
            c = cortex[case]
            h = c.get("final_torso_height", c.get("final_height"))
            panels.append(("%s: %s" % (cortex.get("engine", "cortex"), case),
                           ["%s %s, %s steps/s" % (
                               "torso" if case == "humanoid" else "mean height",
                               "-" if h is None else "%.3f m" % h,
                               "-" if c.get("steps_per_s") is None else "%.0f" % c["steps_per_s"]),
                            cortex.get("settings", "")], img))
        picture_rows.append(compose(panels, os.path.join(args.out, "%s_final.png" % case)))
    png = os.path.join(args.out, "humanoid_compare.png")
    stacked(picture_rows, png)
    for sim in last.values():
        sim.close()
    for server in servers:
        server.close()
    with open(os.path.join(args.out, "humanoid_compare.json"), "w") as f:
        json.dump(report, f, indent=1)
    print()
    print("final poses: %s (and %s)" % (os.path.relpath(png), ", ".join(
        os.path.relpath(os.path.join(args.out, "%s_final.png" % c)) for c in cases)))
    print("numbers: %s" % os.path.relpath(os.path.join(args.out, "humanoid_compare.json")))
    return 0


def divergence_notes(args, seconds=3.0):
    """Why the humanoid runs with implicitfast in MuJoCo and without joint damping in
    PyBullet: the file's RK4, and Bullet's explicit joint damping, diverge at 1/60 s."""
    import numpy as np
    notes = []
    sim = MujocoRun("humanoid", args.xml, 0, integrator="file")
    bad = None
    for k in range(int(seconds / DT)):
        sim.step(1)
        if sim.diverged():
            bad = (k + 1) * DT
            break
    notes.append("MuJoCo with the file's own integrator (RK4) at 1/60 s: %s; the humanoid "
                 "runs with %s (damping implicit), everything else as in the file" % (
                     "diverges (NaN or huge accelerations at t = %.2f s; MuJoCo resets the "
                     "state)" % bad if bad is not None else "stable", HUMANOID_INTEGRATOR))
    sim = PybulletRun("humanoid", args.xml, 0, joint_damping=True)
    prev, top = sim.coms(), 0.0
    for _ in range(int(seconds / DT)):
        sim.step(1)
        now = sim.coms()
        top = max(top, float(np.max(np.linalg.norm(now - prev, axis=1))) / DT)
        prev = now
    sim.close()
    notes.append("PyBullet with MuJoCo's joint damping (Bullet applies it explicitly) at "
                 "1/60 s: a body reaches %.0f m/s in %.0f s (%s); the humanoid runs without "
                 "joint damping" % (top, seconds, "diverges" if top > 20 else "stable"))
    return notes


def pybullet_version():
    try:
        from importlib.metadata import version
        return version("pybullet")
    except Exception:
        return "?"


if __name__ == "__main__":
    sys.exit(main())
