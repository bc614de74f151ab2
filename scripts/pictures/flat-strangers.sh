#!/usr/bin/env bash
# org/images/flat-strangers.png: the strangers' creatures with flat parts
# (test/fixtures/flat-strangers, see org/body.org) after a 3 s fall, as
# `lein run` draws them offscreen: the fish with plane fins, the walker on
# four flat feet, the paddle with an n-gon blade.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
out=$(mktemp -d)
for c in fish leaf-walker flat-hexagon-paddle; do
  bin/lein run -- -s 3 -r 480x360 -o "$out/$c" "test/fixtures/flat-strangers/$c.blend" | grep -E "gap|picture"
done
ffmpeg -loglevel error -y -i "$out/fish/fish.png" -i "$out/leaf-walker/leaf-walker.png" \
  -i "$out/flat-hexagon-paddle/flat-hexagon-paddle.png" -filter_complex hstack=inputs=3 org/images/flat-strangers.png
rm -rf "$out"
echo "wrote org/images/flat-strangers.png"
