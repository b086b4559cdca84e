#!/bin/bash
# A line's tension sections share no element: the modal basis computes each
# one's modes on its own DOFs (src/simulation/modal_basis_groups.cpp). On the
# short three-section line (runs/lines/three-sections-short-250.yaml, modal,
# the pilot off, a fresh cache each), against the whole line's modes at once
# (-pcsim_debug_modes_whole):
#  - the console says the line was computed in 3 parts;
#  - the same eigenvalues (the caches' omega2) and the same figures of every
#    pantograph (summary.json);
#  - the parts on 2 ranks (MUMPS's factors, each part's submatrices spread
#    over both ranks) give the figures of 1 rank.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$PCSIM_SOURCE_DIR/runs/lines/three-sections-short-250.yaml
launch=$(command -v mpiexec || command -v mpirun)
run() {  # name, launcher prefix..., then options after --
  local name=$1
  shift
  local prefix=()
  while [ "$1" != -- ]; do prefix+=("$1"); shift; done
  shift
  "${prefix[@]}" "$PCSIM_BIN" run "$scene" --set catenary.model=modal -pcsim_accuracy_pilot false \
    --no-report --cache "$tmp/cache-$name" -o "$tmp/$name" "$@" > "$tmp/$name.log" 2>&1 ||
    { cat "$tmp/$name.log"; exit 1; }
}
run parts --
run whole -- -pcsim_debug_modes_whole
run parts-np2 "$launch" -n 2 --
grep -q "3 parts that share no element, each on its own" "$tmp/parts.log" ||
  { echo "FAIL: no word of the 3 parts"; cat "$tmp/parts.log"; exit 1; }
if grep -q "parts that share no element" "$tmp/whole.log"; then
  echo "FAIL: the whole line's run says it computed parts"; exit 1
fi
"$PCSIM_PYTHON" - "$tmp" <<'PY'
import glob, json, sys
import h5py
import numpy as np
tmp = sys.argv[1]
def omega2(name):
    (path,) = glob.glob(f"{tmp}/cache-{name}/modal-*.h5")
    with h5py.File(path, "r") as f:
        return f["omega2"][()]
parts, whole = omega2("parts"), omega2("whole")
assert parts.shape == whole.shape, (parts.shape, whole.shape)
worst = np.max(np.abs(parts - whole) / whole)
# Both to SLEPc's tolerance 1e-12: 6.6e-13 and 3.0e-12 measured.
assert worst < 1e-10, f"eigenvalues differ by {worst:.2e}"
def figures(name):
    s = json.load(open(f"{tmp}/{name}/summary.json"))["en50318"]
    return {(p, f["key"]): f["value"] for p, v in s.items() for f in v["figures"]}
a, b, c = figures("parts"), figures("whole"), figures("parts-np2")
assert a.keys() == b.keys() == c.keys() and a, (a.keys(), b.keys())
def worst_of(x, y):
    return max(abs(x[k] - y[k]) / max(abs(y[k]), 1.0) for k in y)
# Each mode's vector to SLEPc's tolerance: 1.2e-11 and 1.4e-11 of a figure
# measured (1-rank parts against the whole line), 1.1e-12 over the ranks; a
# margin of 70.
w1, w2 = worst_of(a, b), worst_of(c, a)
assert w1 < 1e-9, f"parts against the whole line: {w1:.2e}"
assert w2 < 1e-9, f"2 ranks against 1: {w2:.2e}"
print(f"eigenvalues {worst:.1e}, figures {w1:.1e} (whole line), {w2:.1e} (2 ranks)")
PY
