#!/usr/bin/env bash
# `pcsim modes` with a frequency limit (SLEPc spectrum slicing) returns exactly
# the modes below the limit that a count-based shift-and-invert solve finds,
# with the same frequencies (relative 1e-8).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
PY=${PCSIM_PYTHON:-/usr/bin/python3}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cat >"$WORK/slice.yaml" <<YAML
name: slice
catenary: {design: $PCSIM_SOURCE_DIR/tests/catenary/data/two-span.yaml}
modes: {max_frequency_hz: 3.0}
YAML
"$PCSIM_BIN" modes "$WORK/slice.yaml" -o "$WORK/slice" >"$WORK/slice.log" 2>&1
"$PCSIM_BIN" modes "$WORK/slice.yaml" -o "$WORK/count" -modes_fmax 0 -eps_nev 40 >"$WORK/count.log" 2>&1
"$PY" - "$WORK" <<'PY'
import json, sys
work = sys.argv[1]
sliced = json.load(open(f"{work}/slice/summary.json"))["catenary_frequencies_hz"]
counted = [f for f in json.load(open(f"{work}/count/summary.json"))["catenary_frequencies_hz"] if f < 3.0]
assert len(counted) < 40, "count-based solve did not reach 3 Hz"
assert len(sliced) == len(counted), f"{len(sliced)} sliced vs {len(counted)} counted modes below 3 Hz"
worst = max(abs(a / b - 1) for a, b in zip(sliced, counted))
assert worst < 1e-8, f"frequencies differ by {worst:.2e}"
print(f"ok: {len(sliced)} modes below 3 Hz, largest relative difference {worst:.1e}")
PY
