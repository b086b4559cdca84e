#!/bin/bash
# The accuracy pilot's linear FE runs in a second process
# (src/simulation/pilot_process.hpp, -pcsim_pilot_process; docs/fidelity.md,
# "The pilot's second process"), on a 4-span EN 50318 line:
#  - its estimate equals the in-process pilot's bit for bit, the modal
#    level's (cut-off raised the same) and linear FE's (the run at dt/2 and
#    h/2 in the second process, the run at dt and h here); summary.json says
#    which ran where, and the second process's peak memory;
#  - a second process that dies (-pcsim_debug_pilot_process_dies: a crash,
#    the out-of-memory killer) is said in one warning, and the run goes on
#    without the estimate (exit 0);
#  - the folders of a pilot killed while its runs wrote are replaced by the
#    scene's next pilot;
#  - killed with its parent: no pcsim process is left;
#  - another value than auto, true or false is an input error (exit 2,
#    nothing made).
# pcsim-test-processors: 2
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
parent=
trap '[ -z "$parent" ] || kill -9 "$parent" 2> /dev/null || true; rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }
pcsim_run=("$PCSIM_BIN" run "$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml"
  --set catenary.design.spans.count=4 --no-report -pcsim_accuracy_pilot true)
run() { "${pcsim_run[@]}" "$@"; }

for model in modal linear; do
  for where in true false; do
    run --set catenary.model=$model --cache "cache-$where" -o "$model-$where" \
      -pcsim_pilot_process $where > "$model-$where.log" 2>&1 || { cat "$model-$where.log"; fail "$model $where"; }
  done
  grep -q "^    linear FE .* in a second process, beside the" "$model-true.log" ||
    { cat "$model-true.log"; fail "$model: no second process"; }
  if grep -q "second process" "$model-false.log"; then cat "$model-false.log"; fail "$model: one"; fi
  "$PCSIM_PYTHON" - "$model" <<'PY'
import json, sys
model = sys.argv[1]
there, here = (json.load(open(f"{model}-{w}/summary.json"))["accuracy_estimate"]["pilot"]
               for w in ("true", "false"))
assert there["second_process"] is True and here["second_process"] is False, model
# The second process's resident set: PETSc, the scene and one FE run of a
# 4-span line (61 MB measured); 0 where there was none.
assert 20 < there["second_process_peak_memory_mb"] < 1000, there
assert here["second_process_peak_memory_mb"] == 0, here
timing = {"seconds", "second_process", "second_process_peak_memory_mb"}
differ = [k for k in set(there) | set(here) if k not in timing and there.get(k) != here.get(k)]
assert not differ, (model, differ, [(there.get(k), here.get(k)) for k in differ])
assert there["runs"] == (4 if model == "modal" else 2), there["runs"]
print(model, "pilot: equal bit for bit with and without the second process,",
      "its peak %.0f MB" % there["second_process_peak_memory_mb"])
PY
done

# A second process that dies: one warning, the run goes on.
run --set catenary.model=modal --cache cache-dies -o dies -pcsim_pilot_process true \
  -pcsim_debug_pilot_process_dies > dies.log 2>&1 || { cat dies.log; fail "the run with a dying second process"; }
grep -q "^pcsim: warning: no accuracy pilot: the accuracy pilot's second process ended without its result (killed by signal 9 (Killed)); the run goes on without its estimate$" dies.log ||
  { cat dies.log; fail "no warning"; }
"$PCSIM_PYTHON" -c "
import json
s = json.load(open('dies/summary.json'))
assert s['accuracy_estimate'].get('pilot') is None, s['accuracy_estimate']"

# A pilot killed while its runs wrote (a signal in the set-up, SIGKILL, a
# crash) leaves their folders in the cache: "<cache>/accuracy-pilot-<key>.partial"
# and, from its second process, "...-fe.partial", each with its manifest and
# results. The same scene's next pilot uses the same folders: it replaces
# them, as pcsim's own scratch (until 2026-12-05 every later run of the scene
# stopped: "internal error: ... holds the results of an interrupted pcsim
# run"), and leaves none. The leftovers are made here as a killed pilot left
# them (the manifest a pilot run writes, a results file), under the key of a
# first run of the scene, whose cached estimate is then removed.
run --set catenary.model=modal --cache cache-left -o left-first > left-first.log 2>&1 ||
  { cat left-first.log; fail "the first run of the leftover case"; }
estimate=$(find cache-left -name 'accuracy-pilot-*.json')
key=$(basename "$estimate" .json | sed 's/^accuracy-pilot-//' | cut -c1-12)
rm "$estimate"
for leftover in "cache-left/accuracy-pilot-$key.partial" "cache-left/accuracy-pilot-$key-fe.partial"; do
  mkdir "$leftover"
  printf '{"pcsim_result": 1, "command": "run (accuracy pilot)", "complete": false, "pid": 1}\n' \
    > "$leftover/.pcsim-result"
  printf 'partly written' > "$leftover/results.h5"
done
run --set catenary.model=modal --cache cache-left -o left-again > left-again.log 2>&1 ||
  { cat left-again.log; fail "the run after a killed pilot"; }
grep -q "pilot runs in" left-again.log || { cat left-again.log; fail "no pilot after the killed one"; }
[ -z "$(find cache-left -name '*.partial')" ] || { ls -a cache-left; fail "pilot folders left"; }
echo "a killed pilot's folders: replaced by the scene's next pilot, none left"

# Killed with its parent: the second process ends too (PR_SET_PDEATHSIG).
# (-pcsim_pilot_process true: on a machine of one CPU too.)
"${pcsim_run[@]}" --set catenary.model=modal --set catenary.design.spans.count=10 \
  -pcsim_pilot_process true --cache cache-killed -o killed-run-of-this-test > killed.log 2>&1 &
parent=$!
second_process() { pgrep -f killed-run-of-this-test | grep -vqx "$parent"; }
for _ in $(seq 600); do
  grep -q "in a second process" killed.log && second_process && break
  kill -0 "$parent" 2> /dev/null || { cat killed.log; fail "the run ended early"; }
  sleep 0.1
done
second_process || { cat killed.log; fail "no second process"; }
kill -9 "$parent"
wait "$parent" 2> /dev/null || true
parent=
for _ in $(seq 50); do
  pgrep -f killed-run-of-this-test > /dev/null || break
  sleep 0.1
done
if pgrep -f killed-run-of-this-test; then fail "a pcsim process outlived its parent"; fi

# A value other than auto, true or false.
set +e
run --set catenary.model=modal --cache cache-bad -o bad -pcsim_pilot_process often > bad.log 2>&1
status=$?
set -e
[ "$status" -eq 2 ] || { cat bad.log; fail "exit $status, not 2"; }
grep -q -- "-pcsim_pilot_process" bad.log || { cat bad.log; fail "the option is not named"; }
[ ! -e bad ] && [ ! -e cache-bad ] || fail "a bad option left files"
echo "pilot process: OK"
