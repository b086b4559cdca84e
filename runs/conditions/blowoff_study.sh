#!/usr/bin/env bash
# Static blow-off of the EN 50318 line (docs/conditions.md, "Blow-off"): the
# contact wire's lateral position against the cross-wind speed, the speed at
# which it leaves the permissible lateral position (0.40 m: TSI ENE, 1600 mm
# head), against the independent estimate (blowoff_estimate.py).
#   runs/conditions/blowoff_study.sh [out/conditions/blowoff]
# Writes blowoff.csv and blowoff.png into the output folder.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/conditions/blowoff}
pcsim=${PCSIM_BIN:-build/pcsim}
mkdir -p "$out"
for v in 0 10 15 20 25 30 35 40 45 50; do
  "$pcsim" static runs/en50318-static.yaml --set conditions.wind.speed=$v -o "$out/v$v" \
    > "$out/v$v.log"
  grep -h "blow-off" "$out/v$v.log" || true
done
/usr/bin/python3 runs/conditions/blowoff_plot.py "$out"
