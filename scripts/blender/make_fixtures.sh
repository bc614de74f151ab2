#!/usr/bin/env bash
# Regenerate test/fixtures/blend/{b34,b45,b50}/ with three real Blenders.
#
#   scripts/blender/make_fixtures.sh            # all three tags
#   scripts/blender/make_fixtures.sh b34 b50    # only some
#
# What it needs (none of it lives in the repo):
#   b34: Debian's Blender 3.4:       apt-get install -y blender
#   b45: bpy 4.5 wheel in a venv:    /root/.pyenv/versions/3.11.7/bin/python -m venv /work/venvs/bpy45
#                                    /work/venvs/bpy45/bin/pip install 'bpy==4.5.*'
#   b50: bpy 5.0.1 wheel in a venv:  /root/.pyenv/versions/3.11.7/bin/python -m venv /work/venvs/bpy50
#                                    /work/venvs/bpy50/bin/pip install 'bpy==5.0.1'
# (both wheels need CPython 3.11 exactly; any python3.11 will do for the venvs).
# Override the locations with BLENDER=..., BPY45_PYTHON=..., BPY50_PYTHON=...
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
out="$repo/test/fixtures/blend"

BLENDER="${BLENDER:-blender}"
BPY45_PYTHON="${BPY45_PYTHON:-/work/venvs/bpy45/bin/python}"
BPY50_PYTHON="${BPY50_PYTHON:-/work/venvs/bpy50/bin/python}"

tags=("$@")
[ ${#tags[@]} -eq 0 ] && tags=(b34 b45 b50)

for tag in "${tags[@]}"; do
  echo "== $tag"
  rm -rf "$out/$tag"
  case "$tag" in
    b34) "$BLENDER" -b --factory-startup --python-exit-code 1 \
           --python "$here/make_fixtures.py" -- "$out/$tag" ;;
    b45) "$BPY45_PYTHON" "$here/make_fixtures.py" "$out/$tag" ;;
    b50) "$BPY50_PYTHON" "$here/make_fixtures.py" "$out/$tag" ;;
    *) echo "unknown tag $tag (b34, b45, b50)" >&2; exit 2 ;;
  esac
  # Blender writes *.blend1 backups when overwriting; none should exist, but
  # make sure they never end up in the repo.
  rm -f "$out/$tag"/*.blend1
done
