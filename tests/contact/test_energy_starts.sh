#!/bin/bash
# The energy balance (output.energy: E - E0 = W_ext + W_diss every step)
# holds for every start kind, with the ramp's work counted exactly where the
# residual ramps the static force: static, ramp (20 m) and gap starts (the
# latter with a ramp_distance given, which a gap start ignores: its power
# once reported work for a ramp that did not exist, a balance residual of 18 %
# of the turnover). Measured max |balance residual| / turnover: static
# 0.0034, ramp 0.0019, gap 0.0038 (HHT's numerical dissipation at alpha 0.1
# and the gap start's impact); the limit 0.006 sits 1.6x above the worst and
# 30x below the bug.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
for start in static ramp "{gap: 0.01}"; do
  "$PCSIM_BIN" run "$scene" -o "$tmp/run" --overwrite --no-report --set "pantographs[0].start=$start" \
    --set "pantographs[0].ramp_distance=20" --set output.energy=true > "$tmp/log" 2>&1 ||
    { cat "$tmp/log"; exit 1; }
  /usr/bin/python3 - "$tmp/run/summary.json" "$start" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))["energy"]
ratio = abs(e["max_balance_residual_J"]) / e["turnover_J"]
assert ratio <= 0.006, f"{sys.argv[2]} start: balance residual {ratio:.4f} of the turnover"
print(f"ok   {sys.argv[2]} start: max balance residual {ratio:.4f} of the turnover")
PY
done
