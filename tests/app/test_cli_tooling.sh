#!/bin/bash
# The command line around the scenes: --version, per-command --help, --set (taken out
# before PETSc sees the arguments, recorded in the provenance), -help listing pcsim's
# own options, and pcsim sweep's checks (no range, mpirun, a list of values, started by
# mpirun on one rank: the cases must not inherit the launcher's environment).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }
static=$PCSIM_SOURCE_DIR/runs/en50318-static.yaml
short=$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml

# --version: the version of CMake's project() and a commit.
version=$(sed -n 's/^project(pcsim VERSION \([0-9.]*\).*/\1/p' "$PCSIM_SOURCE_DIR/CMakeLists.txt")
"$PCSIM_BIN" --version | grep -qE "^pcsim $version \(git [0-9a-f]{7,}(-dirty)?|unknown\)$" ||
  fail "--version: $("$PCSIM_BIN" --version)"

# Per-command --help: the scene sections and the page that documents them.
declare -A sections=([static]="catenary base" [modes]="catenary modes"
  [run]="catenary pantographs simulation effects contact analysis output"
  [pantograph]="pantograph equilibrium study speed_kmh" [sweep]="FROM:TO:STEP -j --ranks")
for command in "${!sections[@]}"; do
  text=$("$PCSIM_BIN" "$command" --help) || fail "$command --help exits non-zero"
  grep -q "docs/scene-format.md" <<< "$text" || fail "$command --help does not name docs/scene-format.md"
  for s in ${sections[$command]}; do
    grep -qe "$s" <<< "$text" || fail "$command --help lacks '$s'"
  done
done

# --set reaches the scene, not PETSc (-options_left reports no unused option).
"$PCSIM_BIN" static "$static" -o st --set catenary.form_finding=false \
  --set=catenary.design.spans.count=4 -options_left > st.log 2>&1 || { cat st.log; fail "static --set"; }
grep -q "There are no unused options" st.log || { cat st.log; fail "--set was seen by PETSc"; }
"$PCSIM_PYTHON" - <<'PY' || fail "static --set results"
import json, h5py
s = json.load(open("st/summary.json"))
assert s["form_finding"] is False, s["form_finding"]
assert len(s["segment_tensions_N"]) > 0
p = s["provenance"]
assert p["overrides"] == ["catenary.form_finding=false", "catenary.design.spans.count=4"], p["overrides"]
assert "form_finding: false" in p["resolved_scene"] and "form_finding: true" in p["scene_text"]
with h5py.File("st/static.h5") as f:
    assert f.attrs["git_commit"] == p["git_commit"] and f.attrs["command"] == "static"
    assert f["/droppers/force"].attrs["unit"] == "N"
    assert len(f["/droppers/x"]) == 4 * 9  # 4 spans of 9 droppers
PY

# A bad --set: one line naming the override, exit 2, no folder.
set +e
"$PCSIM_BIN" static "$static" -o bad --set catenary.form_finding=maybe > bad.log 2>&1
status=$?
set -e
[ $status -eq 2 ] && [ "$(grep -c . bad.log)" -eq 1 ] && [ ! -e bad ] &&
  grep -q "^pcsim: error: command line --set catenary.form_finding=maybe: key 'catenary.form_finding'" bad.log ||
  { cat bad.log; fail "bad --set: exit $status"; }

# -help lists pcsim's own options.
"$PCSIM_BIN" modes "$static" -o m -help --set modes.count=2 > help.log 2>&1 || { tail help.log; fail "-help"; }
for option in -pcsim_debug_fail_rank -eps_nev -modes_fmax; do
  grep -qe "$option" help.log || fail "-help does not list $option"
done

# pcsim sweep: needs a range (sweeps under mpirun: tests/studies/test_sweep_mpi.sh).
set +e
"$PCSIM_BIN" sweep "$short" -o sw0 > sw0.log 2>&1
s0=$?
"$PCSIM_BIN" sweep "$short" -o sw2 --set simulation.speed_kmh=250:900:50 > sw2.log 2>&1
s2=$?
set -e
[ $s0 -eq 2 ] && grep -q "a sweep needs a range" sw0.log || { cat sw0.log; fail "sweep without range"; }
[ $s2 -eq 2 ] && [ ! -e sw2 ] && grep -q "(case 05_speed_kmh-450): key 'simulation.speed_kmh'" sw2.log ||
  { cat sw2.log; fail "sweep beyond the wave speed is not refused before running"; }
"$PCSIM_SOURCE_DIR/scripts/mpirun.sh" -n 1 "$PCSIM_BIN" sweep "$short" -o sw3 --no-report \
  --set simulation.dt=0.001,0.002 --set pantographs[0].static_force=110 -ts_max_steps 3 \
  > sw3.log 2>&1 || { cat sw3.log sw3/cases/*.log 2> /dev/null; fail "sweep under mpirun -n 1"; }
"$PCSIM_PYTHON" - <<'PY' || fail "sweep of a list"
import json
s = json.load(open("sw3/summary.json"))
assert s["swept"] == {"simulation.dt": ["0.001", "0.002"]}, s["swept"]
assert [c["status"] for c in s["cases"]] == [0, 0], s["cases"]
for c, dt in zip(s["cases"], ("0.001", "0.002")):
    case = json.load(open("sw3/cases/%s/summary.json" % c["name"]))
    assert case["steps"] == 3 and case["provenance"]["ranks"] == 1
    assert case["provenance"]["overrides"] == ["pantographs[0].static_force=110", "simulation.dt=" + dt]
    assert "-ts_max_steps 3" in case["provenance"]["petsc_options"]
PY
echo "ok"
