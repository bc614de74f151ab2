#!/bin/bash
# usage: many.sh label OPTS SOPTS [profile]
cd /work/wt-limp
L="$1"; O="$2"; S="$3"; PROF="${4:-}"
out=$(SHORT=1 EVERY=30 FROM=2.0 UPTO=${UPTO:-7} OPTS="$O" SOPTS="$S" timeout 600 bin/lein $PROF run -m clojure.main notebook/limp/trace.clj 2>&1 | grep -v WARN | tail -2)
echo "== $L  $O $S $PROF"; echo "$out"
