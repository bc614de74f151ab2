# MuJoCo's limp humanoid landing, every other step from 14 to 44: pelvis and torso height and speed.
# target/python/bin/python notebook/limp/landing_trace.py MJCF (the humanoid written as turn.clj writes it)
import sys, numpy as np, mujoco
sys.path.insert(0, "scripts/export")
import check_export as ce
m, err, _ = ce.load(ce.add_floor(sys.argv[1], 0))
m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
d = mujoco.MjData(m); mujoco.mj_forward(m, d)
pel = [b for b in range(m.nbody) if m.body(b).name == "pelvis"][0]
tor = [b for b in range(m.nbody) if m.body(b).name == "torso"][0]
sub = int(round((1/60)/m.opt.timestep))
v = np.zeros(6)
for i in range(1, 46):
    for _ in range(sub): mujoco.mj_step(m, d)
    if i >= 14 and i % 2 == 0:
        mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_BODY, pel, v, 0); vp = v[5]
        mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_BODY, tor, v, 0); vt = v[5]
        print("mujoco %d pelvis z %.3f vz %.2f | torso z %.3f vz %.2f" % (i, d.xpos[pel,2], vp, d.xpos[tor,2], vt))
