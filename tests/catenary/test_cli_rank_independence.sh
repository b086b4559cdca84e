#!/bin/bash
# pcsim-test-processors: 2
# Rank independence of `pcsim modes runs/en50318-static.yaml` (form-finding,
# static configuration and the first 20 catenary frequencies of the EN 50318
# reference catenary): 1, 2 and 3 ranks agree to 1e-9 (relative).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for np in 1 2 3; do
  "$PCSIM_SOURCE_DIR/scripts/mpirun.sh" -n "$np" "$PCSIM_BIN" modes \
    "$PCSIM_SOURCE_DIR/runs/en50318-static.yaml" -o "$tmp/np$np" > "$tmp/np$np.log" 2>&1 || {
    cat "$tmp/np$np.log" >&2
    echo "FAIL: pcsim modes on $np rank(s)" >&2
    exit 1
  }
done

"$PCSIM_PYTHON" - "$tmp" <<'PY'
import json, sys
import h5py, numpy as np
d = sys.argv[1]
tol = 1e-9
runs = {}
for np_ in (1, 2, 3):
    s = json.load(open(f"{d}/np{np_}/summary.json"))
    with h5py.File(f"{d}/np{np_}/static.h5", "r") as f:
        values = f["/nodes/values"][:]
    assert s["ranks"] == np_, (s["ranks"], np_)
    runs[np_] = (np.array(s["catenary_frequencies_hz"]), values, s)
f1, v1, s1 = runs[1]
assert len(f1) == 20, len(f1)
assert np.all(np.diff(f1) >= 0) and f1[0] > 0, f1
assert s1["max_height_error_m"] <= 1e-4 and s1["max_tension_error_rel"] <= 1e-3, s1
# Relative to the largest magnitude of each of the 6 node values (x, y, z,
# x', y', z'), so that the small lateral and vertical components count too.
scale = np.max(np.abs(v1), axis=0)
assert np.all(scale > 0), scale
for np_ in (2, 3):
    f, v, s = runs[np_]
    assert len(f) == 20, (np_, len(f))
    df = np.max(np.abs(f / f1 - 1))
    assert v.shape == v1.shape, (v.shape, v1.shape)
    dv = np.max(np.abs(v - v1) / scale)
    print(f"{np_} ranks vs 1: max relative frequency difference {df:.2e}, "
          f"max node-value difference / max |value| (per component) {dv:.2e}")
    assert df <= tol, f"frequencies on {np_} ranks differ by {df:.3e} (relative): {f} vs {f1}"
    assert dv <= tol, f"static configuration on {np_} ranks differs by {dv:.3e} (relative)"
print("OK")
PY
