#!/usr/bin/env bash
# The step-time tail with and without a real-time policy for the stepping
# thread (docs/benchmarks.md, "Real-time scheduling for the step"): REPS
# pairs of runs of one scene, one plain and one under `chrt -f PRIORITY`
# (SCHED_FIFO), in turn, the order alternating; prints each run's
# step_time of summary.json: the 99.99th percentile, the max, the max over
# the steps without a context switch, the steps with one, the median, and
# the kernel's real-time runtime. Needs the privilege to set SCHED_FIFO
# (root, or CAP_SYS_NICE). The modal basis comes from the cache folder
# (a first run computes it); the accuracy pilot is off.
#   runs/bench_step_scheduling.sh [SCENE [pcsim options...]]
# Environment: BIN=build/pcsim, REPS=6, PRIORITY=10,
# CACHE=out/.pcsim-cache; SCENE defaults to runs/en50318-300-modal.yaml.
# Run it on an otherwise idle machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/pcsim}
REPS=${REPS:-6}
PRIORITY=${PRIORITY:-10}
CACHE=${CACHE:-out/.pcsim-cache}
SCENE=${1:-runs/en50318-300-modal.yaml}
[ $# -gt 0 ] && shift
chrt -f "$PRIORITY" true 2> /dev/null ||
  { echo "$0: cannot set SCHED_FIFO here (chrt -f $PRIORITY: not permitted)" >&2; exit 2; }
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-6s %-5s %10s %9s %13s %14s %10s %12s\n' rep mode "p99.99 ms" "max ms" \
  "max quiet ms" "switched steps" "median ms" "rt runtime"
for rep in $(seq "$REPS"); do
  modes="plain fifo"
  [ $((rep % 2)) -eq 0 ] && modes="fifo plain"
  for mode in $modes; do
    prefix=()
    [ "$mode" = fifo ] && prefix=(chrt -f "$PRIORITY")
    rm -rf "$OUT/run"
    "${prefix[@]}" "$BIN" run "$SCENE" -pcsim_accuracy_pilot false --cache "$CACHE" \
      -o "$OUT/run" --no-report "$@" > "$OUT/log" 2>&1 || { cat "$OUT/log"; exit 1; }
    /usr/bin/python3 - "$OUT/run/summary.json" "$rep" "$mode" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))["step_time"]
s = t["scheduling"]
print("%-6s %-5s %10.3f %9.3f %13.3f %14d %10.4f %12s" % (
    sys.argv[2], sys.argv[3], t["p99_99_ms"], t["max_ms"],
    t["max_without_context_switch_ms"], t["steps_with_context_switch"], t["median_ms"],
    s["rt_runtime_us"]))
PY
  done
done
