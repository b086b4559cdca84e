#!/usr/bin/env bash
# Benchmark of the HHT alpha-term taken from the previous step's last residual
# (-ts_hht_reuse_alpha_term, docs/scaling.md): the EN 50318 case at 300 km/h
# with spans.count = 10, 40, 100 on 1 and 2 ranks, each run with the term
# evaluated and reused (default), REPEAT times interleaved; prints the median
# ms/step of each, their ratio and the largest difference of the contact force
# between the two (round-off: <= 1e-9 of its maximum; runs/bench/step_pair.sh).
#   runs/bench_alpha_term.sh [extra pcsim options]
# Environment: SPANS="10 40 100" RANKS="1 2" STEPS=600 REPEAT=3, SCENE (another
# run scene, e.g. runs/interaction/dsa380-300-base.yaml: a configuration-
# dependent mass). Run it on an otherwise idle machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
exec runs/bench/step_pair.sh evaluated build/pcsim "-ts_hht_reuse_alpha_term 0" \
  reused build/pcsim "-ts_hht_reuse_alpha_term 1" "$@"
