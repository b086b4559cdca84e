#!/bin/bash
# A restart of a modal run whose accuracy pilot raised the cut-off (README
# "Interrupted runs and restarts"; docs/fidelity.md, "The modal cut-off is
# chosen per scene"): the restart runs no pilot, so it takes the cut-off the
# checkpoint records and the checkpointed run's estimate from its
# summary.json. On the small three-span line the pilot raises the default
# 40.5 Hz once, to 50.6 Hz; a checkpoint every 500 steps of 1206. Until
# 2026-12-05 the restart built the default basis and stopped (exit 3:
# "restore: a vector of 296 values for a system of another size").
# Checked: exit 0, the same cut-off, the contact force equal to the
# uninterrupted run's bit for bit (one rank: the same arithmetic), the same
# pilot estimate in summary.json.
set -euo pipefail
fail() { echo "FAIL: $*"; exit 1; }
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# The suite's PETSC_OPTIONS switch the pilot off; the command line wins.
run() {
  "$PCSIM_BIN" run "$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml" \
    --set catenary.model=modal --set output.checkpoint_every=500 --no-report --cache cache \
    -pcsim_accuracy_pilot true "$@"
}
run -o whole > whole.log 2>&1 || { cat whole.log; fail "the uninterrupted run"; }
run --restart whole -o continued > continued.log 2>&1 || { cat continued.log; fail "the restart"; }
grep -q "^  restarted from whole at t = 1.0000 s, step 1000$" continued.log ||
  { cat continued.log; fail "not restarted from step 1000"; }
grep -q "^  accuracy: the estimate of the checkpointed run's pilot (whole/summary.json)$" continued.log ||
  { cat continued.log; fail "the estimate's source is not said"; }
"$PCSIM_PYTHON" - <<'PY'
import json
import h5py
import numpy as np
whole, continued = (json.load(open(f"{d}/summary.json")) for d in ("whole", "continued"))
pilot = whole["accuracy_estimate"]["pilot"]
assert pilot["cutoff_raises"] >= 1, pilot  # the case: a cut-off the scene's default is not
assert continued["modal"]["cutoff_hz"] == whole["modal"]["cutoff_hz"] == pilot["cutoff_hz"], \
    (continued["modal"]["cutoff_hz"], whole["modal"]["cutoff_hz"], pilot["cutoff_hz"])
assert continued["accuracy_estimate"]["pilot"] == pilot
assert continued["restart_step"] == 1000, continued["restart_step"]
forces = []
for d in ("whole", "continued"):
    with h5py.File(f"{d}/results.h5", "r") as f:
        forces.append(f["pantographs/lumped/contact_force"][:])
assert forces[0].shape == forces[1].shape and np.array_equal(forces[0], forces[1]), \
    np.abs(forces[0] - forces[1]).max()
print(f"modal restart at {continued['modal']['cutoff_hz']:.1f} Hz (raised by the pilot): "
      f"{forces[0].size} contact forces equal bit for bit")
PY
