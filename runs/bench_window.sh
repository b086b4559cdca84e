#!/usr/bin/env bash
# The moving window against the full line (docs/scaling.md, "Moving window"):
# the EN 50318 case at 300 km/h on a line of SPANS spans (default 40), the
# full line and the window (spans_behind + 2 + spans_ahead spans) with the same
# dt and mesh, on RANKS ranks (default 1). Prints the EN 50318 figures of
# both, the window's error against the full line, ms/step, DOFs and peak
# memory.
#   runs/bench_window.sh [extra pcsim options]
# Environment: SPANS=40 RANKS=1 BEHIND=2 AHEAD=3 END_X=595. It measures wall
# time: run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
SPANS=${SPANS:-40}
RANKS=${RANKS:-1}
BEHIND=${BEHIND:-2}
AHEAD=${AHEAD:-3}
END_X=${END_X:-595}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"

run() {  # run NAME [options]
  local name=$1
  shift
  scripts/mpirun.sh -n "$RANKS" build/pcsim run runs/en50318-300.yaml -o "$OUT/$name" --overwrite --no-report \
    --set catenary.design.spans.count="$SPANS" --set simulation.end_x="$END_X" "$@" \
    >"$OUT/$name.log" 2>&1 || { echo "run failed: $name"; tail -20 "$OUT/$name.log"; exit 1; }
}
run full "$@"
run window --set window.spans_behind="$BEHIND" --set window.spans_ahead="$AHEAD" "$@"

/usr/bin/python3 - "$OUT" "$SPANS" "$BEHIND" "$AHEAD" <<'PY'
import json, os, sys
out, spans, behind, ahead = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
def summary(name):
    with open(os.path.join(out, name, "summary.json")) as f:
        return json.load(f)
full, win = summary("full"), summary("window")
def figures(s):
    return {f["key"]: f for f in s["en50318"]["pantograph"]["figures"]}
ff, fw = figures(full), figures(win)
w = behind + 2 + ahead
print(f"EN 50318, 300 km/h, {spans} spans; window {w} spans ({behind} behind, {ahead} ahead), "
      f"{win.get('window_shifts', 0)} shifts")
print(f"{'figure':<32} {'full line':>10} {'window':>10} {'error':>8}")
for key in ("mean_N", "std_N", "stat_max_N", "stat_min_N", "max_N", "min_N", "uplift_mm"):
    a, b = ff[key]["value"], fw[key]["value"]
    print(f"{ff[key]['label'] + ' [' + ff[key]['unit'] + ']':<32} {a:>10.2f} {b:>10.2f} "
          f"{100 * (b - a) / abs(a):>+7.2f}%")
for label, key, fmt in (("DOFs", "dofs", "{:>10d}"), ("ms/step", "time_per_step_ms", "{:>10.2f}"),
                        ("real-time factor", "real_time_factor", "{:>10.3f}"),
                        ("peak memory [MB/rank]", "peak_memory_mb", "{:>10.0f}")):
    print(f"{label:<32} " + fmt.format(full[key]) + " " + fmt.format(win[key]))
PY
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
