#!/bin/bash
# Static elasticity of the stitched and unstitched catenary (docs/lines.md,
# "Stitched and unstitched elasticity"): `pcsim static` on
# runs/lines/elasticity-stitched.yaml and elasticity-unstitched.yaml (100 N
# upward every 0.5 m over spans 5-6), then the uplift per 100 N every 5 m
# along span 5 (240..300 m) for both, and over both spans its max, min,
# max/min and the non-uniformity (max - min) / (max + min).
#
#   runs/lines/elasticity.sh
#
# Environment: PCSIM (default build/pcsim), OUT (default out/lines). Results:
# $OUT/elasticity-{stitched,unstitched}/elasticity.csv. One rank, nice.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PCSIM=${PCSIM:-$ROOT/build/pcsim}
OUT=${OUT:-$ROOT/out/lines}
mkdir -p "$OUT"
for variant in stitched unstitched; do
  echo "pcsim static runs/lines/elasticity-$variant.yaml -o $OUT/elasticity-$variant"
  nice "$PCSIM" static "$ROOT/runs/lines/elasticity-$variant.yaml" -o "$OUT/elasticity-$variant" --overwrite \
    > "$OUT/elasticity-$variant.log" 2>&1 ||
    { tail -n 5 "$OUT/elasticity-$variant.log"; exit 1; }
  grep "elasticity (" "$OUT/elasticity-$variant.log" | sed 's/^ */  /'
done
/usr/bin/python3 - "$OUT/elasticity-stitched/elasticity.csv" \
  "$OUT/elasticity-unstitched/elasticity.csv" <<'PY'
import csv, sys

def read(path):  # x [m] -> uplift [mm per 100 N]
    rows = [r for r in csv.reader(open(path)) if r and not r[0].startswith("#")]
    return {round(float(r[0]), 3): float(r[1]) for r in rows}

st, un = read(sys.argv[1]), read(sys.argv[2])
print("\n| x [m] | stitched [mm/100 N] | unstitched [mm/100 N] |")
print("|---|---|---|")
for x in range(240, 301, 5):
    print(f"| {x} | {st[float(x)]:.1f} | {un[float(x)]:.1f} |")
print("\n| over 240..360 m | stitched | unstitched |")
print("|---|---|---|")
stats = {}
for name, e in (("stitched", st), ("unstitched", un)):
    hi, lo = max(e.values()), min(e.values())
    stats[name] = (hi, lo, hi / lo, (hi - lo) / (hi + lo))
for i, label in enumerate(("max [mm/100 N]", "min [mm/100 N]", "max / min",
                           "non-uniformity (max - min) / (max + min)")):
    fmt = "{:.1f}" if i < 2 else ("{:.2f}" if i == 2 else "{:.1%}")
    print(f"| {label} | " + " | ".join(fmt.format(stats[n][i]) for n in ("stitched", "unstitched"))
          + " |")
PY
