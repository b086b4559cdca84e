#!/usr/bin/env bash
# What a first modal run costs before it steps, two pcsim binaries in turn
# (docs/benchmarks.md, "The first run's set-up"): the two-pantograph train
# on the 1000-span line in its moving window
# (runs/interaction/two-pantographs-300-window.yaml, modal level, one rank),
# each run in an empty cache folder, (1) at the defaults, so its accuracy
# pilot runs and chooses the cut-off, and (2) with the pilot off at the
# cut-off the pilot chooses (108.8 Hz), 100 steps. Prints each run's pilot
# runs (seconds: its FE runs, then its modal runs), the set-up of its basis,
# its peak memory (summary.json: the largest resident set of any rank, the
# pilot included) and that of the pilot's second process (-pcsim_pilot_process).
#   runs/bench_first_run.sh BEFORE_BIN AFTER_BIN
# Environment: REPS=1; BEFORE_OPTIONS, AFTER_OPTIONS: options added to each
# binary's runs (one build two ways: BEFORE_OPTIONS="-pcsim_pilot_process
# false" with the same binary twice). Takes ~6 min per repetition and
# binary. Run it on an otherwise idle machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 2 ] || { echo "usage: $0 BEFORE_BIN AFTER_BIN" >&2; exit 2; }
BINS=("$1" "$2")
read -r -a EXTRA0 <<< "${BEFORE_OPTIONS:-}"
read -r -a EXTRA1 <<< "${AFTER_OPTIONS:-}"
REPS=${REPS:-1}
SCENE=runs/interaction/two-pantographs-300-window.yaml
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-6s %-9s %-34s %10s %10s %8s %12s\n' binary run "pilot runs [s]" "pilot [s]" "basis [s]" "peak MB" \
  "2nd proc. MB"
for _ in $(seq "$REPS"); do
  for b in 0 1; do
    for kind in pilot no-pilot; do
      rm -rf "$OUT/cache" "$OUT/run"
      options=(-pcsim_accuracy_pilot true)
      [ "$kind" = no-pilot ] &&
        options=(-pcsim_accuracy_pilot false --set catenary.max_frequency_hz=108.8 -ts_max_steps 100)
      if [ "$b" = 0 ]; then options+=("${EXTRA0[@]}"); else options+=("${EXTRA1[@]}"); fi
      "${BINS[$b]}" run "$SCENE" --set catenary.model=modal "${options[@]}" --cache "$OUT/cache" \
        --no-report -o "$OUT/run" >"$OUT/log" 2>&1 || { echo "run failed: ${BINS[$b]} $kind"; exit 1; }
      # The FE runs first, the modal ones after: a second process runs the FE
      # ones beside the modal ones, and the console gives them as they end.
      pilot=$({ grep -E "^    linear FE at .* s$" "$OUT/log" || true; grep -E "^    modal at .* s$" "$OUT/log" || true; } |
        sed -E 's/.* ([0-9.]+) s$/\1/' | tr '\n' ' ')
      /usr/bin/python3 - "$OUT/run/summary.json" "$b" "$kind" "$pilot" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
pilot = s["accuracy_estimate"].get("pilot", {})
second = pilot.get("second_process_peak_memory_mb", 0)
print("%-6s %-9s %-34s %10s %10.1f %8.0f %12s" % (
    ("before", "after")[int(sys.argv[2])], sys.argv[3], sys.argv[4] or "-",
    "%.1f" % pilot["seconds"] if pilot.get("runs") else "-", s["modal"]["basis_setup_s"],
    s["peak_memory_mb"], "%.0f" % second if second else "-"))
PY
    done
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
