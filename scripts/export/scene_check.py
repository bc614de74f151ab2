#!/usr/bin/env python3
"""A creature's scene (cortex.export/scene) in MuJoCo (org/export.org).

    $CORTEX_PYTHON scripts/export/scene_check.py SCENE.xml SECONDS

Compiles SCENE.xml, the creature's MJCF included on a floor, and lets
the creature fall limp (actuation off, as check_export.py's drops) for
SECONDS.  Printed as JSON: "error" (the compiler's, or null),
"warnings" (the compiler's), "floor" (the floor's height), "gap" (the
distance from the floor to the nearest of the creature's geoms at the
start, m: 0 when it stands on it, less when it reaches into it),
"heights" (the centre of mass's height every 1/60 s), "rest_speed"
(the fastest body over the last half second, m/s) and "sim_warnings"
(what MuJoCo warned of while simulating); for a scene with no
creature, "gap" and "rest_speed" are null and "heights" empty."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mujoco  # noqa: E402
from check_export import load, run_frames, sim_warnings  # noqa: E402


def main():
    path, seconds = sys.argv[1], float(sys.argv[2])
    m, err, warnings = load(path)
    if m is None:
        print(json.dumps({"error": err, "warnings": warnings}))
        return 0
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_ACTUATION
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    floor = m.geom("scene-floor").id
    gap = min((mujoco.mj_geomDistance(m, d, floor, g, 10.0, None)
               for g in range(m.ngeom) if g != floor and m.geom_bodyid[g] > 0), default=None)
    # a scene with no creature has nothing to let fall
    heights, _, speeds, _ = run_frames(m, d, seconds) if m.nbody > 1 else ([], None, [None], None)
    print(json.dumps({"error": None, "warnings": warnings, "floor": float(m.geom_pos[floor][2]),
                      "gap": gap,
                      "heights": heights, "rest_speed": max(speeds[-30:]),
                      "sim_warnings": sim_warnings(d)}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
