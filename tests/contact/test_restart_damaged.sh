#!/bin/bash
# A damaged checkpoint is bad input: `pcsim run --restart DIR` ends with exit 2
# and one message naming the file and what is wrong, before any work and
# with nothing left behind (before, a NaN time or a NaN in the state reached
# the time step: exit 3 or 4). An intact copy restarts (exit 0).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
"$PCSIM_BIN" run "$scene" -o "$tmp/first" --no-report -ts_max_steps 50 > "$tmp/first.log" 2>&1 ||
  { cat "$tmp/first.log"; exit 1; }
[ -f "$tmp/first/checkpoint.h5" ] || { echo "no checkpoint written"; exit 1; }
for what in t-nan step-negative U-nan dt-zero reference-inf cutoff-inf not-hdf5; do
  cp -r "$tmp/first" "$tmp/$what"
  "$PCSIM_PYTHON" - "$tmp/$what/checkpoint.h5" "$what" <<'PY'
import sys
import h5py
import numpy as np
path, what = sys.argv[1], sys.argv[2]
if what == "not-hdf5":
    open(path, "w").write("not an HDF5 file\n")
    sys.exit()
with h5py.File(path, "r+") as f:
    if what == "t-nan":
        f.attrs["t"] = np.nan
    elif what == "step-negative":
        f.attrs["step"] = -3.0
    elif what == "dt-zero":
        f.attrs["time_step"] = 0.0
    elif what == "cutoff-inf":  # the modal cut-off a restart takes
        f.attrs["modal_cutoff_hz"] = np.inf
    elif what == "U-nan":
        u = f["state/U"][:]
        u[3] = np.nan
        f["state/U"][:] = u
    elif what == "reference-inf":
        a = f["reference/A"][:]
        a[0] = np.inf
        f["reference/A"][:] = a
PY
  status=0
  "$PCSIM_BIN" run "$scene" --restart "$tmp/$what" -o "$tmp/out-$what" --no-report \
    > "$tmp/$what.log" 2>&1 || status=$?
  if [ $status -ne 2 ] || ! grep -q "checkpoint.h5" "$tmp/$what.log" ||
    [ "$(grep -c 'pcsim: error' "$tmp/$what.log")" -ne 1 ] || [ -e "$tmp/out-$what" ] ||
    [ -e "$tmp/out-$what.partial" ]; then
    echo "FAIL $what: exit $status"; cat "$tmp/$what.log"; exit 1
  fi
  echo "ok   $what: $(grep 'pcsim: error' "$tmp/$what.log")"
done
"$PCSIM_BIN" run "$scene" --restart "$tmp/first" -o "$tmp/intact" --no-report > "$tmp/intact.log" 2>&1 ||
  { cat "$tmp/intact.log"; exit 1; }
echo "ok   the intact checkpoint restarts"
