#!/usr/bin/env bash
# `pcsim modes` with a frequency limit (SLEPc spectrum slicing) returns exactly
# the modes below the limit that a count-based shift-and-invert solve finds,
# with the same frequencies (relative 1e-10: measured 1e-12 or less, a
# hundredfold for round-off on another machine), with each of its factorisations:
# PETSc's Cholesky on one rank (the default there), PETSc's Cholesky on each
# of two ranks, each slicing a part of the interval (the default in
# parallel), MUMPS's factors over two ranks slicing it together
# (-eps_krylovschur_partitions 1), and MUMPS on one rank when the option asks
# for it.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
PY=${PCSIM_PYTHON:-/usr/bin/python3}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cat >"$WORK/slice.yaml" <<YAML
name: slice
catenary: {design: $PCSIM_SOURCE_DIR/tests/catenary/data/two-span.yaml}
modes: {max_frequency_hz: 3.0}
YAML
"$PCSIM_BIN" modes "$WORK/slice.yaml" -o "$WORK/slice" -st_ksp_view >"$WORK/slice.log" 2>&1
"$PCSIM_BIN" modes "$WORK/slice.yaml" -o "$WORK/mumps" -st_pc_factor_mat_solver_type mumps \
  -st_ksp_view >"$WORK/mumps.log" 2>&1
"$PCSIM_SOURCE_DIR/scripts/mpirun.sh" -n 2 "$PCSIM_BIN" modes "$WORK/slice.yaml" -o "$WORK/np2" \
  -st_ksp_view >"$WORK/np2.log" 2>&1
"$PCSIM_SOURCE_DIR/scripts/mpirun.sh" -n 2 "$PCSIM_BIN" modes "$WORK/slice.yaml" -o "$WORK/np2-together" \
  -eps_krylovschur_partitions 1 -st_ksp_view >"$WORK/np2-together.log" 2>&1
"$PCSIM_BIN" modes "$WORK/slice.yaml" -o "$WORK/count" -modes_fmax 0 -eps_nev 40 >"$WORK/count.log" 2>&1
for run in slice:petsc mumps:mumps np2:petsc np2-together:mumps; do
  grep -q "package used to perform factorization: ${run#*:}" "$WORK/${run%:*}.log" ||
    { echo "${run%:*}: the slicing did not factorise with ${run#*:}"; exit 1; }
done
"$PY" - "$WORK" <<'PY'
import json, sys
work = sys.argv[1]
counted = [f for f in json.load(open(f"{work}/count/summary.json"))["catenary_frequencies_hz"] if f < 3.0]
assert len(counted) < 40, "count-based solve did not reach 3 Hz"
for run in ("slice", "mumps", "np2", "np2-together"):
    sliced = json.load(open(f"{work}/{run}/summary.json"))["catenary_frequencies_hz"]
    assert len(sliced) == len(counted), f"{run}: {len(sliced)} sliced vs {len(counted)} counted modes below 3 Hz"
    worst = max(abs(a / b - 1) for a, b in zip(sliced, counted))
    assert worst < 1e-10, f"{run}: frequencies differ by {worst:.2e}"
    print(f"ok ({run}): {len(sliced)} modes below 3 Hz, largest relative difference {worst:.1e}")
PY
