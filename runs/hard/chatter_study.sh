#!/usr/bin/env bash
# The undamped dropper chatter (docs/hard-cases.md): runs/hard/undamped.yaml
# (no Rayleigh damping, HHT alpha 0) at time steps 2, 1, 0.5 and 0.25 ms and the
# damped reference, with the energy balance; then the slack events per half of
# the run and the energy over time (postproc/chatter.py).
#   runs/hard/chatter_study.sh [RESULTS_DIR]      (default out/chatter; ~3 min on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/../.."
results=${1:-out/chatter}
mkdir -p "$results"
for dt in 0.002 0.001 0.0005 0.00025; do
  build/pcsim run runs/hard/undamped.yaml -o "$results/undamped-dt$dt" --no-report \
    --set simulation.dt=$dt > "$results/undamped-dt$dt.log"
done
build/pcsim run runs/hard/undamped.yaml -o "$results/damped-dt0.001" --no-report \
  --set effects.rayleigh_damping=true --set simulation.hht_alpha=0.1 > "$results/damped-dt0.001.log"
/usr/bin/python3 postproc/chatter.py "$results" --plot docs/hard/chatter.png
