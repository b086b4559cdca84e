#!/bin/bash
# `pcsim static ... -snes_test_jacobian`: the analytic Jacobian of the static
# problem and of the form-finding (augmented) problem agrees with PETSc's
# finite-difference Jacobian at every Newton iteration,
#   ||J - Jfd||_F / ||J||_F < 1e-5,
# on a two-span catenary (tests/catenary/data/two-span.yaml, ~1500 unknowns:
# the FD Jacobian costs one residual evaluation per unknown).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
D=$PCSIM_SOURCE_DIR/tests/catenary/data

# wind: the form-finding, then the static solve under a 30 m/s cross-wind
# (its drag a dead load: no tangent of its own; docs/conditions.md).
for case in jacobian-static jacobian-form-finding jacobian-form-finding:wind; do
  IFS=: read -r scene extra <<< "$case"
  args=()
  [ "$extra" = wind ] && args=(--set conditions.wind.speed=30)
  "$PCSIM_BIN" static "$D/$scene.yaml" -o "$tmp/$case" -snes_test_jacobian "${args[@]}" \
    > "$tmp/$case.log" 2>&1 || {
    cat "$tmp/$case.log" >&2
    echo "FAIL $case: pcsim static failed" >&2
    exit 1
  }
  "$PCSIM_PYTHON" - "$tmp/$case.log" "$tmp/$case/summary.json" "$case" <<'PY'
import json, re, sys
log, summary, case = sys.argv[1:]
text = open(log).read()
ratios = [float(m) for m in re.findall(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F\s*=\s*([-+0-9.eEinfa]+)", text)]
s = json.load(open(summary))
# One test per Jacobian evaluation: at least the first Newton step.
assert len(ratios) >= 1, "no '||J - Jfd||_F/||J||_F' line in the output:\n" + text[-2000:]
assert len(ratios) >= s["snes_iterations"], (len(ratios), s["snes_iterations"])
worst = max(ratios)
assert worst < 1e-5, f"{case}: ||J - Jfd||_F/||J||_F = {ratios}"
assert s["form_finding"] == case.startswith("jacobian-form-finding"), s["form_finding"]
assert ("blow_off" in s) == case.endswith(":wind"), s.keys()
print(f"ok   {case}: {len(ratios)} Jacobians tested, max ||J - Jfd||_F/||J||_F = {worst:.2e}, "
      f"{s['dofs']} catenary DOFs")
PY
done
echo OK
