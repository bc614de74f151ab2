# MuJoCo's held humanoid with each cone servo's forcerange scaled by 1, 1/sqrt 3 and 1/2: its
# centre of mass height after 1 to 10 s. The MJCF is turn.clj's (WRITE=1, FILE the strangers' humanoid,
# HEADINGS "[0.0]", TAG hum): target/python/bin/python notebook/limp/held_clamp.py /tmp/q/hum-0.00.xml
import sys, numpy as np, mujoco, os
sys.path.insert(0, "scripts/export")
import check_export as ce
path = sys.argv[1]
for scale in [1.0, 1/np.sqrt(3), 0.5]:
    floored = ce.add_floor(path, 0)
    m, err, _ = ce.load(floored); os.remove(floored)
    nj = {}
    for a in range(m.nu):
        j = m.actuator_trnid[a, 0]; b = m.jnt_bodyid[j]
        nj[a] = sum(1 for k in range(m.njnt) if m.jnt_bodyid[k] == b)
    for a in range(m.nu):
        if nj[a] == 3:
            m.actuator_forcerange[a] *= scale
    d = mujoco.MjData(m); mujoco.mj_forward(m, d)
    mass = m.body_mass[1:].sum()
    sub = max(1, int(round((1/60)/m.opt.timestep)))
    hs = []
    for i in range(600):
        for _ in range(sub): mujoco.mj_step(m, d)
        hs.append((m.body_mass[1:] * d.xipos[1:, 2]).sum() / mass)
    print("cone clamp x%.3f: heights at 1..10 s" % scale, ["%.3f" % hs[k*60-1] for k in range(1, 11)], "cones actuators", sum(1 for a in nj if nj[a]==3))
