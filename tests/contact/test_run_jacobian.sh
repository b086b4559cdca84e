#!/bin/bash
# `pcsim run -snes_test_jacobian -pcsim_path full` on two small scenes: PETSc
# compares the coupled Jacobian (catenary + contact + pantograph, HHT shifts)
# with its own finite differences in every Newton iteration of 3 steps.
# Criterion ||J - Jfd||_F / ||J||_F < 1e-5: PETSc's one-sided differences
# (step ~1.5e-8 |u|) leave ~1e-7 (measured 1.6e-7 DSA-380, 7.8e-9 lumped),
# a wrong tangent term gives >= 1e-4 (the one-way damper's switch, crossed by
# the differences at the rest start, shows 4e-4).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$PCSIM_SOURCE_DIR/tests/contact/data

for scene in three-span-dsa380 three-span-lumped; do
  "$PCSIM_BIN" run "$data/$scene.yaml" -o "$tmp/$scene" -ts_max_steps 3 \
    -snes_test_jacobian -pcsim_path full > "$tmp/$scene.log" 2>&1 ||
    { cat "$tmp/$scene.log"; exit 1; }
  "$PCSIM_PYTHON" - "$tmp/$scene.log" "$scene" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
assert "full Newton path" in text, "the run did not take the full Newton path"
ratios = [float(m) for m in re.findall(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)", text)]
assert len(ratios) >= 3, f"expected a Jacobian test in each of 3 steps, got {ratios}"
print(f"{sys.argv[2]}: ||J - Jfd||_F/||J||_F = " + ", ".join(f"{r:.3g}" for r in ratios))
assert max(ratios) < 1e-5, ratios
PY
done
