#!/usr/bin/env bash
# Benchmark of the dynamic step against the catenary's length (docs/scaling.md):
# the EN 50318 case at 300 km/h with spans.count = 10, 40, 100 (14k, 57k,
# 144k DOFs) on 1 and 2 ranks, and 4 ranks (oversubscribed on a 2-core
# machine: marked "4*"); then 1000 spans (60 km, 1.4M DOFs) with two
# pantographs for 1 s simulated on 1 and 2 ranks. Prints DOFs, ms/step, real-time
# factor, peak memory (largest rank and total), the nonzeros of the step
# factors, the interface (Schur complement) size, and the largest difference
# of the contact force from the 1-rank run (must be round-off, <= 1e-9).
#   runs/bench_scaling.sh [extra pcsim options]
# Environment: SPANS="10 40 100" RANKS="1 2 4" STEPS=600 BIG=1 (BIG=0: no
# 1000-span run) BIG_RANKS="1 2" (the ranks of the 1000-span runs). Run it on an otherwise idle machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
SPANS=${SPANS:-10 40 100}
RANKS=${RANKS:-1 2 4}
STEPS=${STEPS:-600}
BIG=${BIG:-1}
BIG_RANKS=${BIG_RANKS:-1 2}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
CORES=$(nproc)
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg), $CORES cores"

run() {  # run NAME RANKS SCENE [options]
  local name=$1 ranks=$2 scene=$3
  shift 3
  scripts/mpirun.sh -n "$ranks" build/pcsim run "$scene" -o "$OUT/$name" --overwrite --no-report "$@" \
    >"$OUT/$name.log" 2>&1 || { echo "run failed: $name"; tail -20 "$OUT/$name.log"; exit 1; }
}

for spans in $SPANS; do
  for ranks in $RANKS; do
    run "s${spans}_np${ranks}" "$ranks" runs/en50318-300.yaml \
      --set catenary.design.spans.count="$spans" -ts_max_steps "$STEPS" "$@"
  done
done
if [ "$BIG" = 1 ]; then
  # 1 s at 300 km/h (1000 steps of 1 ms): the scene runs on to x = 1000 m, cut at 1 s.
  # -snes_atol 0.25: the residual's round-off floor grows with the line's length
  # (positions up to 60 km, docs/scaling.md); 0.25 N leaves ~6 mN in the contact force.
  for ranks in $BIG_RANKS; do
    run "s1000_np$ranks" "$ranks" runs/interaction/two-pantographs-300.yaml \
      --set catenary.design.spans.count=1000 -ts_max_steps 1000 -snes_atol 0.25 "$@"
  done
fi

/usr/bin/python3 - "$OUT" "$CORES" "$SPANS" "$RANKS" "$BIG" "$BIG_RANKS" <<'PY'
import json, os, sys
import h5py
import numpy as np
out, cores = sys.argv[1], int(sys.argv[2])
spans, ranks, big = sys.argv[3].split(), sys.argv[4].split(), sys.argv[5] == "1"
big_ranks = sys.argv[6].split()
def summary(name):
    with open(os.path.join(out, name, "summary.json")) as f:
        return json.load(f)
def force(name):
    with h5py.File(os.path.join(out, name, "results.h5")) as f:
        return np.concatenate([f[f"/pantographs/{p}/contact_force"][:] for p in f["/pantographs"]])
print(f"{'spans':>5} {'ranks':>5} {'DOFs':>8} {'steps':>5} {'ms/step':>8} {'RTF':>6} "
      f"{'MB/rank':>8} {'MB total':>8} {'factor nnz':>11} {'iface':>5} {'dFc/Fc':>8}")
def row(n, r, name, ref):
    s = summary(name)
    diff = ""
    if ref:
        a, b = force(ref), force(name)
        diff = f"{np.max(np.abs(a - b)) / np.max(np.abs(a)):.1e}"
    mark = "*" if int(r) > cores else ""
    print(f"{n:>5} {r + mark:>5} {s['dofs']:>8} {s['steps']:>5} {s['time_per_step_ms']:>8.2f} "
          f"{s['real_time_factor']:>6.3f} {s['peak_memory_mb']:>8.0f} "
          f"{s.get('peak_memory_total_mb', 0):>8.0f} {s.get('step_factor_nonzeros', 0):>11.3g} "
          f"{s.get('step_interface_unknowns', 0):>5} {diff:>8}")
for n in spans:
    for r in ranks:
        ref = f"s{n}_np{ranks[0]}" if r != ranks[0] else None
        row(n, r, f"s{n}_np{r}", ref)
if big:
    for r in big_ranks:
        ref = f"s1000_np{big_ranks[0]}" if r != big_ranks[0] else None
        row("1000", r, f"s1000_np{r}", ref)
print("* more ranks than cores (oversubscribed): not a speed figure")
PY
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
