#!/bin/bash
# The stepping thread's scheduling policy in summary.json
# (step_time.scheduling, simulation/step_scheduling.hpp), end to end: a run
# started by `chrt -b 0` (SCHED_BATCH, which needs no privileges) records
# "batch", a plain run "other"; neither is real-time, so neither warns of
# the kernel's real-time throttling (the warning's values:
# tests/simulation/test_step_scheduling.cpp). The kernel's limits are those
# of /proc/sys/kernel (null where it does not have them). Run time: ~1 s.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
run() {  # run NAME [command before pcsim...]
  local name=$1
  shift
  "$@" "$PCSIM_BIN" run "$scene" -o "$tmp/$name" --no-report -ts_max_steps 50 \
    > "$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log"; exit 1; }
  if grep -q "real-time throttling" "$tmp/$name.log"; then
    cat "$tmp/$name.log"
    echo "FAIL: $name warns of real-time throttling"
    exit 1
  fi
}
run plain
run batch chrt -b 0
"$PCSIM_PYTHON" - "$tmp" <<'PY'
import json, sys
tmp = sys.argv[1]
def limit(name):  # None where /proc does not have it (summary.json: null)
    try:
        with open(f"/proc/sys/kernel/sched_rt_{name}_us") as f:
            return int(f.read())
    except OSError:
        return None
runtime, period = limit("runtime"), limit("period")
if runtime is None or period is None:
    runtime = period = None
for name, policy in (("plain", "other"), ("batch", "batch")):
    with open(f"{tmp}/{name}/summary.json") as f:
        s = json.load(f)["step_time"]["scheduling"]
    print(name, s)
    assert s == {"policy": policy, "priority": 0, "rt_runtime_us": runtime,
                 "rt_period_us": period}, (name, s)
PY
echo "PASS"
