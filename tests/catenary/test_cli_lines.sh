#!/bin/bash
# `pcsim static` on a line: the elasticity scene key writes elasticity.csv
# and prints the non-uniformity, summary.json lists the steady arms' pull-off
# forces and the tensioning devices; bad values of the new design and scene
# keys exit with code 2 and one message naming the file, the key and the
# reason.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
M=$PCSIM_SOURCE_DIR/meshes/lines
failures=0

# A 3-span stitched catenary with 1 m elements and balance weights.
sed -e 's/count: 10/count: 3/' -e 's/element_length: 0.5/element_length: 1.0/' "$M/stitched.yaml" \
  > "$tmp/stitched3.yaml"
echo "tensioning: {device: weight, ratio: 3}" >> "$tmp/stitched3.yaml"
cat > "$tmp/elasticity.yaml" <<SCENE
name: elasticity
catenary: {design: stitched3.yaml}
elasticity: {force: 100, from_x: 60.0, to_x: 120.0, step: 10.0}
SCENE
(cd "$tmp" && "$PCSIM_BIN" static elasticity.yaml -o out > out.log 2>&1)
grep -q "elasticity (100 N at 7 points)" "$tmp/out.log" || { cat "$tmp/out.log"; failures=$((failures + 1)); }
rows=$(grep -vc '^#' "$tmp/out/elasticity.csv")
[ "$rows" -eq 7 ] || { echo "FAIL elasticity.csv has $rows rows" >&2; failures=$((failures + 1)); }
# The per-point solves read the -elasticity_ options (docs/catenary.md): MUMPS's
# LU instead of the default Cholesky gives the same uplifts (the factorisations'
# round-off only: 1e-9 relative allows for it), and no option is left unread.
(cd "$tmp" && "$PCSIM_BIN" static elasticity.yaml -o out-lu -elasticity_pc_type lu \
  -elasticity_pc_factor_mat_solver_type mumps -options_left > out-lu.log 2>&1) ||
  { cat "$tmp/out-lu.log"; failures=$((failures + 1)); }
grep -q "There are no unused options" "$tmp/out-lu.log" || { cat "$tmp/out-lu.log"; failures=$((failures + 1)); }
"$PCSIM_PYTHON" - "$tmp/out/elasticity.csv" "$tmp/out-lu/elasticity.csv" <<'PY' || failures=$((failures + 1))
import sys
import numpy as np
a, b = (np.loadtxt(f, delimiter=",", comments="#", usecols=(0, 1)) for f in sys.argv[1:])
assert np.array_equal(a[:, 0], b[:, 0]), "positions differ"
rel = np.max(np.abs(a[:, 1] - b[:, 1]) / np.abs(a[:, 1]))
print(f"elasticity with MUMPS LU vs Cholesky: {rel:.1e} (relative)")
assert rel < 1e-9, rel
PY
"$PCSIM_PYTHON" - "$tmp/out/summary.json" <<'PY' || failures=$((failures + 1))
import json, sys
s = json.load(open(sys.argv[1]))
pull = s["steady_arm_pull_off_N"]
assert len(pull) == 2, pull                     # supports 1 and 2
assert all(250 < abs(f) < 400 for f in pull), pull
dev = s["tensioning_devices"]
assert len(dev) == 4 and all(d["device"] == "weight" for d in dev), dev
# The contact wire's ends pull with its tension (1e-4 measured); the
# messenger's with more: between the anchor and the first stitch clamp it
# also carries the stitch wire's 3.5 kN (16484 N measured).
for d in dev:
    if d["wire"] == "contact":
        assert abs(d["pull_N"] / 20000 - 1) < 1e-3, d
    else:
        assert 16000 < d["pull_N"] < 16000 + 3500, d
print("ok   summary: pull-off", [round(f, 1) for f in pull])
PY

# expect_error NAME SCENE NEEDLE... [--set PATH=VALUE]...: exit code 2, one
# line on stderr with every NEEDLE.
expect_error() {
  local name=$1 scene=$2
  shift 2
  local status=0
  local needles=() extra=()
  while [ $# -gt 0 ]; do  # NEEDLE... [--set PATH=VALUE]...
    if [ "$1" = --set ]; then extra+=(--set "$2"); shift 2; else needles+=("$1"); shift; fi
  done
  (cd "$tmp" && "$PCSIM_BIN" static "$scene" -o "$tmp/$name" "${extra[@]}" > "$tmp/$name.out" \
    2> "$tmp/$name.err") || status=$?
  local ok=1 needle
  [ "$status" -eq 2 ] || ok=0
  [ "$(grep -c . "$tmp/$name.err" || true)" -eq 1 ] || ok=0
  for needle in "${needles[@]}"; do grep -qF -- "$needle" "$tmp/$name.err" || ok=0; done
  if [ "$ok" -eq 1 ]; then
    echo "ok   $name: $(cat "$tmp/$name.err")"
  else
    echo "FAIL $name (exit $status): $(cat "$tmp/$name.err")" >&2
    failures=$((failures + 1))
  fi
}
sed 's/to_x: 120.0/to_x: 500.0/' "$tmp/elasticity.yaml" > "$tmp/bad-elasticity.yaml"
expect_error bad-elasticity bad-elasticity.yaml "bad-elasticity.yaml" "elasticity.to_x" \
  "between from_x and the line's end"
sed 's/raise: 0.3, anchor_raise: 0.6/raise: -0.3, anchor_raise: 0.6/' "$M/three-sections-short.yaml" \
  > "$tmp/bad-overlap.yaml"
printf 'name: bad\ncatenary: {design: bad-overlap.yaml}\n' > "$tmp/bad-overlap-scene.yaml"
expect_error bad-overlap bad-overlap-scene.yaml "bad-overlap.yaml" "overlap.raise" "must be positive"
# Keys checked since issue 12's review: overlapping worn stretches, an empty
# profile file, a messenger stiffness the fixed model does not use, a support
# overridden twice, presag.sag.
printf 'name: bad\ncatenary: {design: %s}\n' "$M/three-sections-short.yaml" > "$tmp/short.yaml"
expect_error bad-wear short.yaml "three-sections-short.yaml" "irregularities.wear[1]" \
  "overlaps irregularities.wear[0]" --set \
  "catenary.design.irregularities={wear: [{from: 10, to: 30, section_loss: 0.1}, {from: 20, to: 40, section_loss: 0.1}]}"
printf '# x [m], dz [m]\nx,dz\n' > "$tmp/empty-profile.csv"
expect_error empty-profile short.yaml "irregularities.profile" "empty-profile.csv" \
  "needs at least two (x, dz) points" --set "catenary.design.irregularities.profile=$tmp/empty-profile.csv"
expect_error unused-stiffness short.yaml "messenger_supports.stiffness" \
  "only for models 'spring' and 'spring_mass'" --set \
  "catenary.design.messenger_supports={model: fixed, stiffness: -1}"
expect_error override-twice short.yaml "support_overrides[1].supports[0]" "listed twice" --set \
  "catenary.design.support_overrides=[{supports: [3], steady_arms: {mass: 2}}, {supports: [3], steady_arms: {mass: 3}}]"
expect_error negative-presag short.yaml "presag.sag" "must not be negative" --set \
  "catenary.design.presag={profile: parabola, sag: -0.01}"

if [ "$failures" -ne 0 ]; then
  echo "$failures case(s) failed" >&2
  exit 1
fi
echo OK
