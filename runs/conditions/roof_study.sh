#!/usr/bin/env bash
# The EN 50318 case at 300 km/h with the pantograph's base moved by the
# vehicle (runs/conditions/en50318-300-roof.yaml: roof.csv, car-body bounce
# 3 mm at 1.2 Hz plus 0.5 mm at 8 Hz) against a still base (docs/conditions.md,
# "Vehicle excitation"); linear FE, one rank per run.
#   runs/conditions/roof_study.sh [out/conditions/roof]
# Writes roof.png (filtered contact force along the analysis section and the
# roof's motion, with each run's sigma) into the output folder.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/conditions/roof}
pcsim=${PCSIM_BIN:-build/pcsim}
mkdir -p "$out"
"$pcsim" run runs/en50318-300.yaml -o "$out/still" --no-report --overwrite > "$out/still.log"
"$pcsim" run runs/conditions/en50318-300-roof.yaml -o "$out/roof" --no-report --overwrite \
  > "$out/roof.log"
/usr/bin/python3 runs/conditions/roof_plot.py "$out" runs/conditions/roof.csv
