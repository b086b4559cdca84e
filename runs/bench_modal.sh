#!/usr/bin/env bash
# What a time step costs at each fidelity level (docs/fidelity.md) and how it
# grows with the catenary: nonlinear FE (full path), linearised FE (cheap
# path) and the modal catenary, on the EN 50318 case at 300 km/h
# (runs/en50318-300.yaml) with 10 and 40 spans (catenary.design.spans.count),
# one rank, the first STEPS steps (default 1000; ms/step and the real-time
# factor of the time loop, as summary.json reports them). The modal runs take
# their modes from the cache (out/.pcsim-cache), computed on first use (the 40
# spans: tens of minutes). Prints a Markdown table and the load average
# before and after: run it on an otherwise idle machine (it measures wall time).
#   runs/bench_modal.sh [extra pcsim options]      STEPS=500 runs/bench_modal.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
STEPS=${STEPS:-1000}
OUT=${OUT:-out/bench-modal}
mkdir -p "$OUT"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| fidelity | spans | unknowns | ms/step | real-time factor | peak memory [MB] |"
echo "|---|---|---|---|---|---|"
for spans in 10 40; do
  for model in nonlinear linear modal; do
    dir=$OUT/$model-$spans
    build/pcsim run runs/en50318-300.yaml -o "$dir" --overwrite --no-report -ts_max_steps "$STEPS" \
      --set catenary.design.spans.count="$spans" --set catenary.model="$model" "$@" > "$dir.log" 2>&1 ||
      { cat "$dir.log"; exit 1; }
    python3 - "$dir/summary.json" "$model" "$spans" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {sys.argv[3]} | {s['dofs']} | {s['time_per_step_ms']:.3f} | "
      f"{s['real_time_factor']:.2f} | {s['peak_memory_mb']:.0f} |")
PY
  done
done
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
