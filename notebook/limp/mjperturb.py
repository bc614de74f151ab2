# The limp four-legged creature's unturned MJCF (written by turn.clj WRITE=1), settled 5 s in MuJoCo, then
# pushed sideways as a whole or tipped, with either friction cone: where it is at 30 s.
#   target/python/bin/python notebook/limp/mjperturb.py /tmp/q/q-0.00.xml
import sys, numpy as np, mujoco
sys.path.insert(0, "scripts/export")
import check_export as ce
path = sys.argv[1]
for cone in ["pyramidal", "elliptic"]:
  for kind, size in [("push", 0.02), ("push", 0.05), ("push", 0.1), ("push", 0.2), ("push", 0.4), ("roll", 0.02), ("roll", 0.05), ("roll", 0.1)]:
    m, err = ce.load_on_floor(path)
    if cone == "elliptic": m.opt.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    d = mujoco.MjData(m); mujoco.mj_forward(m, d)
    mass = m.body_mass[1:].sum()
    com = lambda: (m.body_mass[1:]*d.xipos[1:,2]).sum()/mass
    while d.time < 5: mujoco.mj_step(m, d)
    h0 = com()
    if kind == "push": d.qvel[1] += size          # sideways (the torso's y), whole free body
    else: d.qvel[3] += size / 0.1                 # roll rate for 0.1 s
    if kind == "roll":
        t1 = d.time + 0.1
        while d.time < t1: mujoco.mj_step(m, d)
        d.qvel[3] = 0
    ys = []
    while d.time < 30:
        mujoco.mj_step(m, d)
    t = m.body("torso").id
    print("%s %s %.2f: belly at 5 s %.3f, at 30 s %.3f up %.2f speed %.3f" % (cone, kind, size, h0, com(), d.xmat[t][8], np.abs(d.qvel).max()))
