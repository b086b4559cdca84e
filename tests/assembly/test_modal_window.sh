#!/bin/bash
# The modal catenary in a moving window (catenary.modal.method window/auto;
# docs/fidelity.md, "Lines of any length: the modal window"), end to end
# through `pcsim run` on one rank:
# 1. Every mode of the window and exact bars (small-window-modal-all.yaml,
#    374 unknowns) equal the linearised FE window (small-window-linear.yaml)
#    on the full Newton path over 882 steps with two window shifts, the rear
#    end pinned (the line's anchor) before the first: with a complete basis the
#    shift eta' = P eta, P = B^T M S B, is the FE shift exactly up to P's
#    rounding to single precision (catenary::ReducedBasis::shift), the end
#    dashpots and pins are the FE ones. max |dFc| <= 1e-7 max Fc: measured
#    3.0e-8 (2.9e-8 at the scenes' dt of 1 ms, 1764 steps; 2.4e-10 with P
#    in double at 1 ms, the floor of the Newton tolerance
#    -snes_atol 1e-6 N as in test_modal_catenary.sh; P's entries are
#    rounded by up to 2^-24 = 6e-8 of themselves); a shift that moved the
#    state by one node, or a missing dashpot, gives > 1e-3.
# 2. -snes_test_jacobian on the truncated modal window (169 vectors, pins
#    active, dashpots): the operator against PETSc's finite differences on
#    the cheap path (J0 + rank-one terms of contact, pins, dashpots) and the
#    full path: ||J - Jfd||_F/||J||_F < 1e-5 (measured <= 3.1e-11; a dashpot's
#    tangent without its shift_v gives ~1e-2).
# 3. The method's choice: auto keeps the whole line for a short one and says
#    why, takes a window on a long line of identical spans (no 'window'
#    section), and 'whole' with a 'window' section is one error, exit 2,
#    nothing written.
# 4. The bounded dropper check in a window, where no record anchors it (its
#    droppers are not recorded): the single-precision updates measured from
#    the last exact anchor find every slack dropper (16 of the 36 go slack
#    after the ramp start, as the FE line without a window shows): the
#    contact force equals that of evaluating every dropper at every state to
#    1e-11 of max Fc (measured 4.6e-13: only the order of sums differs), with
#    single-precision updates made (0.42 per step) and an exact anchor at
#    most every 100 steps (measured 1 in 1764: the bound follows the distance
#    from the exact anchor, it does not add up over the updates). The cache
#    holds every mode's data from 1.: they do not serve this cut-off (they
#    have no dropper shapes), so its basis has its 12 shapes (169 vectors; it
#    had 157 when they served it).
# 5. A cut-off raised by the accuracy pilot (once here: 40.5 to 50.6 Hz, 27
#    modes computed, 157 kept)
#    computes only the modes above the last one, and the window's shift
#    products of the new vectors only (simulation::ModalDataBuilder): the run
#    equals one whose modes at the raised cut-off were computed at once, in a
#    cache of its own, to 1e-9 of max Fc (measured 4.0e-12: the eigenvectors
#    of other slicing intervals, equal to round-off; without the products of
#    the new rows with the old columns the contact force reaches 6e9 N).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$PCSIM_SOURCE_DIR/tests/assembly/data
run() {  # run NAME SCENE [options]: pcsim run, output in $tmp/NAME, log in $tmp/NAME.log
  local name=$1 scene=$2
  shift 2
  "$PCSIM_BIN" run "$scene" -o "$tmp/$name" --cache "${CACHE:-$tmp/cache}" --no-report "$@" \
    > "$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log"; exit 1; }
}

# 1. Every mode = FE, across shifts.
# At dt = 2 ms, twice the scenes' (the equality holds at any dt): 882 steps
# of the modal run's dense LU of 374 unknowns instead of 1764, at 1.8 Newton
# iterations a step instead of 1.1 (its log; 42 s of stepping instead of 57).
run fe "$data/small-window-linear.yaml" -pcsim_path full -snes_atol 1e-6 --set simulation.dt=0.002
run all "$data/small-window-modal-all.yaml" -snes_atol 1e-6 --set simulation.dt=0.002
grep -q "modal method: window (the scene's 'window')" "$tmp/all.log" || { cat "$tmp/all.log"; exit 1; }
"$PCSIM_PYTHON" - "$tmp/fe" "$tmp/all" <<'PY'
import json, sys
import h5py
import numpy as np
fe, modal = (h5py.File(d + "/results.h5", "r") for d in sys.argv[1:3])
a = fe["pantographs/pantograph/contact_force"][:]
b = modal["pantographs/pantograph/contact_force"][:]
assert a.shape == b.shape, (a.shape, b.shape)
shifts = [json.load(open(d + "/summary.json"))["window_shifts"] for d in sys.argv[1:3]]
assert shifts == [2, 2], shifts
rel = np.max(np.abs(a - b)) / np.max(np.abs(a))
print(f"every mode against FE in a window with {shifts[0]} shifts: max |dFc| / max Fc = {rel:.2e}")
assert rel <= 1e-7, rel
PY

# 2. The Jacobian of the truncated modal window.
printf 'base: %s\ncatenary: {model: modal}\n' "$data/small-window-linear.yaml" > "$tmp/truncated.yaml"
for path in cheap full; do
  run "jacobian-$path" "$tmp/truncated.yaml" -ts_max_steps 3 -snes_test_jacobian -pcsim_path "$path"
  "$PCSIM_PYTHON" - "$tmp/jacobian-$path.log" "$path" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
