#!/usr/bin/env bash
# What accuracy costs (docs/fidelity.md): the fidelity ladder of a run scene
# (nonlinear full path, linearised cheap path, modal catenary at 0.8, 1.1 and
# 1.2 times the Doppler cut-off, vertical modes), at dt x 1, 2 and element
# length x 1, 2, on one rank, by `pcsim study accuracy`. Prints the table;
# results (accuracy.csv, accuracy.md, accuracy.svg) in out/<scene>-accuracy/.
# The modes go to the cache (out/.pcsim-cache): a second run reuses them.
#   runs/bench_fidelity.sh [SCENE.yaml] [extra pcsim options]
# Run it on an otherwise idle machine: it measures wall time (the table
# records the load average before and after).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
SCENE=${1:-runs/en50318-300.yaml}
shift || true
build/pcsim study accuracy "$SCENE" -study_dt_factors 1,2 -study_h_factors 1,2 \
  -study_cutoff_factors 0.8,1.2 "$@"
