# Nudged MuJoCo drops of the exported four-legged creature: python perturb.py MJCF SECONDS
import sys, numpy as np, mujoco
sys.path.insert(0, "scripts/export")
import check_export as ce
secs = float(sys.argv[2])
m, err, _ = ce.load(ce.add_floor(sys.argv[1], 0))
m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
mass = m.body_mass[1:].sum()
def run(name, setup):
    d = mujoco.MjData(m)
    d.qpos[2] += 1.0
    setup(d)
    mujoco.mj_forward(m, d)
    out = []
    for i in range(int(secs / m.opt.timestep)):
        mujoco.mj_step(m, d)
        if (i + 1) % int(2 / m.opt.timestep) == 0:
            out.append("%.3f" % ((m.body_mass[1:] * d.xipos[1:, 2]).sum() / mass))
    print(name, out, flush=True)
def vy(v):
    def f(d): d.qvel[1] = v
    return f
def roll(a):
    def f(d):
        q = np.zeros(4); mujoco.mju_axisAngle2Quat(q, np.array([1.0, 0, 0]), a)
        r = np.zeros(4); mujoco.mju_mulQuat(r, q, d.qpos[3:7].copy()); d.qpos[3:7] = r
    return f
def yaw(a):
    def f(d):
        q = np.zeros(4); mujoco.mju_axisAngle2Quat(q, np.array([0, 0, 1.0]), a)
        r = np.zeros(4); mujoco.mju_mulQuat(r, q, d.qpos[3:7].copy()); d.qpos[3:7] = r
    return f
#run("none", lambda d: None)
#, yaw(0.3))
#, yaw(1.0))
#run("vy 0.01", vy(0.01))
#run("vy 0.1", vy(0.1))
#run("roll 0.01", roll(0.01))
#run("roll 0.05", roll(0.05))
print("---")
for a in [0.1, 0.2, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.1, 1.2, 1.4, 1.5707963]:
    run("yaw %.2f" % a, yaw(a))
