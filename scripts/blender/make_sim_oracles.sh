#!/bin/sh
# Blender 4.5's and 5.2's own simulation of each test/fixtures/physics-sim/
# scene, beside the Blender 3.4 one (NAME_sim.json, from make_sim_fixtures.sh):
# NAME_sim-4.5.json and NAME_sim-5.2.json, same format (simulate_physics.py
# --times 0.5,1,2,4: every rigid body at 0, 0.5, 1, 2 and 4 s, with the Blender
# version that said so).  The .blend files are only opened, never re-saved:
# they stay the Blender 3.4 files the 3.4 oracle was made from.
#
# Usage (from the repo root): scripts/blender/make_sim_oracles.sh [NAME...]
#
# What it needs (none of it lives in the repo):
#   4.5: bpy 4.5 wheel (CPython 3.11):   /root/.pyenv/versions/3.11.7/bin/python -m venv /work/venvs/bpy45
#                                        /work/venvs/bpy45/bin/pip install 'bpy==4.5.*'
#   5.2: bpy 5.2.3 wheel (CPython 3.13): /root/.pyenv/versions/3.13.0/bin/python -m venv /work/venvs/bpy52
#                                        /work/venvs/bpy52/bin/pip install 'bpy==5.2.3'
# Other locations: BPY45=/path/to/python BPY52=/path/to/python.
# A version whose python is missing or cannot import bpy is skipped with a
# message (its files are left as they are); the exit status is then still 0.
set -e
BPY45=${BPY45:-/work/venvs/bpy45/bin/python}
BPY52=${BPY52:-/work/venvs/bpy52/bin/python}
OUT=test/fixtures/physics-sim
SCRIPT=scripts/blender/simulate_physics.py

# oracle VERSION PYTHON NAME...: simulate every fixture (or the NAMEs given)
# with that python's bpy into NAME_sim-VERSION.json.
oracle() {
  version=$1
  py=$2
  shift 2
  if ! "$py" -c 'import bpy' >/dev/null 2>&1; then
    echo "skipping Blender $version: $py cannot import bpy" >&2
    return 0
  fi
  for f in "$OUT"/*.blend; do
    name=$(basename "$f" .blend)
    if [ $# -gt 0 ] && ! echo " $* " | grep -q " $name "; then continue; fi
    # simulate_physics.py takes its arguments after "--" under both the
    # Blender executable and a plain python with the bpy module.
    first=; [ "$name" = kick ] && first=--first-frame
    "$py" "$SCRIPT" -- "$f" "$OUT/${name}_sim-$version.json" --times 0.5,1,2,4 $first
  done
}

oracle 4.5 "$BPY45" "$@"
oracle 5.2 "$BPY52" "$@"
