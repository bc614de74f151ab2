#!/bin/bash
cd /work/wt-limp
L="$1"; O="$2"; S="$3"; PROF="${4:-}"
LABEL="$L" OPTS="$O" SOPTS="$S" timeout 900 bin/lein $PROF run -m clojure.main notebook/limp/batch.clj 2>&1 | grep -v WARN | tail -2
