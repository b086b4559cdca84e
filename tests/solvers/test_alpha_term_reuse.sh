#!/bin/bash
# The HHT alpha-term F(t_n, U_n, V_n, 0) taken from the previous step's last
# residual (-ts_hht_reuse_alpha_term, include/pcsim/solvers/hht.hpp) on the
# paths of a run: linear FE (cheap path), nonlinear FE (full path), the modal
# level, a moving window (its shifts replace the state: the next step
# evaluates), and a scene with a DSA-380 (configuration-dependent mass M(q):
# its product at the step's state). Each against the same run with every alpha-term evaluated
# (-ts_hht_reuse_alpha_term 0): the contact forces must agree to round-off,
# 1e-9 of their maximum (measured up to 4e-11 on EN 50318 at 10 and 100 spans;
# a reused term without its inertia or with a stale load differs by 1e-5 and
# more), and the counts of -ts_view must say which steps reused it.
# Checkpoints carry the reused term (test_run_restart.sh: a restart is bit for
# bit); a head force set from Python invalidates it (stepping_check.py, part 6).
# Run time: ~1 min.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$PCSIM_SOURCE_DIR/tests/contact/data

pair() {  # pair NAME SCENE [options]: the run with the alpha-term reused and evaluated
  local name=$1 scene=$2
  shift 2
  for reuse in 1 0; do
    "$PCSIM_BIN" run "$scene" -o "$tmp/$name$reuse" --no-report --cache "$tmp/cache" \
      -ts_view -ts_hht_reuse_alpha_term $reuse "$@" > "$tmp/$name$reuse.log" 2>&1 ||
      { cat "$tmp/$name$reuse.log"; exit 1; }
  done
}
pair fe "$data/three-span-lumped.yaml"
pair nonlinear "$data/three-span-lumped.yaml" --set effects.catenary_nonlinear=true
pair modal "$data/three-span-lumped.yaml" --set catenary.model=modal -pcsim_accuracy_pilot false
pair dsa "$data/three-span-dsa380.yaml" --set effects.catenary_nonlinear=false
# One shift (the leading pantograph reaches 360 m at step ~2820).
pair window "$data/window-two-pantographs.yaml" --set window.spans_behind=2 \
  --set window.spans_ahead=2 -ts_max_steps 3200

"$PCSIM_PYTHON" - "$tmp" <<'PY'
import re, sys
import h5py
import numpy as np
d = sys.argv[1]

def counts(name):
    text = open(f"{d}/{name}.log").read()
    m = re.search(r"alpha-term: (.*) \((\d+) steps from it, (\d+) evaluated\)", text)
    assert m, f"{name}: no alpha-term line in -ts_view"
    return int(m.group(2)), int(m.group(3))

def forces(name):
    with h5py.File(f"{d}/{name}/results.h5") as f:
        return np.concatenate([f[f"/pantographs/{p}/contact_force"][:]
                               for p in sorted(f["/pantographs"])])

# name: (steps that evaluate with reuse on) -- the first; one more per shift
expected_evaluated = {"fe": 1, "nonlinear": 1, "modal": 1, "window": 2, "dsa": 1}
for name in ["fe", "nonlinear", "modal", "window", "dsa"]:
    reused, evaluated = counts(name + "1")
    steps = reused + evaluated
    off_reused, off_evaluated = counts(name + "0")
    assert (off_reused, off_evaluated) == (0, steps), (name, off_reused, off_evaluated)
    assert evaluated == expected_evaluated[name], (name, reused, evaluated)
    a, b = forces(name + "1"), forces(name + "0")
    gap = np.max(np.abs(a - b)) / np.max(np.abs(b))
    assert gap <= 1e-9, f"{name}: reused and evaluated alpha-terms differ by {gap:.2e}"
    print(f"ok   {name}: {reused} of {steps} steps reused the alpha-term, "
          f"contact forces within {gap:.1e} of the evaluated run")
PY
