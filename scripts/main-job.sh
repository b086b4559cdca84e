#!/usr/bin/env bash
# The main job: the EN 50318 reference case on 2 MPI ranks.
#  1. form-finding, static configuration and modes of the reference catenary
#     (picture: out/en50318-static/catenary.png);
#  2. the reference pantograph at 300 km/h (HHT-alpha, penalty contact), the
#     EN 50318 table (ours beside the acceptance range), plots of the
#     contact force, its spectrum and the uplift (out/en50318-300/*.png) and
#     the report (out/en50318-300/report.html: all of it on one page).
# Installs what is missing and builds first.  Usage: scripts/main-job.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
OUT=${1:-out}
RANKS=${PCSIM_RANKS:-2}
PY=/usr/bin/python3
echo "== pcsim modes runs/en50318-static.yaml on $RANKS ranks"
scripts/mpirun.sh -n "$RANKS" build/pcsim modes runs/en50318-static.yaml -o "$OUT/en50318-static"
$PY postproc/plot_catenary.py "$OUT/en50318-static"
echo
echo "== pcsim run runs/en50318-300.yaml on $RANKS ranks"
scripts/mpirun.sh -n "$RANKS" build/pcsim run runs/en50318-300.yaml -o "$OUT/en50318-300" --no-report
echo
$PY postproc/report.py run "$OUT/en50318-300"
$PY postproc/interaction_table.py "$OUT/en50318-300"
for plot in force spectrum uplift; do
  $PY postproc/interaction_plots.py $plot "$OUT/en50318-300" -o "$OUT/en50318-300/$plot.png"
done
echo "plots: $OUT/en50318-static/catenary.png $OUT/en50318-300/{force,spectrum,uplift}.png"
echo "report: $OUT/en50318-300/report.html"
