#!/bin/bash
# Every XDMF file pcsim writes opens in ParaView's default XDMF reader
# (Xdmf3ReaderS, from Debian's python3-paraview: scripts/setup-deps.sh), headless:
# `pcsim static`, `pcsim modes` and a short `pcsim run` with snapshots (2 ranks).
# xdmf_paraview_check.py checks the point, cell and time-step counts and that
# the fields read equal the HDF5 datasets. Every *.xdmf written must be checked.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
check=$PCSIM_SOURCE_DIR/tests/output/xdmf_paraview_check.py
if ! "$PCSIM_PYTHON" -c "import paraview.simple" 2> "$tmp/import.err"; then
  echo "FAIL: ParaView's Python modules are missing (scripts/setup-deps.sh installs python3-paraview)"
  cat "$tmp/import.err"
  exit 1
fi

"$PCSIM_BIN" static "$PCSIM_SOURCE_DIR/runs/en50318-static.yaml" -o "$tmp/static" > "$tmp/static.log"
"$PCSIM_BIN" modes "$PCSIM_SOURCE_DIR/runs/en50318-static.yaml" -o "$tmp/modes" > "$tmp/modes.log"
# The short EN 50318 run with a snapshot every 5 steps: 20 steps give the
# snapshots of steps 0, 5, 10, 15 and 20.
sed -e "s|\.\./\.\./\.\./meshes/|$PCSIM_SOURCE_DIR/meshes/|" \
  "$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml" > "$tmp/short.yaml"
printf 'output:\n  snapshot_every: 5\n' >> "$tmp/short.yaml"
timeout 300 mpirun -n 2 "$PCSIM_BIN" run "$tmp/short.yaml" -o "$tmp/run" -ts_max_steps 20 \
  > "$tmp/run.log"

# Expected time steps per kind: static none, modes one per mode (count: 20 in
# the scene), snapshots 5.
declare -A steps=([static]=0 [modes]=20 [snapshots]=5)
checked=0
while IFS= read -r xdmf; do
  kind=$(basename "$xdmf" .xdmf)
  if [ -z "${steps[$kind]+set}" ]; then
    echo "FAIL: $xdmf is an XDMF file this test does not know"
    exit 1
  fi
  if ! grep -q 'Format="HDF"' "$xdmf" || grep -q 'Format="HDF5"' "$xdmf"; then
    echo "FAIL: $xdmf: DataItems must say Format=\"HDF\""
    exit 1
  fi
  # A reader that cannot parse the file aborts (SIGABRT): the status says so.
  timeout 300 "$PCSIM_PYTHON" "$check" "$xdmf" "$kind" "${steps[$kind]}"
  checked=$((checked + 1))
done < <(find "$tmp/static" "$tmp/modes" "$tmp/run" -name '*.xdmf' | sort)
# static/static.xdmf, modes/{static,modes}.xdmf, run/{static,snapshots}.xdmf
if [ "$checked" -ne 5 ]; then
  echo "FAIL: $checked XDMF files checked, expected 5"
  exit 1
fi
echo "ok: $checked XDMF files open in ParaView's XDMF3 reader"
