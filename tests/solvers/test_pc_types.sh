#!/bin/bash
# pcsim's step solvers as PETSc PC types (src/solvers/low_rank.cpp,
# src/solvers/schur_dd.cpp): -help lists them under -pc_type;
# -pc_type pcsimwoodbury is the cheap path (bitwise the default run: the same
# solver chosen by name); -pcsim_path full -pc_type pcsimschur is the full
# path's default exact domain decomposition (bitwise); -pc_type pcsimschur
# factors J0 for the cheap path's inner KSP (-cheap_pc_type: bitwise the
# default, which is that solver too on one rank: the LU of the whole matrix);
# contradictions and unknown types are input errors before any work (exit 2,
# no output folder).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
common=(--no-report -ts_max_steps 300)

run() {  # name, options...
  local name=$1
  shift
  "$PCSIM_BIN" run "$scene" -o "$tmp/$name" "${common[@]}" "$@" > "$tmp/$name.log" 2>&1 ||
    { cat "$tmp/$name.log"; exit 1; }
}
same() {  # two result folders: bitwise equal time series
  "$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/tests/contact/compare_runs.py" "$tmp/$1" "$tmp/$2" 0 ||
    exit 1
}
refused() {  # expected text, options...: exit 2 before any work
  local text=$1 status=0
  shift
  "$PCSIM_BIN" run "$scene" -o "$tmp/refused" "${common[@]}" "$@" > "$tmp/refused.log" 2>&1 ||
    status=$?
  [ "$status" = 2 ] || { echo "exit $status, expected 2:"; cat "$tmp/refused.log"; exit 1; }
  grep -q -- "$text" "$tmp/refused.log" || { cat "$tmp/refused.log"; exit 1; }
  [ ! -e "$tmp/refused" ] || { echo "an output folder was left behind"; exit 1; }
}

"$PCSIM_BIN" run "$scene" -o "$tmp/help" "${common[@]}" -help > "$tmp/help.log" 2>&1 || true
for type in pcsimwoodbury pcsimschur; do
  grep -- "-pc_type" "$tmp/help.log" | grep -q "$type" ||
    { echo "-help does not list $type under -pc_type"; grep -- "-pc_type" "$tmp/help.log"; exit 1; }
done

run default
run woodbury -pc_type pcsimwoodbury -ksp_view
grep -q "type: pcsimwoodbury" "$tmp/woodbury.log" || { cat "$tmp/woodbury.log"; exit 1; }
grep -q '"path": "cheap"' "$tmp/woodbury/summary.json"
same default woodbury
run inner-schur -cheap_pc_type pcsimschur
same default inner-schur

run full -pcsim_path full
run full-schur -pcsim_path full -pc_type pcsimschur -ksp_view
grep -q "type: pcsimschur" "$tmp/full-schur.log" || { cat "$tmp/full-schur.log"; exit 1; }
same full full-schur

refused "-pcsim_path full asks for the full Newton path" -pcsim_path full -pc_type pcsimwoodbury
refused "unknown preconditioner 'nosuchpc'" -pc_type nosuchpc
refused "the cheap path needs a linearised or modal catenary" \
  -pc_type pcsimwoodbury --set effects.catenary_nonlinear=true
echo "PC types: listed by -help; chosen by name, bitwise the default solvers; errors exit 2"
