#!/bin/bash
# The three-section line (docs/lines.md, "Three-section line"): 3 x 20 spans of
# 60 m joined by two two-span overlaps (meshes/lines/three-sections.yaml),
# the EN 50318 two-mass pantograph at 300 km/h, on 2 ranks; prints the
# EN 50318 figures over each section and each overlap (summary.json
# "line_zones": 20 Hz low-pass contact force) and the whole-line figures.
#
#   runs/lines/three-sections.sh [extra pcsim options]
#
# Environment: PCSIM (default build/pcsim), OUT (default out/lines), RANKS
# (default 2). Results: $OUT/three-sections-300/. About 13 minutes on 2 idle
# cores (43 s simulated, 97 667 DOFs).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PCSIM=${PCSIM:-$ROOT/build/pcsim}
OUT=${OUT:-$ROOT/out/lines}
RANKS=${RANKS:-2}
mkdir -p "$OUT"
echo "pcsim run runs/lines/three-sections-300.yaml on $RANKS ranks -o $OUT/three-sections-300"
"$ROOT/scripts/mpirun.sh" -n "$RANKS" "$PCSIM" run "$ROOT/runs/lines/three-sections-300.yaml" \
  -o "$OUT/three-sections-300" --overwrite --no-report "$@" > "$OUT/three-sections-300.log" 2>&1 ||
  { tail -n 20 "$OUT/three-sections-300.log"; exit 1; }
/usr/bin/python3 - "$OUT/three-sections-300/summary.json" <<'PY'
import json, sys

s = json.load(open(sys.argv[1]))
print(f"{s['dofs']} DOFs, {s['steps']} steps, {s['time_per_step_ms']:.2f} ms/step on "
      f"{s.get('ranks', '?')} ranks")
print("| zone | x [m] | mean [N] | σ [N] | Fm+3σ [N] | max [N] | min [N] | loss of contact [%] |")
print("|---|---|---|---|---|---|---|---|")
for p in s["line_zones"]:
    for z in p["zones"]:
        if not z["complete"]:
            print(f"| {z['name']} | {z['from_x']:.0f}–{z['to_x']:.0f} | (not fully run) |||||")
            continue
        print(f"| {z['name']}{' (overlap)' if z['overlap'] else ''} | "
              f"{z['from_x']:.0f}–{z['to_x']:.0f} | {z['mean_N']:.1f} | {z['std_N']:.1f} | "
              f"{z['stat_max_N']:.1f} | {z['max_N']:.1f} | {z['min_N']:.1f} | "
              f"{z['loss_of_contact_percent']:.2f} |")
w = s["pantographs"][0]
print(f"| whole analysis window | | {w['mean_N']:.1f} | {w['std_N']:.1f} | {w['stat_max_N']:.1f} | "
      f"{w['max_N']:.1f} | {w['min_N']:.1f} | {w['loss_of_contact_percent']:.2f} |")
print(f"maximum uplift at a support: {1000 * s['max_uplift_at_support_m']:.1f} mm")
PY
