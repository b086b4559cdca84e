#!/usr/bin/env bash
# The README's study (docs/studies.md, "The 1024-case study"): first-order and
# total Sobol indices of every EN 50318 figure with respect to six parameters
# of the default pantograph (the EN 50318 two-mass model,
# meshes/pantographs/en50318_two_mass.yaml: head and frame mass, stiffness and
# damping), each uniform on +-20 % of its value, on the EN 50318 case at
# 300 km/h at the modal level (runs/en50318-300-modal.yaml); a Saltelli design
# with N base rows, N (6 + 2) cases: N = 128 gives 1024.
#   runs/studies/sobol-1024.sh [N] [OUT]       (defaults: 128, out/sobol-<cases>)
# Environment: RANKS (mpirun -n, default 2), PCSIM_PYTHON (/usr/bin/python3).
# Writes OUT.csv (the case table), OUT/ (the sweep: sweep.csv, one run per
# case), OUT/sensitivity.{csv,md,png} and OUT/scatter.png, OUT/study-time.txt
# (the sweep's wall time). The same command again resumes a stopped sweep
# (the same table: the design is seeded). The cases' modal basis comes from
# out/.pcsim-cache (computed by the first case if missing: about a minute).
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-128}
OUT=${2:-out/sobol-$((N * 8))}
RANKS=${RANKS:-2}
PYTHON=${PCSIM_PYTHON:-/usr/bin/python3}
[ -x build/pcsim ] || scripts/build.sh > /dev/null
mkdir -p "$(dirname "$OUT")"
# +-20 % of the model's values (head: m1 7.2 kg, k1 4200 N/m, c1 10 Ns/m;
# frame: m2 15 kg, k2 50 N/m, c2 90 Ns/m).
stage() { echo "pantographs[0].model.stages[$1].$2=uniform($3,$4)"; }
"$PYTHON" postproc/sample.py saltelli -n "$N" --seed 1 -o "$OUT.csv" \
  -p "$(stage 0 mass 5.76 8.64)" -p "$(stage 0 stiffness 3360 5040)" \
  -p "$(stage 0 damping 8 12)" -p "$(stage 1 mass 12 18)" \
  -p "$(stage 1 stiffness 40 60)" -p "$(stage 1 damping 72 108)"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
start=$(date +%s.%N)
status=0
scripts/mpirun.sh -n "$RANKS" build/pcsim sweep runs/en50318-300-modal.yaml --cases "$OUT.csv" \
  -o "$OUT" --no-report || status=$?
end=$(date +%s.%N)
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
# 3: a case failed (sensitivity.py drops its base row); anything else stops here.
[ $status -eq 0 ] || [ $status -eq 3 ] || exit $status
wall=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
echo "$((N * 8)) cases on $RANKS ranks: $wall s (sweep exit $status)" | tee "$OUT/study-time.txt"
"$PYTHON" postproc/sensitivity.py "$OUT"
