# MuJoCo drops of the MJCF files turn.clj wrote: python mjturn.py SECONDS "GLOB"
import sys, glob, numpy as np, mujoco
sys.path.insert(0, "scripts/export")
import check_export as ce
secs = float(sys.argv[1])
for path in sorted(glob.glob(sys.argv[2])):
    m, err, _ = ce.load(ce.add_floor(path, 0))
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    mass = m.body_mass[1:].sum()
    d = mujoco.MjData(m); mujoco.mj_forward(m, d)
    h = lambda: (m.body_mass[1:] * d.xipos[1:, 2]).sum() / mass
    out = []; one = None
    for i in range(int(round(secs / m.opt.timestep))):
        mujoco.mj_step(m, d)
        if i + 1 == 240: one = h()
        if (i + 1) % 480 == 0: out.append("%.3f" % h())
    print(path, "1 s %.3f" % one, out, flush=True)
