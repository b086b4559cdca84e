#!/usr/bin/env bash
# Benchmark of the residual after an exact Newton update
# (-ts_hht_residual_update, docs/scaling.md): the EN 50318 case at 300 km/h
# with spans.count = 10, 40, 100 on 1 and 2 ranks, each run with every
# residual evaluated and with the update (default), REPEAT times interleaved;
# prints the median ms/step of each, their ratio and the largest difference of
# the contact force between the two (round-off: <= 1e-9 of its maximum;
# runs/bench/step_pair.sh).
#   runs/bench_residual_update.sh [extra pcsim options]
# Environment: SPANS="10 40 100" RANKS="1 2" STEPS=600 REPEAT=3. Run it on an
# otherwise idle machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
exec runs/bench/step_pair.sh evaluated build/pcsim "-ts_hht_residual_update 0" \
  updated build/pcsim "-ts_hht_residual_update 1" "$@"
