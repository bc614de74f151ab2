#!/bin/sh
# Make test/fixtures/physics-sim/ and Blender's own simulation of each file
# (NAME_sim.json: where each rigid body is at 0, 0.5, 1, 2 and 4 s).
# Usage (from the repo root): scripts/blender/make_sim_fixtures.sh [NAME...]
set -e
BLENDER=${BLENDER:-blender}
OUT=test/fixtures/physics-sim
"$BLENDER" -b --factory-startup --python-exit-code 1 \
  --python scripts/blender/make_sim_fixtures.py -- "$OUT" "$@"
for f in "$OUT"/*.blend; do
  name=$(basename "$f" .blend)
  if [ $# -gt 0 ] && ! echo " $* " | grep -q " $name "; then continue; fi
  # kick's oracle keeps the first frame's substeps too (its test's speeds)
  first=; [ "$name" = kick ] && first=--first-frame
  "$BLENDER" -b --factory-startup --python-exit-code 1 \
    --python scripts/blender/simulate_physics.py -- "$f" "$OUT/${name}_sim.json" --times 0.5,1,2,4 $first
done
