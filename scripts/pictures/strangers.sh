#!/usr/bin/env bash
# org/images/strangers.png: the strangers' creatures (test/fixtures/strangers,
# see org/body.org) after a 3 s fall, as `lein run` draws them offscreen:
# MuJoCo's humanoid, the hobbyist's hand, the worm with its camera eye.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
out=$(mktemp -d)
for c in humanoid hand worm-eye; do
  bin/lein run -- -s 3 -r 480x360 -o "$out/$c" "test/fixtures/strangers/$c.blend" | grep -E "gap|picture"
done
ffmpeg -loglevel error -y -i "$out/humanoid/humanoid.png" -i "$out/hand/hand.png" \
  -i "$out/worm-eye/worm-eye.png" -filter_complex hstack=inputs=3 org/images/strangers.png
rm -rf "$out"
echo "wrote org/images/strangers.png"
