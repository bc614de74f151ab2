#!/usr/bin/env bash
# Dump what Blender 3.4 says about each legacy corpus file to
# test/fixtures/corpus/<name>.json and write test/fixtures/corpus/README.md.
#
#   scripts/blender/dump_corpus.sh [CORPUS_DIR]
#
# CORPUS_DIR defaults to ../shared/corpus/blend-legacy next to the repo
# (/work/shared/corpus/blend-legacy).  The .blend files are only read, never
# copied into the repo.  Needs Debian's Blender 3.4 (apt-get install -y blender);
# override with BLENDER=...
set -uo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
corpus="${1:-$repo/../shared/corpus/blend-legacy}"
out="$repo/test/fixtures/corpus"
BLENDER="${BLENDER:-blender}"

mkdir -p "$out"
version="$("$BLENDER" --version 2>/dev/null | head -n1)"
rows=""
for f in "$corpus"/*.blend; do
  name="$(basename "$f" .blend)"
  log="$(mktemp)"
  rm -f "$out/$name.json"
  "$BLENDER" -b --factory-startup --python-exit-code 1 --python "$here/dump.py" \
      -- -i "$f" -o "$out/$name.json" >"$log" 2>&1
  rc=$?
  # What Blender printed, minus the banner lines that every run prints.
  msgs="$(grep -v -e '^Blender [0-9]' -e '^Read blend:' -e '^Blender quit' -e '^$' "$log" \
          | tr '\n' ' ' | sed 's/|/\\|/g; s/  */ /g; s/ $//')"
  rm -f "$log"
  if [ $rc -eq 0 ] && [ -s "$out/$name.json" ]; then
    summary="$(python3 - "$out/$name.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
objs = ", ".join("%s (%s%s)" % (o["name"], o["type"],
                 ", %d verts" % o["mesh"]["vertices"] if o["mesh"] else "")
                 for o in d["objects"])
print("%s | %d | %s" % (".".join(map(str, d["file_version"])), len(d["objects"]), objs))
PY
)"
    rows+="| $name.blend | opened | $summary | ${msgs:-none} |"$'\n'
    echo "ok    $name"
  else
    rows+="| $name.blend | FAILED (exit $rc) | | | | ${msgs:-none} |"$'\n'
    echo "FAIL  $name (exit $rc): $msgs"
  fi
done

cat > "$out/README.md" <<MD
# Corpus oracle dumps

What \`$version\` says about each file of the read-only legacy corpus
(\`../shared/corpus/blend-legacy/\`, Blender 2.48-2.93 files, not copied
here), one \`<name>.json\` per file in the schema of
\`scripts/blender/dump.py\`.  Regenerate with
\`scripts/blender/dump_corpus.sh\`.

Notes:
- Blender 3.4 converts old files on load (versioning): 2.4x/2.7x scenes
  come back with collections instead of layers and lamps as LIGHT objects.
- \`matrix_world\` is what Blender reports after loading and updating the
  view layer; for all of these files it is bit-for-bit the matrix it had
  right after loading, and for the 64-bit files it was checked by hand to
  equal the stored \`obmat\` bit for bit.
- \`file_version\` is \`bpy.data.version\`: the version of the Blender that
  saved the file (major, minor, file subversion).

| file | result | file_version | objects | objects (type) | Blender's messages |
|---|---|---|---|---|---|
$rows
MD
