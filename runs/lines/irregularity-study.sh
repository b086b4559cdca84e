#!/bin/bash
# Contact force against the RMS amplitude of a random contact-wire
# irregularity (docs/lines.md, "Contact-wire irregularities"):
# runs/lines/irregular-random-300.yaml (EN 50318 reference catenary,
# 1-50 m wavelengths, seed 1, 300 km/h) at RMS amplitudes 0, 0.5, 1 and 2 mm
# through --set catenary.design.irregularities.random.rms, then the EN 50318
# statistics of the contact force over spans 5-6 per amplitude.
#
#   runs/lines/irregularity-study.sh            # 4 runs, ~2 min each (1 core)
#   runs/lines/irregularity-study.sh --reuse    # reuse runs whose summary.json exists
#
# Environment: PCSIM (default build/pcsim), OUT (default out/lines). Results:
# $OUT/irregular-rms-<mm>/{results.h5,summary.json}. Serial, one rank, nice.
# Two tables: the EN 50318 statistics of summary.json (force low-pass
# filtered at 20 Hz) and the same moments of the unfiltered force
# (results.h5) over the same stretch.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
PCSIM=${PCSIM:-$ROOT/build/pcsim}
OUT=${OUT:-$ROOT/out/lines}
REUSE=0
[ "${1:-}" = "--reuse" ] && REUSE=1
mkdir -p "$OUT"
dirs=()
for mm in 0 0.5 1 2; do
  rms=$(/usr/bin/python3 -c "print($mm / 1000)")
  dir=$OUT/irregular-rms-$mm
  dirs+=("$mm=$dir")
  if [ $REUSE = 1 ] && [ -f "$dir/summary.json" ]; then
    echo "reuse $dir"
    continue
  fi
  echo "pcsim run runs/lines/irregular-random-300.yaml --set catenary.design.irregularities.random.rms=$rms -o $dir"
  nice "$PCSIM" run "$ROOT/runs/lines/irregular-random-300.yaml" \
    --set "catenary.design.irregularities.random.rms=$rms" -o "$dir" --overwrite --no-report \
    > "$dir.log" 2>&1 || { tail -n 5 "$dir.log"; exit 1; }
done
/usr/bin/python3 - "${dirs[@]}" <<'PY'
import json, sys

import h5py

runs = [pair.split("=", 1) for pair in sys.argv[1:]]
print("\nEN 50318 statistics (contact force filtered at the analysis cutoff, summary.json):\n")
print("| RMS [mm] | mean [N] | sigma [N] | max [N] | min [N] | mean + 3 sigma [N] | mean - 3 sigma [N] | loss of contact [%] |")
print("|---|---|---|---|---|---|---|---|")
for mm, d in runs:
    p = json.load(open(d + "/summary.json"))["pantographs"][0]
    print(f"| {mm} | {p['mean_N']:.1f} | {p['std_N']:.1f} | {p['max_N']:.1f} | {p['min_N']:.1f} "
          f"| {p['stat_max_N']:.1f} | {p['stat_min_N']:.1f} | {p['loss_of_contact_percent']:.2f} |")
print("\nUnfiltered contact force over the same stretch (results.h5):\n")
print("| RMS [mm] | mean [N] | sigma [N] | max [N] | min [N] |")
print("|---|---|---|---|---|")
for mm, d in runs:
    s = json.load(open(d + "/summary.json"))
    a = s["analysis"]
    with h5py.File(d + "/results.h5", "r") as f:
        name = s["pantographs"][0]["name"]
        x = f[f"/pantographs/{name}/position"][()]
        force = f[f"/pantographs/{name}/contact_force"][()]
    F = force[(x >= a["from_x"]) & (x <= a["to_x"])]
    print(f"| {mm} | {F.mean():.1f} | {F.std():.1f} | {F.max():.1f} | {F.min():.1f} |")
PY