blocks = text.split("---------- Testing Jacobian")[1:]
ratios = [float(re.search(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)", b).group(1))
          for b in blocks if not b.startswith(" for preconditioner")]
assert len(ratios) >= 3, ratios
print(f"modal window ({sys.argv[2]}): ||J - Jfd||_F/||J||_F = " + ", ".join(f"{r:.3g}" for r in ratios))
assert max(ratios) < 1e-5, ratios
PY
done

# 3. The choice of method.
sed '/^window:/d; s/spans.count: 12/spans.count: 6/' "$data/small-window-linear.yaml" > "$tmp/short.yaml"
sed '/^window:/d; s/spans.count: 12/spans.count: 40/' "$data/small-window-linear.yaml" > "$tmp/long.yaml"
sed -i "s#three-span-small.yaml#$data/three-span-small.yaml#; s#\.\./\.\./\.\./meshes#$PCSIM_SOURCE_DIR/meshes#" \
  "$tmp/short.yaml" "$tmp/long.yaml"
sed -i 's/end_x: 100.0/end_x: 88.0/' "$tmp/short.yaml"
run short "$tmp/short.yaml" --set catenary.model=modal -ts_max_steps 5
grep -q "modal method: whole (auto: the line (6 spans) is shorter than 2 x a window" "$tmp/short.log" ||
  { cat "$tmp/short.log"; exit 1; }
run long "$tmp/long.yaml" --set catenary.model=modal -ts_max_steps 5
grep -q "modal method: window (auto: a line of 40 identical spans, a window of 7)" "$tmp/long.log" ||
  { cat "$tmp/long.log"; exit 1; }
# `pcsim check` names the same choice, before any work.
for case in short long; do
  "$PCSIM_BIN" check "$tmp/$case.yaml" --set catenary.model=modal > "$tmp/check-$case.log" 2>&1 ||
    { cat "$tmp/check-$case.log"; exit 1; }
done
grep -q "modal method whole (auto: the line (6 spans) is shorter than 2 x a window" \
  "$tmp/check-short.log" || { cat "$tmp/check-short.log"; exit 1; }
grep -q "modal method window (auto: a line of 40 identical spans, a window of 7);" \
  "$tmp/check-long.log" || { cat "$tmp/check-long.log"; exit 1; }
"$PCSIM_PYTHON" -c "
import json, sys
s = json.load(open('$tmp/long/summary.json'))
assert s['modal']['method'] == 'window', s['modal']
" || exit 1
status=0
"$PCSIM_BIN" run "$data/small-window-modal-all.yaml" --set catenary.modal.method=whole \
  -o "$tmp/refused" > "$tmp/refused.log" 2>&1 || status=$?
[ "$status" -eq 2 ] && [ ! -e "$tmp/refused" ] && [ "$(wc -l < "$tmp/refused.log")" -eq 1 ] &&
  grep -q "catenary.modal.method.*whole cannot be combined with a moving window" "$tmp/refused.log" ||
  { echo "whole with a window: exit $status"; cat "$tmp/refused.log"; exit 1; }
# 4. Bounded against every dropper in the truncated window.
run bounded "$tmp/truncated.yaml" -pcsim_accuracy_pilot false
run every "$tmp/truncated.yaml" --set catenary.modal.droppers=all -pcsim_accuracy_pilot false
"$PCSIM_PYTHON" - "$tmp/bounded" "$tmp/every" <<'PY'
import json, sys
import h5py
import numpy as np
a, b = (h5py.File(d + "/results.h5", "r")["pantographs/pantograph/contact_force"][:]
        for d in sys.argv[1:3])
rel = np.max(np.abs(a - b)) / np.max(np.abs(a))
m = json.load(open(sys.argv[1] + "/summary.json"))["modal"]
half, exact = m["half_precision_updates_per_step"], m["exact_updates_per_step"]
print(f"bounded vs every dropper in a window: {rel:.2e}; {half:.3f} half-precision updates "
      f"and {exact:.4f} exact anchors per step")
assert rel <= 1e-11, rel
# A window records no dropper forces: its check's updates are in half
# precision (src/assembly/rounded_rows.cpp), and they are exercised; a
# single-precision one only renews their base (src/assembly/modal_slack_set.cpp;
# none in this short run, tests/simulation/test_modal_parts.sh has them).
assert half > 0.1 and m["single_precision_updates_per_step"] <= half, m
assert exact <= 0.01, m
# The cache holds every mode's data (1.) besides: they serve only every mode,
# so this basis has its dropper shapes (with them it is the basis computed
# in a cache of its own).
assert m["basis_size"] == m["eigenmodes"] + 12 == 169, m
PY
# 5. The pilot's raise against the modes at once.
CACHE=$tmp/raise-cache run raised "$tmp/truncated.yaml" -pcsim_accuracy_pilot true
grep -q "^      27 modes computed, the 157 below 40.5 Hz kept from the last$" \
  "$tmp/raised.log" || { cat "$tmp/raised.log"; exit 1; }
cutoff=$("$PCSIM_PYTHON" -c "import json; print(repr(json.load(open('$tmp/raised/summary.json'))['modal']['cutoff_hz']))")
CACHE=$tmp/at-once-cache run at-once "$tmp/truncated.yaml" -pcsim_accuracy_pilot false \
  --set catenary.max_frequency_hz="$cutoff"
"$PCSIM_PYTHON" - "$tmp/raised" "$tmp/at-once" <<'PY'
import sys
import h5py
import numpy as np
a, b = (h5py.File(d + "/results.h5", "r")["pantographs/pantograph/contact_force"][:]
        for d in sys.argv[1:3])
rel = np.max(np.abs(a - b)) / np.max(np.abs(a))
print(f"raised cut-off, modes above the last only, against at once: {rel:.2e}")
assert rel <= 1e-9, rel
PY
echo "test_modal_window: ok"
