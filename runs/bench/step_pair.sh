#!/usr/bin/env bash
# Two variants of the FE time step, interleaved: the EN 50318 case at 300 km/h
# (or SCENE) with spans.count = SPANS on RANKS ranks, each variant REPEAT
# times; prints the median ms/step of each, the ratio A / B and the largest
# difference of the contact force between them (relative to A's maximum, over
# the pantographs). A variant is a binary and its own options (one word list,
# may be empty).
#   runs/bench/step_pair.sh LABEL_A BIN_A "OPTIONS_A" LABEL_B BIN_B "OPTIONS_B" [common options]
# Environment: SPANS="10 40 100" RANKS="1 2" STEPS=600 REPEAT=3
# SCENE=runs/en50318-300.yaml. Used by runs/bench_step_ab.sh and
# runs/bench_alpha_term.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."
[ $# -ge 6 ] || { echo "usage: $0 LABEL_A BIN_A OPTIONS_A LABEL_B BIN_B OPTIONS_B [options]" >&2; exit 2; }
LABELS=("$1" "$4")
BINS=("$2" "$5")
read -r -a OPTS_A <<<"$3"
read -r -a OPTS_B <<<"$6"
shift 6
for b in "${BINS[@]}"; do [ -x "$b" ] || { echo "not an executable: $b" >&2; exit 2; }; done
SPANS=${SPANS:-10 40 100}
RANKS=${RANKS:-1 2}
STEPS=${STEPS:-600}
REPEAT=${REPEAT:-3}
SCENE=${SCENE:-runs/en50318-300.yaml}
[ -f "$SCENE" ] || { echo "no such scene: $SCENE" >&2; exit 2; }
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
for spans in $SPANS; do
  for ranks in $RANKS; do
    for k in $(seq "$REPEAT"); do
      for v in 0 1; do
        name="s${spans}_np${ranks}_v${v}_$k"
        if [ "$v" = 0 ]; then opts=(${OPTS_A[@]+"${OPTS_A[@]}"}); else opts=(${OPTS_B[@]+"${OPTS_B[@]}"}); fi
        scripts/mpirun.sh -n "$ranks" "${BINS[$v]}" run "$SCENE" -o "$OUT/$name" \
          --overwrite --no-report --set catenary.design.spans.count="$spans" \
          -ts_max_steps "$STEPS" ${opts[@]+"${opts[@]}"} "$@" >"$OUT/$name.log" 2>&1 ||
          { echo "run failed: $name"; tail -20 "$OUT/$name.log"; exit 1; }
      done
    done
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$OUT" "$SPANS" "$RANKS" "$REPEAT" "${LABELS[0]}" "${LABELS[1]}" <<'PY'
import json, sys
import h5py
import numpy as np
out, spans, ranks = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
repeat, label_a, label_b = int(sys.argv[4]), sys.argv[5], sys.argv[6]
def ms(name):
    return json.load(open(f"{out}/{name}/summary.json"))["time_per_step_ms"]
def force(name):
    with h5py.File(f"{out}/{name}/results.h5") as f:
        return np.concatenate([f[f"/pantographs/{p}/contact_force"][:]
                               for p in sorted(f["/pantographs"])])
print(f"| spans | ranks | ms/step {label_a} | ms/step {label_b} | {label_a} / {label_b} | dFc/Fc |")
print("|---:|---:|---:|---:|---:|---:|")
for s in spans:
    for r in ranks:
        a = [ms(f"s{s}_np{r}_v0_{k}") for k in range(1, repeat + 1)]
        b = [ms(f"s{s}_np{r}_v1_{k}") for k in range(1, repeat + 1)]
        fa, fb = force(f"s{s}_np{r}_v0_1"), force(f"s{s}_np{r}_v1_1")
        gap = np.max(np.abs(fa - fb)) / np.max(np.abs(fa))
        ra, rb = np.median(a), np.median(b)
        print(f"| {s} | {r} | {ra:.2f} | {rb:.2f} | {ra / rb:.2f} | {gap:.1e} |")
PY
