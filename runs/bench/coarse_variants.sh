#!/bin/bash
# Issue 21's coarse variants of a scene: the accuracy pilot's estimates
# against the actual errors at the scene's defaults and with the modal
# cut-off at 0.8 x the one the default run takes, dt 2 ms, or h 1 m
# (docs/fidelity.md, "Coarse variants").
#
#   runs/bench/coarse_variants.sh SCENE OUT [--set KEY=VALUE ...]
#
# For each variant: the modal level with its pilot, linear FE with the same
# change (the reduction's reference), and linear FE at a quarter of the
# variant's dt and h (the discretisation's), then postproc/pilot_check.py.
# The scene's own dt and element length are DT and H (default 0.001 s and
# 0.5 m); VARIANTS picks variants (default "default cutoff dt2 h1"); PCSIM
# the binary (default build/pcsim); the runs share the cache OUT/cache.
# Prints each variant's table and a line of counts; OUT/counts.txt keeps
# the counts. Runs one rank; the pilot takes a second core where it has one.
set -euo pipefail
if [[ $# -lt 2 ]]; then
  sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
scene=$1
out=$2
shift 2
extra=("$@")
pcsim=${PCSIM:-build/pcsim}
dt=${DT:-0.001}
h=${H:-0.5}
variants=${VARIANTS:-default cutoff dt2 h1}
for v in $variants; do
  case $v in
    default | cutoff | dt2 | h1) ;;
    *)
      echo "coarse_variants.sh: unknown variant '$v' (default, cutoff, dt2, h1)" >&2
      exit 2
      ;;
  esac
done
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

quarter() { /usr/bin/python3 -c "print($1 / 4)"; }

# run NAME ARGS...: one pcsim run into OUT/NAME, kept when it is there already.
run() {
  local name=$1
  shift
  if [[ -f "$out/$name/summary.json" ]]; then return 0; fi
  "$pcsim" run "$scene" "${extra[@]}" "$@" --cache "$out/cache" -o "$out/$name" --no-report \
    > "$out/$name.log" 2>&1 || {
    echo "coarse_variants.sh: $name failed, see $out/$name.log" >&2
    exit 1
  }
}

fe=(--set catenary.model=linear -pcsim_accuracy_pilot false)
run default-modal --set catenary.model=modal
cutoff=$(/usr/bin/python3 -c "import json; print(json.load(open('$out/default-modal/summary.json'))['modal']['cutoff_hz'])")

: > "$out/counts.txt"
for v in $variants; do
  case $v in
    default) change=() vdt=$dt vh=$h ;;
    cutoff)
      change=(--set "catenary.max_frequency_hz=$(/usr/bin/python3 -c "print(0.8 * $cutoff)")")
      vdt=$dt vh=$h ;;
    dt2) change=(--set simulation.dt=0.002) vdt=0.002 vh=$h ;;
    h1) change=(--set catenary.design.element_length=1.0) vdt=$dt vh=1.0 ;;
  esac
  run "$v-modal" --set catenary.model=modal "${change[@]}"
  # The cut-off changes only the modal run: its references are the default's.
  ref=$v fe_change=("${change[@]}") fine_dt=$(quarter "$vdt") fine_h=$(quarter "$vh")
  [[ $v == cutoff ]] && ref=default fe_change=()
  run "$ref-linear" "${fe[@]}" "${fe_change[@]}"
  run "$ref-converged" "${fe[@]}" --set "simulation.dt=$fine_dt" \
    --set "catenary.design.element_length=$fine_h"
  echo "== $v: $scene ${extra[*]} ${change[*]}"
  table=$(/usr/bin/python3 postproc/pilot_check.py "$out/$v-modal" --reference "$out/$ref-linear" \
    --converged "$out/$ref-converged")
  echo "$table"
  echo "$v: $(grep 'estimates within their bounds' <<< "$table")" >> "$out/counts.txt"
done
echo "== counts ($scene ${extra[*]})"
cat "$out/counts.txt"
