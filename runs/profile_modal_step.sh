#!/usr/bin/env bash
# Where a modal step's time goes (docs/benchmarks.md, "Where a modal step's
# time goes"): runs each scene once with -log_view and prints, per time step,
# the microseconds of the time loop and of pcsim's events in it (residuals,
# state loads with the dropper check, contacts, the Woodbury solve, the
# low-rank changes, records), the time outside TSStep, and the dropper rows'
# products per step with the megabytes they read. Bases come from the cache
# (a first run computes them); the accuracy pilot is off.
#   runs/profile_modal_step.sh [BIN]
# Environment: SCENES="en300 win109 dsa136" (the names of
# runs/bench_modal_step.sh). Run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${1:-build/pcsim}
SCENES=${SCENES:-en300 win109 dsa136}
# shellcheck source=runs/bench/modal_scenes.sh
source runs/bench/modal_scenes.sh
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for s in $SCENES; do
  # shellcheck disable=SC2086
  "$BIN" run ${MODAL_SCENES[$s]} -pcsim_accuracy_pilot false --no-report -o "$OUT/$s" --overwrite \
    -log_view ":$OUT/$s.log" >/dev/null 2>&1 || { echo "run failed: $s"; exit 1; }
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
# shellcheck disable=SC2086
/usr/bin/python3 - "$OUT" $SCENES <<'PY'
import json, re, sys
out, scenes = sys.argv[1], sys.argv[2:]
EVENTS = ["TSStep", "pcsimResidual", "pcsimStateLoad", "pcsimContact", "pcsimWoodbury",
          "pcsimLowRankChg", "pcsimRecord"]
print("| scene | vectors | time loop µs/step | TSStep | residuals (per step) | state loads "
      "(per step) | contacts | Woodbury | low-rank changes | records | outside TSStep, "
      "records apart | window shifts | dropper products per step: half, single, exact | MB read "
      "per step |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for s in scenes:
    text = open(f"{out}/{s}.log").read()
    stage = text[text.index("--- Event Stage 4: Time loop"):]
    stage = stage[:stage.index("--- Event Stage", 10)] if "--- Event Stage" in stage[10:] else stage
    loop = float(re.search(r"4:\s+Time loop:\s+(\S+)", text).group(1))
    ev = {}
    for line in stage.splitlines():
        f = line.split()
        if f and f[0] in EVENTS:
            ev[f[0]] = (int(f[1]), float(f[3]))  # count, max time [s]
    j = json.load(open(f"{out}/{s}/summary.json"))
    n, m = j["steps"], j["modal"]
    us = lambda e: 1e6 * ev[e][1] / n
    per = lambda e: ev[e][0] / n
    outside = 1e6 * loop / n - us("TSStep") - us("pcsimRecord")
    rows, vectors = m["tracked_bars"], m["basis_size"]
    single, exact = m["single_precision_updates_per_step"], m["exact_updates_per_step"]
    half = m.get("half_precision_updates_per_step", 0.0)
    mb = rows * vectors * (2 * half + 4 * single + 8 * exact) / 1e6
    # A basis in column blocks (a line's tension sections) reads each block's
    # rows over its columns, one block at a time: not known from the summary.
    mb_text = f"{mb:.2f}" if m.get("column_blocks", 1) == 1 else "—"
    print(f"| {s} | {vectors} | {1e6 * loop / n:.0f} | {us('TSStep'):.0f} "
          f"| {us('pcsimResidual'):.0f} ({per('pcsimResidual'):.2f}) "
          f"| {us('pcsimStateLoad'):.0f} ({per('pcsimStateLoad'):.2f}) "
          f"| {us('pcsimContact'):.0f} | {us('pcsimWoodbury'):.0f} | {us('pcsimLowRankChg'):.0f} "
          f"| {us('pcsimRecord'):.0f} | {outside:.0f} | {j.get('window_shifts', 0)} "
          f"| {half:.3f}, {single:.3f}, {exact:.3f} | {mb_text} |")
PY
