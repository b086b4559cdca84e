#!/bin/bash
# Every XDMF file pcsim writes opens in ParaView's default XDMF reader
# (Xdmf3ReaderS, from Debian's python3-paraview: scripts/setup-deps.sh), and
# ParaView colours it: `pcsim static`, `pcsim modes` and a short `pcsim run`
# with snapshots (2 ranks) on the small three-span catenary
# (tests/contact/data). xdmf_paraview_check.py checks the point, cell and
# time-step counts, that every block has the same node arrays, that the fields
# read (node fields, a mode's frequency_hz and vertical, the pantographs)
# equal the HDF5 datasets, and renders each file coloured by a node field on
# a virtual X display (Xvfb, Mesa) checking that the lines are coloured. Every
# *.xdmf written must be checked. PCSIM_KEEP_RENDERS=DIR keeps the pictures.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:?}"
tmp=$(mktemp -d)
xvfb=""
trap '[ -z "$xvfb" ] || kill "$xvfb"; rm -rf "$tmp"' EXIT
check=$PCSIM_SOURCE_DIR/tests/output/xdmf_paraview_check.py
data=$PCSIM_SOURCE_DIR/tests/contact/data
if ! "$PCSIM_PYTHON" -c "import paraview.simple" 2> "$tmp/import.err"; then
  echo "FAIL: ParaView's Python modules are missing (scripts/setup-deps.sh installs python3-paraview)"
  cat "$tmp/import.err"
  exit 1
fi
# ParaView renders through OpenGL on an X display: a virtual one (Xvfb, Mesa),
# started here; -displayfd tells its number once it accepts clients (xvfb-run
# gives no such guarantee: ParaView may connect before the server is up).
if ! command -v Xvfb > /dev/null; then
  echo "FAIL: Xvfb is missing (scripts/setup-deps.sh installs xvfb)"
  exit 1
fi
exec 3> "$tmp/display"
Xvfb -displayfd 3 -noreset -nolisten tcp -screen 0 1024x768x24 2> "$tmp/xvfb.log" &
xvfb=$!
exec 3>&-
for _ in $(seq 100); do
  [ -s "$tmp/display" ] && break
  sleep 0.1
done
if [ ! -s "$tmp/display" ]; then
  echo "FAIL: Xvfb did not start"
  cat "$tmp/xvfb.log"
  exit 1
fi
export DISPLAY=:$(head -1 "$tmp/display")

# The three-span test catenary (point masses: clamps, steady arms), 10 modes.
cat > "$tmp/three-span-static.yaml" << SCENE
name: three-span-static
catenary: {design: $data/three-span.yaml, form_finding: true}
modes: {count: 10}
SCENE
"$PCSIM_BIN" static "$tmp/three-span-static.yaml" -o "$tmp/static" > "$tmp/static.log"
"$PCSIM_BIN" modes "$tmp/three-span-static.yaml" -o "$tmp/modes" > "$tmp/modes.log"
# The short three-span run with a snapshot every 5 steps: 20 steps give the
# snapshots of steps 0, 5, 10, 15 and 20.
sed -e "s|\.\./\.\./\.\./meshes/|$PCSIM_SOURCE_DIR/meshes/|" \
  -e "s|design: three-span.yaml|design: $data/three-span.yaml|" \
  "$data/three-span-lumped.yaml" > "$tmp/short.yaml"
printf 'output:\n  snapshot_every: 5\n' >> "$tmp/short.yaml"
timeout 300 mpirun -n 2 "$PCSIM_BIN" run "$tmp/short.yaml" -o "$tmp/run" -ts_max_steps 20 \
  > "$tmp/run.log"

# Expected time steps per kind: static none, modes one per mode, snapshots 5.
declare -A steps=([static]=0 [modes]=10 [snapshots]=5)
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
  png=$tmp/$(basename "$(dirname "$xdmf")")-$kind.png
  # A reader that cannot parse the file aborts (SIGABRT): the status says so.
  timeout 300 "$PCSIM_PYTHON" "$check" "$xdmf" "$kind" "${steps[$kind]}" "$png"
  if [ -n "${PCSIM_KEEP_RENDERS:-}" ]; then
    mkdir -p "$PCSIM_KEEP_RENDERS" && cp "$png" "$PCSIM_KEEP_RENDERS/"
  fi
  checked=$((checked + 1))
done < <(find "$tmp/static" "$tmp/modes" "$tmp/run" -name '*.xdmf' | sort)
# static/static.xdmf, modes/{static,modes}.xdmf, run/{static,snapshots}.xdmf
if [ "$checked" -ne 5 ]; then
  echo "FAIL: $checked XDMF files checked, expected 5"
  exit 1
fi
# energy.h5 and results.h5 carry the same provenance (a run with output.energy).
printf '  energy: true\n' >> "$tmp/short.yaml"
timeout 300 "$PCSIM_BIN" run "$tmp/short.yaml" -o "$tmp/energy" -ts_max_steps 2 > "$tmp/energy.log"
"$PCSIM_PYTHON" - "$tmp/energy" << 'PY'
import sys
import h5py
folder = sys.argv[1]
results, energy = (dict(h5py.File(f"{folder}/{f}.h5", "r").attrs) for f in ("results", "energy"))
keys = ["pcsim_version", "git_commit", "command", "command_line", "scene_file", "resolved_scene",
        "ranks", "date", "host"]
missing = [k for k in keys if k not in energy]
differ = [k for k in keys if k in energy and str(energy[k]) != str(results[k])]
if missing or differ:
    sys.exit(f"FAIL: energy.h5 provenance: missing {missing}, differs from results.h5 {differ}")
PY
echo "ok: $checked XDMF files open in ParaView's XDMF3 reader and render coloured; energy.h5 has the provenance"
