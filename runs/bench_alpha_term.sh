#!/usr/bin/env bash
# Benchmark of the HHT alpha-term taken from the previous step's last residual
# (-ts_hht_reuse_alpha_term, docs/scaling.md): the EN 50318 case at 300 km/h
# with spans.count = 10, 40, 100 on 1 and 2 ranks, each run with the term
# reused (default) and evaluated, REPEAT times interleaved; prints the median
# ms/step of each, their ratio and the largest difference of the contact force
# between the two (round-off: <= 1e-9 of its maximum).
#   runs/bench_alpha_term.sh [extra pcsim options]
# Environment: SPANS="10 40 100" RANKS="1 2" STEPS=600 REPEAT=3. Run it on an
# otherwise idle machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
SPANS=${SPANS:-10 40 100}
RANKS=${RANKS:-1 2}
STEPS=${STEPS:-600}
REPEAT=${REPEAT:-3}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
for spans in $SPANS; do
  for ranks in $RANKS; do
    for k in $(seq "$REPEAT"); do
      for reuse in 1 0; do
        name="s${spans}_np${ranks}_r${reuse}_$k"
        scripts/mpirun.sh -n "$ranks" build/pcsim run runs/en50318-300.yaml -o "$OUT/$name" \
          --overwrite --no-report --set catenary.design.spans.count="$spans" \
          -ts_max_steps "$STEPS" -ts_hht_reuse_alpha_term "$reuse" "$@" >"$OUT/$name.log" 2>&1 ||
          { echo "run failed: $name"; tail -20 "$OUT/$name.log"; exit 1; }
      done
    done
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$OUT" "$SPANS" "$RANKS" "$REPEAT" <<'PY'
import json, sys
import h5py
import numpy as np
out, spans, ranks, repeat = sys.argv[1], sys.argv[2].split(), sys.argv[3].split(), int(sys.argv[4])
def ms(name):
    return json.load(open(f"{out}/{name}/summary.json"))["time_per_step_ms"]
def force(name):
    with h5py.File(f"{out}/{name}/results.h5") as f:
        return f["/pantographs/pantograph/contact_force"][:]
print("| spans | ranks | ms/step reused | ms/step evaluated | evaluated / reused | dFc/Fc |")
print("|---:|---:|---:|---:|---:|---:|")
for s in spans:
    for r in ranks:
        a = [ms(f"s{s}_np{r}_r1_{k}") for k in range(1, repeat + 1)]
        b = [ms(f"s{s}_np{r}_r0_{k}") for k in range(1, repeat + 1)]
        fa, fb = force(f"s{s}_np{r}_r1_1"), force(f"s{s}_np{r}_r0_1")
        gap = np.max(np.abs(fa - fb)) / np.max(np.abs(fb))
        ra, rb = np.median(a), np.median(b)
        print(f"| {s} | {r} | {ra:.2f} | {rb:.2f} | {rb / ra:.2f} | {gap:.1e} |")
PY
