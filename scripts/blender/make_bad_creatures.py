"""Build broken creatures for cortex's error tests: test/fixtures/creatures/.

    blender -b --factory-startup --python scripts/blender/make_bad_creatures.py -- [OUTDIR]

Each file is the worm of make_creatures.py with one thing wrong, the way
a designer might get it wrong (or a hostile file might):
- lonely.blend        one segment, and a joint that has nothing to join it to
- evil-joint.blend    a joint description that would write a file if evaluated
- read-eval.blend     a joint description using the reader's #= eval form
- bad-mass.blend      a segment whose mass is text
- unknown-type.blend  a joint of a type cortex does not know
The file the two evil descriptions would write is EVIL_PATH.
"""

import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dump  # noqa: E402
from make_creatures import (HALF_GAP, chamfered_prism_x, joint_empty,  # noqa: E402
                            joints_root, save, segment)
from make_fixtures import empty_file, update  # noqa: E402

EVIL_PATH = "/tmp/cortex-evil-joint-was-evaluated"


def worm(joint_spec, lonely=False, mass_2=1.0):
    """The reference worm, with the given joint text and second mass."""
    empty_file()
    c = 1.0 + HALF_GAP
    segment("worm-1", chamfered_prism_x("worm-1", 1.0, 0.3, 0.2, 0.15), (-c, 0.0, 0.5), 1.0)
    if not lonely:
        seg = segment("worm-2", chamfered_prism_x("worm-2", 1.0, 0.3, 0.2, 0.15),
                      (c, 0.0, 0.5), 1.0)
        seg["mass"] = mass_2
    joint_empty("worm-joint", joints_root(), (0.0, 0.0, 0.5), joint_spec)
    update()


def main():
    args = dump.script_args()
    out = os.path.normpath(os.path.abspath(args[0]) if args else os.path.join(
        HERE, "..", "..", "test", "fixtures", "creatures"))
    os.makedirs(out, exist_ok=True)
    print("Blender", bpy.app.version_string, "->", out)
    cases = [
        ("lonely", dict(joint_spec="{:type :point}", lonely=True)),
        ("evil-joint", dict(joint_spec='{:type :point :x (spit "%s" "evaluated")}' % EVIL_PATH)),
        ("read-eval", dict(joint_spec='#=(clojure.core/spit "%s" "evaluated")' % EVIL_PATH)),
        ("bad-mass", dict(joint_spec="{:type :point}", mass_2="heavy")),
        ("unknown-type", dict(joint_spec="{:type :rubber :stiffness 3}")),
    ]
    for name, kw in cases:
        worm(**kw)
        save(os.path.join(out, name + ".blend"))


if __name__ == "__main__":
    main()
