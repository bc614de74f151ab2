#!/bin/sh
# Generated from org/engine.org by lein tangle: edit the chapter, not this file.
# Step throughput of chain-100 and chain-300 on both engines, one after
# the other, and the native/jBullet ratio.
cd "$(dirname "$0")/.."
j=$(lein run -m cortex.engine-speed "$@" | grep sim-s/s)
n=$(lein with-profile +native run -m cortex.engine-speed "$@" | grep sim-s/s)
echo "$j"
echo "$n"
echo "$j" | while read -r _ chain speed _; do
  other=$(echo "$n" | awk -v c="$chain" '$2 == c {print $3}')
  echo "$chain native/jBullet $(echo "$other / $speed" | bc -l | cut -c1-5)"
done
