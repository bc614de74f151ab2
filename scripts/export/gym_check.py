#!/usr/bin/env python3
"""An exported creature as a Gymnasium environment (org/export.org).

    $CORTEX_PYTHON scripts/export/gym_check.py SCENE.xml MAIN_BODY STEPS

SCENE.xml includes cortex's MJCF and adds a floor, as doc/export.md
shows.  Gymnasium's Ant-v5 is made of it, reset with seed 0 and stepped
STEPS times with actions drawn from its action space (seeded); printed
as JSON: the observation and action sizes, the action space's bounds,
the steps taken, and what MuJoCo warned of ({warning: times}).  Exit 3
where Gymnasium does not import."""
import json
import sys
import warnings

warnings.filterwarnings("ignore")
try:
    import gymnasium as gym
except ImportError as e:
    print(json.dumps({"skipped": str(e)}))
    sys.exit(3)
import mujoco


def main():
    scene, body, steps = sys.argv[1], sys.argv[2], int(sys.argv[3])
    env = gym.make("Ant-v5", xml_file=scene, main_body=body, healthy_z_range=(-1e9, 1e9),
                   include_cfrc_ext_in_observation=False)
    env.action_space.seed(0)
    env.reset(seed=0)
    taken = 0
    for _ in range(steps):
        _, _, terminated, truncated, _ = env.step(env.action_space.sample())
        taken += 1
        if terminated or truncated:
            break
    d = env.unwrapped.data
    print(json.dumps({
        "observations": int(env.observation_space.shape[0]),
        "actions": int(env.action_space.shape[0]),
        "low": env.action_space.low.tolist(), "high": env.action_space.high.tolist(),
        "steps": taken,
        "warnings": {mujoco.mjtWarning(i).name: int(d.warning[i].number)
                     for i in range(len(d.warning)) if d.warning[i].number > 0}}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
