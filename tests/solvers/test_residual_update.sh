#!/bin/bash
# The residual after an exact Newton update (-ts_hht_residual_update,
# CoupledSystem::residual_update): on the cheap path the update Y solved
# (J0 + D) Y = R exactly, so the linear parts' products are not evaluated
# again; R(X - Y) = F_rest(X - Y) - F_rest(X) + T Y + D Y.
# Each scene runs with -ts_hht_residual_update_check, which evaluates every
# updated residual too and reports the largest difference (max norm, in N):
# it must stay below 5e-5 N, 1000 times below the Newton tolerance (5e-2 N).
# Measured 4.1e-7 to 5.3e-7 N on the 3-span scenes and 8.2e-6 to 8.7e-6 N on
# the 12-span window: the evaluated residual's own rounding, which grows with the
# absolute coordinates (K0 (U - U_ref) with U up to 720 m there; 7.6e-5 N on
# the 100-span EN 50318 line), hence the margin of ~6 over the window. Leaving
# D Y out (the contact's and switched droppers' terms) gives 1.2 N and two
# Newton iterations a step instead of one; leaving T Y out stalls Newton
# (both checked by hand). Each scene also runs with every residual evaluated
# (-ts_hht_residual_update 0): the contact forces must agree to 1e-9 of their
# maximum (measured 7e-11 to 1.6e-10: the round-off of two Newton paths).
# Scenes: linear FE with dropper slack on 1 and 2 ranks; the rigid DSA-380
# (its block refactored at every iteration: D has a block change); a moving
# window with two pantographs (pins, dashpots, J0 rebuilt at the shift).
# Where the update does not apply, every residual is evaluated: the full
# path (nonlinear catenary), the modal level (no linear parts to save) and
# an inner solve that is not a factorisation (-cheap_ksp_type gmres).
# Run time: ~15 s.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$PCSIM_SOURCE_DIR/tests/contact/data
mpirun=$PCSIM_SOURCE_DIR/scripts/mpirun.sh

run() {  # run NAME RANKS SCENE [options]
  local name=$1 np=$2 scene=$3
  shift 3
  "$mpirun" -n "$np" "$PCSIM_BIN" run "$scene" -o "$tmp/$name" --no-report --cache "$tmp/cache" \
    "$@" > "$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log"; exit 1; }
}
pair() {  # pair NAME RANKS SCENE [options]: updated (checked) and evaluated
  local name=$1 np=$2 scene=$3
  shift 3
  run "${name}_updated" "$np" "$scene" -ts_hht_residual_update_check "$@"
  run "${name}_evaluated" "$np" "$scene" -ts_hht_residual_update 0 "$@"
}
pair fe 1 "$data/three-span-lumped.yaml"
pair fe_np2 2 "$data/three-span-lumped.yaml"
pair dsa 1 "$data/three-span-dsa380.yaml" --set effects.catenary_nonlinear=false
# One shift (the leading pantograph reaches 360 m at step ~2820).
pair window 1 "$data/window-two-pantographs.yaml" --set window.spans_behind=2 \
  --set window.spans_ahead=2 -ts_max_steps 3200
run full 1 "$data/three-span-lumped.yaml" --set effects.catenary_nonlinear=true
run modal 1 "$data/three-span-lumped.yaml" --set catenary.model=modal -pcsim_accuracy_pilot false
run gmres 1 "$data/three-span-lumped.yaml" -cheap_ksp_type gmres -cheap_pc_type lu

"$PCSIM_PYTHON" - "$tmp" <<'PY'
import json, sys
import h5py
import numpy as np
d = sys.argv[1]

def summary(name):
    return json.load(open(f"{d}/{name}/summary.json"))

def forces(name):
    with h5py.File(f"{d}/{name}/results.h5") as f:
        return np.concatenate([f[f"/pantographs/{p}/contact_force"][:]
                               for p in sorted(f["/pantographs"])])

def newton_iterations(s):
    with h5py.File(f"{d}/{s}/results.h5") as f:
        steps = len(f["/time"]) - 1
    return round(summary(s)["newton_iterations_per_step"] * steps)

for name in ["fe", "fe_np2", "dsa", "window"]:
    up, ev = summary(name + "_updated"), summary(name + "_evaluated")
    iterations = newton_iterations(name + "_updated")
    # Every residual after an update is given by it (a window's shift step too).
    assert up["residuals_updated"] == iterations, (name, up["residuals_updated"], iterations)
    assert ev["residuals_updated"] == 0, (name, ev["residuals_updated"])
    assert "residual_update_gap_n" not in ev
    gap = up["residual_update_gap_n"]
    assert gap <= 5e-5, f"{name}: updated and evaluated residuals differ by {gap:.2e} N"
    a, b = forces(name + "_updated"), forces(name + "_evaluated")
    rel = np.max(np.abs(a - b)) / np.max(np.abs(b))
    assert rel <= 1e-9, f"{name}: contact forces differ by {rel:.2e} of their maximum"
    print(f"ok   {name}: {iterations} residuals updated, largest gap {gap:.1e} N, "
          f"contact forces within {rel:.1e}")
for name in ["full", "modal", "gmres"]:
    s = summary(name)
    assert s["residuals_updated"] == 0, (name, s["residuals_updated"])
    print(f"ok   {name}: every residual evaluated")
PY
