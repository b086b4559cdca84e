#!/usr/bin/env bash
# The modal basis's first computation on several ranks (docs/benchmarks.md,
# "The modes on several ranks"): each scene's modal run with an empty cache
# and two steps, on 1 rank and on each count of RANKS, with pcsim's defaults
# (each rank slices a part of the interval with a factorisation of its own;
# the static shapes solved with a copy of the factor on every rank) and with
# BEFORE_OPTIONS (default: MUMPS's factors over the ranks, as before). Prints
# a Markdown table: the basis's time (summary.json's modal.basis_compute_s),
# the peak memory per rank and the largest relative difference of the
# eigenvalues from the 1-rank run. Run it on an otherwise idle machine.
#   runs/bench_modes_ranks.sh          RANKS="2 3" SCENES="en50318" runs/bench_modes_ranks.sh
# SCENES: en50318 (runs/en50318-300-modal.yaml, 10 spans), sections
# (runs/lines/three-sections-short-250.yaml: three tension sections computed
# apart), window (runs/interaction/two-pantographs-300-window.yaml, modal).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh > /dev/null
RANKS=${RANKS:-2}
SCENES=${SCENES:-en50318 sections}
BEFORE_OPTIONS=${BEFORE_OPTIONS:--modal_eps_krylovschur_partitions 1 -modal_static_pc_type cholesky -modal_static_pc_factor_mat_solver_type mumps}
OUT=${OUT:-out/bench-modes-ranks}
PY=/usr/bin/python3
rm -rf "$OUT"
mkdir -p "$OUT"
scene_file() {
  case $1 in
    en50318) echo runs/en50318-300-modal.yaml ;;
    sections) echo runs/lines/three-sections-short-250.yaml ;;
    window) echo runs/interaction/two-pantographs-300-window.yaml ;;
    *) echo "unknown scene '$1' (en50318, sections, window)" >&2; exit 2 ;;
  esac
}
run() {  # scene, ranks, label, options...
  local scene=$1 ranks=$2 label=$3
  shift 3
  local dir=$OUT/$scene-$ranks-$label
  # shellcheck disable=SC2086 # (the options are words)
  scripts/mpirun.sh -n "$ranks" build/pcsim run "$(scene_file "$scene")" --set catenary.model=modal \
    -pcsim_accuracy_pilot false -ts_max_steps 2 --no-report --cache "$dir/cache" -o "$dir/out" "$@" \
    > "$dir.log" 2>&1 || { cat "$dir.log"; exit 1; }
}
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| scene | ranks | factorisation | basis [s] | eigenmodes | peak memory [MB/rank] | eigenvalues against 1 rank |"
echo "|---|---|---|---:|---:|---:|---:|"
for scene in $SCENES; do
  run "$scene" 1 default
  for ranks in 1 $RANKS; do
    for label in default before; do
      [ "$ranks" = 1 ] && [ "$label" = before ] && continue
      if [ "$ranks" != 1 ]; then
        # shellcheck disable=SC2086
        if [ "$label" = before ]; then run "$scene" "$ranks" "$label" $BEFORE_OPTIONS; else run "$scene" "$ranks" "$label"; fi
      fi
      "$PY" - "$OUT/$scene-1-default" "$OUT/$scene-$ranks-$label" "$scene" "$ranks" "$label" <<'PY'
import glob, json, sys
import h5py
import numpy as np
one, this, scene, ranks, label = sys.argv[1:]
def omega2(d):
    (path,) = glob.glob(f"{d}/cache/modal-*.h5")
    with h5py.File(path, "r") as f:
        return f["omega2"][()]
s = json.load(open(f"{this}/out/summary.json"))
a, b = omega2(one), omega2(this)
diff = f"{np.max(np.abs(a - b) / a):.1e}" if a.shape == b.shape else f"{b.size} modes, not {a.size}"
name = "one a rank (default)" if label == "default" else "MUMPS over the ranks"
if ranks == "1":
    name = "PETSc's Cholesky"
print(f"| {scene} | {ranks} | {name} | {s['modal']['basis_compute_s']:.2f} | "
      f"{s['modal']['eigenmodes']} | {s['peak_memory_mb']:.0f} | {diff} |")
PY
    done
  done
done
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
