#!/bin/bash
# Static blow-off of the EN 50318 line (issue 25, docs/conditions.md
# "Blow-off"): `pcsim static` under a 30 m/s cross-wind, on 1 and 2 ranks:
#  1. the contact wire's lateral deflection at the interior mid-spans
#     (spans 2-9) against the independent estimate of
#     runs/conditions/blowoff_estimate.py (strings coupled by the droppers'
#     pendulum stiffness, each dropper's drag half on either wire; no pcsim
#     code): measured -0.71 %; bound 1.2 %, the estimate's own modelling
#     error (constant dropper forces from the weight's share, straight
#     strings) being of that order, while the line without the droppers'
#     drag is -2.4 %, the contact wire alone (no messenger pulling through
#     the droppers) -4.3 % and the wind's absence -100 %;
#  2. the supports hold the stagger (+-0.2 m), the results carry the
#     blow-off datasets with their unit, summary.json its entry;
#  3. the two partitions agree to 1e-9 m;
#  4. the mean speed from EN 1991-1-4's basic wind speed (conditions.wind.basic_speed):
#     v_b 27 m/s at 6 m, category II: 0.19 ln(6/0.05) 27 = 24.5598 m/s; category IV
#     (z_min 10 m): 0.19 (1/0.05)^0.07 ln(10/1) 27 = 14.5682 m/s.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
S=$PCSIM_SOURCE_DIR
"$PCSIM_BIN" static "$S/runs/en50318-static.yaml" --set conditions.wind.speed=30 -o "$tmp/np1" \
  > "$tmp/np1.log" 2>&1 || { cat "$tmp/np1.log"; exit 1; }
"$S/scripts/mpirun.sh" -n 2 "$PCSIM_BIN" static "$S/runs/en50318-static.yaml" \
  --set conditions.wind.speed=30 -o "$tmp/np2" > "$tmp/np2.log" 2>&1 ||
  { cat "$tmp/np2.log"; exit 1; }
grep -q "blow-off: contact wire" "$tmp/np1.log" || { cat "$tmp/np1.log"; exit 1; }
"$PCSIM_PYTHON" - "$tmp" "$S/runs/conditions" <<'PY'
import json, sys
import h5py
import numpy as np
tmp, runs = sys.argv[1], sys.argv[2]
sys.path.insert(0, runs)
from blowoff_estimate import estimate
est = estimate(30.0)
res = {}
for np_ in ("np1", "np2"):
    with h5py.File(f"{tmp}/{np_}/static.h5") as f:
        b = f["blow_off"]
        for name in ("x", "lateral", "lateral_bare", "max_excursion", "permissible"):
            assert b[name].attrs["unit"] in (b"m", "m"), (name, b[name].attrs["unit"])
        x, lat, bare, sup = (np.array(b[k]) for k in ("x", "lateral", "lateral_bare", "at_support"))
        res[np_] = lat
    mid = (sup == 0) & (x > 60) & (x < 540)
    defl = lat[mid] - bare[mid]
    rel = defl / est["contact_mid"] - 1
    alone = est["contact_alone"] / est["contact_mid"] - 1
    print(f"{np_}: interior mid-span deflection {defl.min():.5f} .. {defl.max():.5f} m, estimate "
          f"{est['contact_mid']:.5f} m: {100 * rel.min():+.2f} .. {100 * rel.max():+.2f} % "
          f"(the contact wire alone {100 * alone:+.2f} %)")
    assert np.all(np.abs(rel) < 0.012), rel
    assert np.allclose(np.abs(lat[sup == 1]), 0.2, atol=1e-9), lat[sup == 1]
    s = json.load(open(f"{tmp}/{np_}/summary.json"))["blow_off"]
    assert s["inside"] and abs(s["permissible_m"] - 0.40) < 1e-12, s
diff = np.max(np.abs(res["np1"] - res["np2"]))
print(f"1 and 2 ranks: largest difference {diff:.2e} m")
assert diff < 1e-9, diff
PY
for case in "II:24.5598" "IV:14.5682"; do
  IFS=: read -r category speed <<< "$case"
  "$PCSIM_BIN" static "$S/runs/en50318-static.yaml" -o "$tmp/vb-$category" \
    --set "conditions.wind={basic_speed: 27, terrain_category: $category}" > "$tmp/vb.log" 2>&1 ||
    { cat "$tmp/vb.log"; exit 1; }
  grep -q "wind $speed m/s" "$tmp/vb.log" || { grep conditions: "$tmp/vb.log"; exit 1; }
done
echo "basic_speed: the EN 1991-1-4 mean speeds"
