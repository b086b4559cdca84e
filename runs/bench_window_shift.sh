#!/usr/bin/env bash
# A/B benchmark of a modal window's shift between two pcsim binaries (e.g. a
# build of the previous commit and one of this): two-pantographs-300-window
# at the modal level and a pinned cut-off (5 shifts), each binary REPEAT
# times, interleaved, each with a cache folder of its own (filled by a first
# run that is not counted). Prints per run the shift steps' mean
# (step_time.by_cause.window_shift of summary.json), the largest step with
# and without an involuntary context switch, the median step and the peak
# memory; then the largest difference of each pantograph's contact force
# between the two binaries' first counted runs.
#   runs/bench_window_shift.sh BEFORE_BIN AFTER_BIN [extra pcsim options]
# Environment: CUTOFF=136.1 (Hz) REPEAT=3. Run it on an otherwise idle
# machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { echo "usage: $0 BEFORE_BIN AFTER_BIN [pcsim options]" >&2; exit 2; }
bins=("$1" "$2")
shift 2
extra=("$@")
CUTOFF=${CUTOFF:-136.1}
REPEAT=${REPEAT:-3}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
run() {  # run BINARY_INDEX NAME (the extra options after the scene's)
  "${bins[$1]}" run runs/interaction/two-pantographs-300-window.yaml --set catenary.model=modal \
    --set catenary.max_frequency_hz="$CUTOFF" -pcsim_accuracy_pilot false --no-report \
    --cache "$OUT/cache$1" -o "$OUT/$2" "${extra[@]}" >"$OUT/$2.log" 2>&1 ||
    { echo "run failed: ${bins[$1]} ($2)"; tail -20 "$OUT/$2.log"; exit 1; }
}
for b in 0 1; do run "$b" "fill$b"; done
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
for r in $(seq "$REPEAT"); do
  for b in 0 1; do run "$b" "run$b-$r"; done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$OUT" "$REPEAT" "${bins[@]}" <<'PY'
import json, sys
import h5py
import numpy as np
out, repeat, bins = sys.argv[1], int(sys.argv[2]), sys.argv[3:5]
print("| binary | run | shifts | shift step mean ms | max ms | max without a context switch ms "
      "| median ms | peak memory MB |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for r in range(1, repeat + 1):
    for b in (0, 1):
        j = json.load(open(f"{out}/run{b}-{r}/summary.json"))
        st = j["step_time"]
        w = st["by_cause"]["window_shift"]
        print(f"| {bins[b]} | {r} | {w['steps']} | {w['mean_ms']:.2f} | {st['max_ms']:.2f} | "
              f"{st['max_without_context_switch_ms']:.2f} | {st['median_ms']:.3f} | "
              f"{j['peak_memory_mb']:.0f} |")
a, b = (h5py.File(f"{out}/run{k}-1/results.h5", "r") for k in (0, 1))
for p in a["pantographs"]:
    x = a[f"pantographs/{p}/contact_force"][:]
    y = b[f"pantographs/{p}/contact_force"][:]
    d = np.max(np.abs(x - y))
    print(f"{p}: contact force differs by up to {d:.3e} N ({d / np.max(np.abs(x)):.2e} of its largest)")
PY
