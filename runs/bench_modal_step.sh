#!/usr/bin/env bash
# The modal level's step on several scenes, two pcsim binaries run in turn
# (interleaved, REPS times each, the order alternating; docs/benchmarks.md,
# "A modal step on several pantographs"): prints per scene and binary the median over the
# repetitions of the real-time factor and of the step-time median and 99.99th
# percentile. Modes and bases come from the cache (a first run computes
# them); the accuracy pilot is off (its runs are not the step's cost).
#   runs/bench_modal_step.sh BEFORE_BIN AFTER_BIN
# Environment: REPS=3, SCENES="en300 win70 win109 two20 three" (also two109:
# two20 at 108.8 Hz, the cut-off its pilot chooses; three109: three-pantographs-300
# at 108.8 Hz, its pilot's since 2026-12-04; dsa136: dsa380-300-base
# at 136.1 Hz, its pilot's; flex136: dsa380-300-flexible at 136.1 Hz; win136:
# the 1000-span window at 136.1 Hz, its pilot's since 2026-12-04; ts300:
# three-sections-300 at its default 69.7 Hz, whose first run computes 18000
# modes: 615 s with its run, peak 9887 MB (2026-12-04); ts1: one of its
# sections alone, runs/bench/one-section-300.yaml; the names:
# runs/bench/modal_scenes.sh). Run it on an otherwise idle machine: it
# measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 2 ] || { echo "usage: $0 BEFORE_BIN AFTER_BIN" >&2; exit 2; }
BINS=("$1" "$2")
REPS=${REPS:-3}
SCENES=${SCENES:-en300 win70 win109 two20 three}
# shellcheck source=runs/bench/modal_scenes.sh
source runs/bench/modal_scenes.sh
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
# The hour's stalls of the machine itself: a step's time includes any that
# falls in it (docs/benchmarks.md, "What a modal run's slow steps are").
echo "the machine's stalls before the runs (runs/bench/stall_probe.py 10):"
/usr/bin/python3 runs/bench/stall_probe.py 10
for rep in $(seq "$REPS"); do
  for s in $SCENES; do
    # The order alternates from one repetition to the next: the second run of
    # a pair can run faster (docs/benchmarks.md, "No line of bounds for
    # batched records").
    order="0 1"
    [ $((rep % 2)) -eq 0 ] && order="1 0"
    for b in $order; do
      # shellcheck disable=SC2086
      "${BINS[$b]}" run ${MODAL_SCENES[$s]} -pcsim_accuracy_pilot false --no-report -o "$OUT/run" \
        --overwrite >/dev/null 2>&1 || { echo "run failed: $s with ${BINS[$b]}"; exit 1; }
      /usr/bin/python3 -c "
import json, sys
s = json.load(open(sys.argv[1]))
t = s['step_time']
print(sys.argv[2], sys.argv[3], s['real_time_factor'], t['median_ms'], t['p99_99_ms'])
" "$OUT/run/summary.json" "$s" "$b" >>"$OUT/rows"
    done
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$OUT/rows" "$1" "$2" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
print(f"before: {sys.argv[2]}\nafter:  {sys.argv[3]}")
print("| scene | RTF before | RTF after | step median ms before | after | p99.99 ms before | after |")
print("|---|---:|---:|---:|---:|---:|---:|")
for scene in dict.fromkeys(r[0] for r in rows):
    med = lambda b, k: statistics.median(float(r[k]) for r in rows if r[0] == scene and r[1] == b)
    print(f"| {scene} | {med('0', 2):.2f} | {med('1', 2):.2f} | {med('0', 3):.3f} | {med('1', 3):.3f} "
          f"| {med('0', 4):.2f} | {med('1', 4):.2f} |")
PY
