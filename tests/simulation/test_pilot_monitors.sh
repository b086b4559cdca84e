#!/bin/bash
# The accuracy pilot's runs are the run's own business: with -ts_monitor and
# -snes_monitor on the command line, only the run's steps print (the pilot's
# runs, in this process and in the second one, print nothing:
# solvers::DynamicSolver::silence_monitors), on the three-span modal catenary
# (1440 steps, one Newton iteration each).
# pcsim-test-processors: 2
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$PCSIM_SOURCE_DIR/tests/assembly/data/three-span-modal.yaml
for process in true false; do
  "$PCSIM_BIN" run "$scene" -o "$tmp/run-$process" --cache "$tmp/cache-$process" --no-report \
    -pcsim_accuracy_pilot true -pcsim_pilot_process "$process" -ts_monitor -snes_monitor \
    > "$tmp/$process.log" 2>&1 || { cat "$tmp/$process.log"; exit 1; }
  grep -q "4 pilot runs in" "$tmp/$process.log" || { echo "no pilot ($process)"; exit 1; }
  # One TS line a step and at the start; two SNES lines a step (before and
  # after its iteration) and three for the initial acceleration.
  ts=$(grep -c " TS dt " "$tmp/$process.log")
  snes=$(grep -c "SNES Function norm" "$tmp/$process.log")
  echo "second process $process: $ts TS lines, $snes SNES lines"
  [ "$ts" -eq 1441 ] && [ "$snes" -eq 2883 ] || { echo "the pilot's runs printed"; exit 1; }
done
echo "pilot monitors: ok"
