#!/bin/bash
# Results a user can reproduce and trust (README "Results"):
#  1. summary.json records every input file (content and SHA-256), the
#     toolchain and the machine; `pcsim run --rerun DIR` runs the record again
#     and reproduces every figure bit for bit (one rank);
#  2. a rerun refuses (exit 2, naming the file) when an input file changed;
#  3. a result is replaced only by one of the same inputs, or with
#     --overwrite; files a user added to a result are never deleted;
#  4. command-line slips are input errors (exit 2) that leave nothing behind:
#     an unknown -- option (a typo of --set), a second scene, an option
#     without its value, no command at all;
#  5. the speed warning reaches stderr from `pcsim check` as from `pcsim run`.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
mkdir inputs
data=$PCSIM_SOURCE_DIR/tests/contact/data
cp "$data/three-span.yaml" inputs/
cp "$PCSIM_SOURCE_DIR/meshes/pantographs/en50318_two_mass.yaml" inputs/
sed -e 's#\.\./\.\./\.\./meshes/pantographs/##' "$data/three-span-lumped.yaml" > inputs/scene.yaml

expect_input_error() {  # expect_input_error TEXT COMMAND...: exit 2 and TEXT on stderr
  local text=$1; shift
  set +e; "$@" > out.log 2> err.log; local code=$?; set -e
  [ $code -eq 2 ] || { echo "expected exit 2, got $code: $*"; cat out.log err.log; exit 1; }
  grep -qF -- "$text" err.log || { echo "expected '$text' in: $(cat err.log)"; exit 1; }
}

# 1. The record and the rerun.
"$PCSIM_BIN" run inputs/scene.yaml -o first --no-report --set simulation.speed_kmh=180 \
  -ts_dt 0.002 > first.log
"$PCSIM_BIN" run --rerun first --no-report > rerun.log
"$PCSIM_PYTHON" - <<'PY'
import hashlib, json
a = json.load(open("first/summary.json"))
b = json.load(open("first-rerun/summary.json"))
p = a["provenance"]
roles = [f["role"] for f in p["inputs"]]
assert roles == ["scene", "catenary.design", "pantographs[0].model"], roles
for f in p["inputs"]:
    assert hashlib.sha256(f["content"].encode()).hexdigest() == f["sha256"], f["role"]
design = p["inputs"][1]["content"]
assert "three-span-test" in design and "spans" in design, design[:200]
for key in ("compiler", "petsc_version", "slepc_version", "hdf5_version", "mpi_version",
            "cpu_model", "blas", "results_schema", "git_commit", "working_directory"):
    assert p.get(key) not in (None, ""), key
assert p["overrides"] == ["simulation.speed_kmh=180"] and "-ts_dt 0.002" in p["petsc_options"]
assert a["en50318"] == b["en50318"] and a["steps"] == b["steps"] == 669, (a["steps"], b["steps"])
assert b["provenance"]["inputs_fingerprint"] == p["inputs_fingerprint"]
print("rerun: figures equal bit for bit,", a["steps"], "steps")
PY

# 2. A changed input file: the rerun refuses and names it.
sed -i 's/tension: 20000.0/tension: 21000.0/' inputs/three-span.yaml
expect_input_error "catenary.design file" "$PCSIM_BIN" run --rerun first -o second --no-report
[ ! -e second ] && [ ! -e second.partial ]

# 3. Overwrite protection (the design is changed now: other inputs).
expect_input_error "give --overwrite" "$PCSIM_BIN" run inputs/scene.yaml -o first --no-report
"$PCSIM_BIN" run inputs/scene.yaml -o first --no-report --overwrite > /dev/null
"$PCSIM_BIN" run inputs/scene.yaml -o first --no-report > /dev/null  # the same inputs again
echo "my notes" > first/notes.txt
expect_input_error "notes.txt" "$PCSIM_BIN" run inputs/scene.yaml -o first --no-report --overwrite
[ "$(cat first/notes.txt)" = "my notes" ]

# 4. Command-line slips: exit 2, nothing written.
expect_input_error "unknown option --sett" \
  "$PCSIM_BIN" run inputs/scene.yaml -o slip --sett simulation.speed_kmh=200
expect_input_error "one scene only" "$PCSIM_BIN" run inputs/scene.yaml other.yaml -o slip
expect_input_error "needs a folder" "$PCSIM_BIN" run inputs/scene.yaml -o --no-report
expect_input_error "no command" "$PCSIM_BIN"
[ ! -e slip ] && [ ! -e slip.partial ] && [ ! -e ./--no-report ] && [ ! -e out ]

# 5. The speed warning from check, on stderr.
"$PCSIM_BIN" check inputs/scene.yaml --set simulation.speed_kmh=390 > out.log 2> err.log
grep -q "pcsim: warning: .*simulation.speed_kmh.*70% of the contact wire's wave speed" err.log ||
  { cat out.log err.log; exit 1; }
echo "records, rerun, overwrite and command-line checks: all as expected"
