#!/usr/bin/env bash
# A/B benchmark of the FE time step between two pcsim binaries (e.g. a build
# of the previous commit and one of this): the EN 50318 case at 300 km/h with
# spans.count = 10, 40, 100 on 1 and 2 ranks, each binary REPEAT times,
# interleaved; prints the median ms/step of each, their ratio and the largest
# difference of the contact force between the two (runs/bench/step_pair.sh).
#   runs/bench_step_ab.sh BEFORE_BIN AFTER_BIN [extra pcsim options]
# Environment: SPANS="10 40 100" RANKS="1 2" STEPS=600 REPEAT=3. Run it on an
# otherwise idle machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { echo "usage: $0 BEFORE_BIN AFTER_BIN [pcsim options]" >&2; exit 2; }
before=$1 after=$2
shift 2
exec runs/bench/step_pair.sh before "$before" "" after "$after" "" "$@"
