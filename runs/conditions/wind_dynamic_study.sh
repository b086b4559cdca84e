#!/usr/bin/env bash
# The EN 50318 case at 300 km/h under a turbulent cross-wind (docs/conditions.md,
# "Wind"): the contact force's standard deviation and the contact point's
# largest lateral position (from snapshots every 20 ms) against the mean wind
# speed, three seeds per speed, against still air; linear FE, one rank per run.
#   runs/conditions/wind_dynamic_study.sh [out/conditions/wind]
# Writes wind_sigma.csv and wind_sigma.png into the output folder.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/conditions/wind}
pcsim=${PCSIM_BIN:-build/pcsim}
speeds=${SPEEDS:-"10 20 30 40"}
seeds=${SEEDS:-"1 2 3"}
mkdir -p "$out"
[ -f "$out/still/summary.json" ] ||
  "$pcsim" run runs/en50318-300.yaml -o "$out/still" --no-report --overwrite \
    --set output.snapshot_every=20 > "$out/still.log"
for v in $speeds; do
  for s in $seeds; do
    d="$out/v$v-s$s"
    [ -f "$d/summary.json" ] && continue
    "$pcsim" run runs/conditions/en50318-300-wind.yaml -o "$d" --no-report --overwrite \
      --set conditions.wind.speed=$v --set conditions.wind.turbulence.seed=$s \
      --set output.snapshot_every=20 > "$d.log"
  done
done
/usr/bin/python3 runs/conditions/wind_sigma_plot.py "$out"
