#!/usr/bin/env bash
# doc/export-side-by-side.png: the four-legged creature dropped in cortex
# and, exported, in MuJoCo, side by side (org/export.org, "One creature in
# both"). Arguments, both optional: the picture's file (default
# doc/export-side-by-side.png) and the seconds after the drop (default 1).
# CORTEX_PYTHON is a Python with MuJoCo (default target/python, which
# .ci/run makes).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
export CORTEX_PYTHON="${CORTEX_PYTHON:-$PWD/target/python/bin/python}"
exec bin/lein run -m cortex.export-picture "$@"
