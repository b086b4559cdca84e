#!/usr/bin/env bash
# A/B benchmark of the FE time step between two pcsim binaries (e.g. a build
# of the previous commit and one of this): the EN 50318 case at 300 km/h with
# spans.count = 10, 40, 100 on 1 and 2 ranks, each binary REPEAT times,
# interleaved; prints the median ms/step of each, their ratio and the largest
# difference of the contact force between the two.
#   runs/bench_step_ab.sh BEFORE_BIN AFTER_BIN [extra pcsim options]
# Environment: SPANS="10 40 100" RANKS="1 2" STEPS=600 REPEAT=3. Run it on an
# otherwise idle machine: it measures wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { echo "usage: $0 BEFORE_BIN AFTER_BIN [pcsim options]" >&2; exit 2; }
BINS=("$1" "$2")
shift 2
for b in "${BINS[@]}"; do [ -x "$b" ] || { echo "not an executable: $b" >&2; exit 2; }; done
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
      for b in 0 1; do
        name="s${spans}_np${ranks}_b${b}_$k"
        scripts/mpirun.sh -n "$ranks" "${BINS[$b]}" run runs/en50318-300.yaml -o "$OUT/$name" \
          --overwrite --no-report --set catenary.design.spans.count="$spans" \
          -ts_max_steps "$STEPS" "$@" >"$OUT/$name.log" 2>&1 ||
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
print("| spans | ranks | ms/step before | ms/step after | before / after | dFc/Fc |")
print("|---:|---:|---:|---:|---:|---:|")
for s in spans:
    for r in ranks:
        a = [ms(f"s{s}_np{r}_b0_{k}") for k in range(1, repeat + 1)]
        b = [ms(f"s{s}_np{r}_b1_{k}") for k in range(1, repeat + 1)]
        fa, fb = force(f"s{s}_np{r}_b0_1"), force(f"s{s}_np{r}_b1_1")
        gap = np.max(np.abs(fa - fb)) / np.max(np.abs(fa))
        ra, rb = np.median(a), np.median(b)
        print(f"| {s} | {r} | {ra:.2f} | {rb:.2f} | {ra / rb:.2f} | {gap:.1e} |")
PY
