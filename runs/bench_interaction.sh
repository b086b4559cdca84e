#!/usr/bin/env bash
# Benchmark of the dynamic interaction: the EN 50318 case at 300 km/h on 1
# and 2 ranks, cheap path (J0 factored once, contact by Woodbury) and full
# Newton path. Prints steps, Newton iterations per step, time per step,
# real-time factor (simulated s per wall s), peak memory per rank, and the
# statistics of both paths (they must agree within 0.5 %).
#   runs/bench_interaction.sh [SCENE.yaml] [extra pcsim options]
# Run it on an otherwise idle machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
SCENE=${1:-runs/en50318-300.yaml}
shift || true
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
for ranks in 1 2; do
  for path in cheap full; do
    scripts/mpirun.sh -n "$ranks" build/pcsim run "$SCENE" -o "$OUT/np${ranks}_$path" --overwrite \
      -pcsim_path "$path" "$@" >"$OUT/np${ranks}_$path.log" 2>&1 ||
      { echo "run failed: $ranks ranks, $path path"; cat "$OUT/np${ranks}_$path.log"; exit 1; }
  done
done
/usr/bin/python3 - "$OUT" "$SCENE" <<'PY'
import json, sys, os
out, scene = sys.argv[1], sys.argv[2]
rows = []
for ranks in (1, 2):
    for path in ("cheap", "full"):
        with open(os.path.join(out, f"np{ranks}_{path}", "summary.json")) as f:
            rows.append((ranks, path, json.load(f)))
print(f"scene: {scene}, {rows[0][2]['dofs']} DOFs, {rows[0][2]['simulated_time_s']:.3f} s simulated")
print(f"{'ranks':>5} {'path':>6} {'steps':>6} {'Newton/step':>11} {'ms/step':>8} {'RTF':>6} "
      f"{'mem MB/rank':>11} {'mean N':>8} {'std N':>7}")
for ranks, path, s in rows:
    p = s["pantographs"][0]
    print(f"{ranks:>5} {path:>6} {s['steps']:>6} {s['newton_iterations_per_step']:>11.2f} "
          f"{s['time_per_step_ms']:>8.2f} {s['real_time_factor']:>6.2f} {s['peak_memory_mb']:>11.0f} "
          f"{p['mean_N']:>8.2f} {p['std_N']:>7.2f}")
ref = rows[1][2]["pantographs"][0]
worst = 0.0
for _, _, s in rows:
    p = s["pantographs"][0]
    for k in ("mean_N", "std_N", "stat_max_N", "stat_min_N", "max_N", "min_N"):
        worst = max(worst, abs(p[k] - ref[k]) / max(abs(ref[k]), 1.0))
print(f"largest relative difference of any statistic from the 1-rank full path: {worst:.2e}")
PY
