#!/bin/bash
# runs/bench/loss_samples.py places each interruption's start and end between
# samples (docs/fidelity.md, "What is left in the loss of contact"): two
# synthetic runs whose contact forces are one clipped sine, the other's
# shifted by a known time (or lowered), sampled at 1 ms, must give that
# shift to a few microseconds, far below the sample it is finer than.
set -euo pipefail
: "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$PCSIM_PYTHON" - "$work" <<'EOF'
import json, os, sys
import h5py
import numpy as np

root = sys.argv[1]
t = np.arange(0.0, 4.0, 1e-3)
def write(name, force):
    os.makedirs(os.path.join(root, name))
    with open(os.path.join(root, name, "summary.json"), "w") as f:
        json.dump({"analysis": {"from_x": 0.0, "to_x": 1e9}}, f)
    with h5py.File(os.path.join(root, name, "results.h5"), "w") as f:
        f["time"] = t
        f["pantographs/pantograph/position"] = 83.3 * t
        f["pantographs/pantograph/contact_force"] = force
# 100 + 150 sin(2 pi 2 t), clipped at zero: an interruption of 116 ms a period.
clipped = lambda s, offset=0.0: np.maximum(0.0, 100 + offset + 150 * np.sin(2 * np.pi * 2 * s))
write("reference", clipped(t))
write("later", clipped(t - 3e-4))          # every instant 0.3 ms later
write("lower", clipped(t, offset=-1.5))    # starts earlier, ends later
EOF

summary() {
  "$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/runs/bench/loss_samples.py" "$work/reference" "$work/$1" |
    sed -n 's/.*mean: start \([-+0-9.]*\) ms, end \([-+0-9.]*\) ms, duration \([-+0-9.]*\) ms/\1 \2 \3/p'
}

check() {  # name, expected start, end, duration [ms]
  local got
  got=$(summary "$1")
  [ -n "$got" ] || { echo "FAIL: $1: no interruptions line"; exit 1; }
  # The line through the two samples next to a crossing misses it by at most
  # |f''| dt² / |f'| = 0.011 ms on this sine (f' = 1.4e3 N/s, f'' = 1.6e4 N/s²
  # there): a shift between two runs by at most 0.022 ms, a duration's (two
  # crossings of each run) by 0.044 ms; counting samples
  # instead would be off by up to half a sample (0.5 ms) on each.
  "$PCSIM_PYTHON" - "$1" "$got" "$2" "$3" "$4" <<'EOF' || exit 1
import sys
name, got, expected = sys.argv[1], [float(v) for v in sys.argv[2].split()], [float(v) for v in sys.argv[3:]]
for what, g, e, tol in zip(("start", "end", "duration"), got, expected, (0.022, 0.022, 0.044)):
    if abs(g - e) > tol:
        sys.exit(f"FAIL: {name}: {what} shift {g:+.3f} ms, expected {e:+.3f} ms")
print(f"ok: {name}: start {got[0]:+.3f}, end {got[1]:+.3f}, duration {got[2]:+.3f} ms")
EOF
}

check later 0.300 0.300 0.000
# Lowered by 1.5 N: the zero crossings of 100 + 150 sin move by
# asin(101.5/150) - asin(100/150) = 0.0135 rad, / (2 pi 2) = 1.074 ms each.
check lower -1.074 1.074 2.148
echo "loss_samples: interruption shifts placed between samples"
