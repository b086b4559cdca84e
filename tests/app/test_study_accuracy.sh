#!/bin/bash
# `pcsim study accuracy` end to end on a tiny scene (tests/app/data/study-tiny.yaml:
# three 30 m spans, 1.5 m elements, 200 km/h, 1.44 s): the star grid over
# fidelity (nonlinear, linear, modal), time step x 1, 2, element length x 1, 2
# and modal cut-off x 0.8, 1.2 (and the scene's 1.1) is 10 runs on one rank
# (~3 s on an idle machine), then linear and modal on two ranks.
# Asserted: the files (accuracy.csv, accuracy.md, accuracy.svg, a folder per
# run), the reference (the nonlinear run, finest FE), and what the physics
# says about the errors (measured values in brackets):
# - the reduction error of the modal runs falls as the cut-off rises
#   (29 Hz: 9.8 %, 40.5 Hz: 1.6 %, 44 Hz: 0.6 %);
# - the coarser mesh (3 m) is worse than the base mesh (sigma -4.0 % against
#   +0.2 %; the linear and nonlinear catenaries differ by ~1 % here);
# - the linearised catenary's sigma is within 0.5 % of the nonlinear one's (0.22 %);
# - a modal run is on the Pareto front.
# On two ranks every figure equals the one-rank run's to 1e-6 (the runs are
# rank-independent to ~1e-10, tests/contact/test_run_ranks.sh).
# Costs are not asserted (the machine is shared).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$PCSIM_SOURCE_DIR/tests/app/data/study-tiny.yaml
mpirun=$PCSIM_SOURCE_DIR/scripts/mpirun.sh

# Bad input: exit 2, one message naming the key.
for bad in "study precision $scene|'study'" "study accuracy $scene -study_models fast|-study_models" \
  "study accuracy $scene -study_dt_factors 1,-2|-study_dt_factors"; do
  set +e
  "$PCSIM_BIN" ${bad%|*} -o "$tmp/bad" > "$tmp/bad.log" 2>&1
  code=$?
  set -e
  [ $code -eq 2 ] && grep -q -- "${bad#*|}" "$tmp/bad.log" || { echo "$bad: exit $code"; cat "$tmp/bad.log"; exit 1; }
done

"$PCSIM_BIN" study accuracy "$scene" -o "$tmp/np1" --cache "$tmp/cache" \
  -study_models nonlinear,linear,modal -study_dt_factors 1,2 -study_h_factors 1,2 \
  -study_cutoff_factors 0.8,1.2 > "$tmp/np1.log" 2>&1 || { cat "$tmp/np1.log"; exit 1; }
"$mpirun" -n 2 "$PCSIM_BIN" study accuracy "$scene" -o "$tmp/np2" --cache "$tmp/cache" \
  -study_models linear,modal -study_dt_factors 1 -study_h_factors 1 -study_cutoff_factors 1.1 \
  -study_vertical false > "$tmp/np2.log" 2>&1 || { cat "$tmp/np2.log"; exit 1; }
grep -q "10 runs on 1 rank" "$tmp/np1.log" || { cat "$tmp/np1.log"; exit 1; }
grep -q "2 runs on 2 rank" "$tmp/np2.log" || { cat "$tmp/np2.log"; exit 1; }

"$PCSIM_PYTHON" - "$tmp" <<'PY'
import csv, json, os, sys
d = sys.argv[1]
for f in ("accuracy.csv", "accuracy.md", "accuracy.svg", "study.json", "runs/1/summary.json"):
    assert os.path.isfile(f"{d}/np1/{f}"), f
rows = list(csv.DictReader(open(f"{d}/np1/accuracy.csv")))
assert len(rows) == 10, len(rows)
assert all(r["failure"] == "" for r in rows), [r["failure"] for r in rows]
key = lambda r: (r["model"], float(r["dt_s"]), float(r["element_length_m"]), float(r["cutoff_hz"]),
                 r["vertical_only"])
by = {key(r): r for r in rows}
ref = [r for r in rows if r["reference"] == "1"]
assert len(ref) == 1 and ref[0]["model"] == "nonlinear", ref
num = lambda r, k: float(r[k])

modal = sorted((r for r in rows if r["model"] == "modal" and r["vertical_only"] == "0"
                and num(r, "element_length_m") == 1.5 and num(r, "dt_s") == 1e-3),
               key=lambda r: num(r, "cutoff_hz"))
cuts = [(round(num(r, "cutoff_hz"), 1), num(r, "reduction_err_worst_pct")) for r in modal]
print("modal cut-off [Hz] and reduction error [%]:", cuts)
assert [c for c, _ in cuts] == [29.4, 40.5, 44.1], cuts
assert cuts[0][1] > cuts[1][1] > cuts[2][1], cuts

linear = by[("linear", 1e-3, 1.5, 0.0, "0")]
coarse = by[("linear", 1e-3, 3.0, 0.0, "0")]
print("linear sigma error [%]: base mesh", linear["err_std_pct"], "coarse mesh", coarse["err_std_pct"])
assert abs(num(coarse, "err_std_pct")) > abs(num(linear, "err_std_pct")) + 2
assert abs(num(linear, "err_std_pct")) < 0.5
assert any(r["pareto"] == "1" for r in modal), "no modal run on the Pareto front"
assert open(f"{d}/np1/accuracy.svg").read().count("<circle") == 9 + 3  # runs but the reference, legend

two = list(csv.DictReader(open(f"{d}/np2/accuracy.csv")))
assert len(two) == 2 and two[0]["reference"] == "1", two
for r in two:
    one = by[key(r)]
    for k in ("mean_N", "std_N", "stat_max_N", "max_N", "min_N", "uplift_m"):
        assert abs(num(r, k) - num(one, k)) <= 1e-6 * abs(num(one, k)), (r["model"], k, r[k], one[k])
print("two ranks: the same figures")
PY
