#!/bin/bash
# A line's tension sections share no element: the modal basis computes each
# one's modes on its own DOFs (src/simulation/modal_basis_groups.cpp). On the
# short three-section line (runs/lines/three-sections-short-250.yaml, modal,
# the pilot off, a fresh cache each), against the whole line's modes at once
# (-pcsim_debug_modes_whole):
#  - the console says the line was computed in 3 parts;
#  - the same eigenvalues (the caches' omega2) and the same figures of every
#    pantograph (summary.json);
#  - the parts on 2 ranks (each rank slicing a part of the frequency interval
#    for each part, and saying so) give the figures of 1 rank;
#  - the parts' basis is in 3 column blocks, the whole line's in 1, and the
#    droppers' forces of both agree;
#  - with records in batches the bounded dropper check renews its base by
#    single-precision updates, and gives the contact forces of checking
#    every dropper at every state.
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
    --no-report --cache "$tmp/cache-${cache_of:-$name}" -o "$tmp/$name" "$@" > "$tmp/$name.log" 2>&1 ||
    { cat "$tmp/$name.log"; exit 1; }
}
run parts --
run whole -- -pcsim_debug_modes_whole
run parts-np2 "$launch" -n 2 --
# Records in batches: no line of bounds, each block's anchor apart
# (ModalCatenary::refresh_blocks); the bases from the runs above.
cache_of=parts run parts-batches -- -pcsim_record_batches true
cache_of=whole run whole-batches -- -pcsim_debug_modes_whole -pcsim_record_batches true
cache_of=parts run every-batches -- -pcsim_record_batches true --set catenary.modal.droppers=all
grep -q "3 parts that share no element, each on its own" "$tmp/parts.log" ||
  { echo "FAIL: no word of the 3 parts"; cat "$tmp/parts.log"; exit 1; }
# On 2 ranks each rank slices a part of the frequency interval (configure_slicing).
grep -q "3 parts that share no element, each on its own; the interval in 2 slices at once" \
  "$tmp/parts-np2.log" || { echo "FAIL: no word of the 2 slices"; cat "$tmp/parts-np2.log"; exit 1; }
if grep -q "slices at once" "$tmp/parts.log"; then
  echo "FAIL: the 1-rank run says it sliced parts of the interval at once"; exit 1
fi
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
# Each mode's vector to SLEPc's tolerance: 1.2e-11 to 3.3e-11 of a figure
# measured (1-rank parts against the whole line), 1.1e-12 to 3.1e-11 over
# the ranks (the larger on an AMD EPYC machine, 2026-12-05); a margin of 30.
w1, w2 = worst_of(a, b), worst_of(c, a)
assert w1 < 1e-9, f"parts against the whole line: {w1:.2e}"
assert w2 < 1e-9, f"2 ranks against 1: {w2:.2e}"
# The parts' basis in 3 column blocks (each section's modes and droppers'
# Ritz vectors on its own columns: the step reads a dropper's or contact
# point's block only); the whole line's modes are not zero outside a
# section, one block.
def blocks(name):
    return json.load(open(f"{tmp}/{name}/summary.json"))["modal"]["column_blocks"]
assert blocks("parts") == 3 and blocks("parts-np2") == 3, (blocks("parts"), blocks("parts-np2"))
assert blocks("whole") == 1, blocks("whole")
# The droppers' forces by blocks against one block: the same slack samples,
# and forces within the records' rounding. One at a time (single precision,
# bound 1 N): 9.8e-5 N measured of 225 N, 1e-3 allowed. In batches (double
# precision) what is left is the two bases' own rounding, which the run
# carries along: 8.9e-8 N measured on one machine, 7.4e-6 N on another
# (2026-12-04, AMD EPYC family 26, BLIS serial), growing from 1.8e-8 N in
# the run's first 1000 samples to 7.4e-6 N in its sixth, smoothly; the
# figures agree to 3.3e-11 there. 1e-4 N allowed: 14 times the larger, and
# a block's product over wrong columns would be off by newtons.
def dropper_gap(parts, whole):
    with h5py.File(f"{tmp}/{parts}/results.h5") as fa, h5py.File(f"{tmp}/{whole}/results.h5") as fb:
        fp, fw = fa["droppers/force"][()], fb["droppers/force"][()]
    assert fp.shape == fw.shape, (fp.shape, fw.shape)
    assert np.array_equal(fp <= 0, fw <= 0), f"the slack droppers differ ({parts})"
    return np.max(np.abs(fp - fw))
df, db = dropper_gap("parts", "whole"), dropper_gap("parts-batches", "whole-batches")
assert df < 1e-3, f"dropper forces differ by {df:.2e} N"
assert db < 1e-4, f"dropper forces in batches differ by {db:.2e} N"
d, e = figures("parts-batches"), figures("whole-batches")
wb = worst_of(d, e)
assert wb < 1e-9, f"parts against the whole line, records in batches: {wb:.2e}"
# The bounded check against every dropper at every state: the slack set is
# the same (its bounds are rigorous) and a candidate's elongation exact, so
# the contact forces differ by the elongations' order of summation only
# (1.3e-12 of the largest measured; 1e-11 allowed, where a missed slack
# dropper moves the force by newtons). The check's bases in single
# precision are exercised (0.035 a step measured).
def contact(name):
    with h5py.File(f"{tmp}/{name}/results.h5") as f:
        return np.concatenate([f[f"pantographs/{p}/contact_force"][()] for p in f["pantographs"]])
cb, ce = contact("parts-batches"), contact("every-batches")
we = np.max(np.abs(cb - ce)) / np.max(np.abs(ce))
assert we < 1e-11, f"bounded against every dropper: {we:.2e}"
m = json.load(open(f"{tmp}/parts-batches/summary.json"))["modal"]
assert m["single_precision_updates_per_step"] > 0.01, m
print(f"eigenvalues {worst:.1e}, figures {w1:.1e} (whole line), {w2:.1e} (2 ranks), "
      f"{wb:.1e} (batches); dropper forces {df:.1e} N, {db:.1e} N (batches); bounded "
      f"against every dropper {we:.1e}")
PY
