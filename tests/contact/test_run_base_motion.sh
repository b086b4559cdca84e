#!/bin/bash
# A run whose pantograph's base (the vehicle roof) moves (issue 25,
# docs/conditions.md "Vehicle excitation"), on the three-span line with the
# EN 50318 two-mass model, base driven at 10 mm, 5 Hz:
#  1. the energy balance (output.energy) holds with the base's work
#     (k z_b + c v_b) v_frame counted as external work: the limit 0.006 of
#     the turnover is test_energy_starts.sh's (HHT's numerical dissipation at
#     alpha 0.1);
#  2. a roof history from a file ({type: file}) runs and balances too.
# The Jacobian with the base motion (a load: the tangent is unchanged) is
# checked in test_run_jacobian.sh (scene three-span-lumped-base.yaml).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$PCSIM_SOURCE_DIR/tests/contact/data
# A roof history: 0 for 0.05 s, then 10 mm at 4 Hz, sampled every 2 ms.
"$PCSIM_PYTHON" -c '
import math
for k in range(400):
    t = 0.002 * k
    print(f"{t:.3f}, {0.01 * math.sin(2 * math.pi * 4 * (t - 0.05)) if t > 0.05 else 0.0:.9f}")
' > "$tmp/roof.csv"
# The same run with the base at rest: its external work, to show the base's.
"$PCSIM_BIN" run "$data/three-span-lumped.yaml" -o "$tmp/rest" --no-report \
  --set output.energy=true > "$tmp/log" 2>&1 || { cat "$tmp/log"; exit 1; }
for motion in harmonic file; do
  extra=()
  [ "$motion" = file ] &&
    extra=(--set "pantographs[0].base_motion={type: file, file: $tmp/roof.csv}")
  "$PCSIM_BIN" run "$data/three-span-lumped-base.yaml" -o "$tmp/run" --overwrite --no-report \
    "${extra[@]}" --set output.energy=true > "$tmp/log" 2>&1 || { cat "$tmp/log"; exit 1; }
  "$PCSIM_PYTHON" - "$tmp/run/summary.json" "$tmp/rest/summary.json" "$motion" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))["energy"]
rest = json.load(open(sys.argv[2]))["energy"]
ratio = abs(e["max_balance_residual_J"]) / e["turnover_J"]
base_work = e["work_external_J"] - rest["work_external_J"]
print(f"{sys.argv[3]}: max balance residual {e['max_balance_residual_J']:.3g} J, "
      f"{ratio:.4f} of the turnover {e['turnover_J']:.3g} J; the base's work about "
      f"{base_work:.3g} J")
assert ratio <= 0.006, ratio
# Harmonic: the base's net work (0.97 J measured) is 50x the residual, so a
# balance without it would fail (the file's oscillation nets only 0.14 J).
if sys.argv[3] == "harmonic":
    assert abs(base_work) > 10 * abs(e["max_balance_residual_J"]), base_work
PY
done
