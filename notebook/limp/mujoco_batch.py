# Ten limp drops of an exported creature in MuJoCo, each 3 mm higher than the one
# before (the notebook README): python mujoco_batch.py NAME SECONDS MJCF, run from
# the repository root, MJCF written by cortex.export (its lowest point 1 m up).
import sys, numpy as np, mujoco
sys.path.insert(0, "scripts/export")
import check_export as ce
f = sys.argv[1]; secs = float(sys.argv[2])
m, err, _ = ce.load(ce.add_floor(sys.argv[3], 0))
m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
mass = m.body_mass[1:].sum()
for k in range(10):
    d = mujoco.MjData(m)
    d.qpos[2] += 0.003 * k
    mujoco.mj_forward(m, d)
    out = []
    for i in range(int(secs * 240)):
        mujoco.mj_step(m, d)
        if (i + 1) % 1200 == 0:
            out.append("%.3f" % ((m.body_mass[1:] * d.xipos[1:, 2]).sum() / mass))
    print(k, out, "max speed last", "%.3f" % np.abs(d.qvel).max())
