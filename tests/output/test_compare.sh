#!/bin/bash
# pcsim compare (postproc/compare.py), read back as a user would:
#  - two runs of the EN 50318 short scene (3 spans) that differ in the head damping of the
#    pantograph model (--set pantographs[0].model.stages[0].damping=30): compare.csv,
#    compare.md and compare.json hold both runs' figures and their differences (checked
#    against the two summary.json), the pantograph model is listed as the input that differs
#    (inputs.diff shows the line), report.html and the PNGs exist and decode;
#  - the run against the synthetic measurement runs/measurements/en50318-short-synthetic.csv
#    (postproc/make_measurement.py from this run: lag 3.7 m, force offset 8 N, noise 5 N)
#    finds the lag and the offset, also from the same data by time in kN;
#    postproc/measurement.py's filter and statistics reproduce
#    the run's own filtered force and figures;
#  - bad inputs: one line naming the file and the reason, exit 2, nothing left behind.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }
scene=$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml
short=(--set catenary.design.spans.count=3 --no-report)
measured=$PCSIM_SOURCE_DIR/runs/measurements/en50318-short-synthetic.csv

"$PCSIM_BIN" run "$scene" "${short[@]}" -o a > a.log 2>&1 || { cat a.log; fail "run a"; }
"$PCSIM_BIN" run "$scene" "${short[@]}" --set 'pantographs[0].model.stages[0].damping=30' -o b \
  > b.log 2>&1 || { cat b.log; fail "run b"; }
"$PCSIM_BIN" compare a b -options_left > ab.log 2>&1 || { cat ab.log; fail "compare a b"; }
grep -q "There are no unused options" ab.log || { cat ab.log; fail "compare: unused options"; }
grep -q "pcsim compare: wrote out/compare-a-b" ab.log || { cat ab.log; fail "default folder"; }
"$PCSIM_BIN" compare a --measurement "$measured" -o am > am.log 2>&1 || { cat am.log; fail "compare a measured"; }

measured=$measured "$PCSIM_PYTHON" - "$PCSIM_SOURCE_DIR/postproc" <<'PY' || fail "compare results"
import csv, json, os, re, sys
from PIL import Image
sys.path.insert(0, sys.argv[1])
import interaction_plots, measurement
ab = "out/compare-a-b"
for name in ("compare.csv", "compare.md", "compare.json", "force_uplift.png", "spectra.png",
             "inputs.diff", "report.html", ".pcsim-result"):
    assert os.path.isfile(os.path.join(ab, name)), name
for name in ("force_uplift.png", "spectra.png"):
    image = Image.open(os.path.join(ab, name))
    image.load()
    assert image.format == "PNG" and image.size[0] > 800, (name, image.size)
page = open(os.path.join(ab, "report.html")).read()
assert page.count('src="data:image/png;base64,') == 2 and 'href="http' not in page
sa, sb = (json.load(open(f + "/summary.json"))["pantographs"][0] for f in ("a", "b"))
assert abs(sa["std_N"] - sb["std_N"]) > 0.1, "the runs do not differ"
rows = list(csv.reader(open(os.path.join(ab, "compare.csv"))))
assert rows[0] == ["pantograph", "figure", "unit", "a", "b", "b - a", "b - a [%]"], rows[0]
std = next(r for r in rows if r[1] == "standard deviation sigma")  # rounded to 0.1 or 0.01 N
assert abs(float(std[3]) - sa["std_N"]) <= 0.05 and abs(float(std[4]) - sb["std_N"]) <= 0.05, std
assert abs(float(std[5]) - (sb["std_N"] - sa["std_N"])) <= 0.05, std
assert abs(float(std[6]) - 100 * (sb["std_N"] - sa["std_N"]) / sa["std_N"]) <= 0.005, std
record = json.load(open(os.path.join(ab, "compare.json")))
mean = next(r for r in record["figures"] if r["key"] == "mean_N")
assert mean["values"] == [sa["mean_N"], sb["mean_N"]], mean
assert mean["differences"][0][0] == sb["mean_N"] - sa["mean_N"], mean
assert len(rows) == 1 + 8, len(rows)  # the 8 EN 50318 figures of one pantograph
differs = {i["role"]: i["differs"] for i in record["inputs"]}
assert differs["pantographs[0].model"] and not differs["catenary.design"], differs
assert re.search(r"^\+.*damping: 30", open(os.path.join(ab, "inputs.diff")).read(), re.M)
assert "| pantographs[0].model | yes |" in open(os.path.join(ab, "compare.md")).read()

# Where the extremes fall: the spans of the section (spans 2-2 of the 3-span scene, or more),
# each run's local extremes; their extremes are summary.json's to the last bit.
spans = list(csv.reader(open(os.path.join(ab, "span_extremes.csv"))))
assert spans[0][:6] == ["pantograph", "span", "from_x [m]", "to_x [m]", "a max [N]", "a min [N]"], spans[0]
assert spans[0][-2:] == ["b - a max [%]", "b - a min [%Fm]"], spans[0]
body = [[float(c) for c in r[1:]] for r in spans[1:]]
assert len(body) >= 1 and all(r[2] > r[1] for r in body), body
for k, s in ((0, sa), (1, sb)):  # printed to 3 decimals
    assert abs(max(r[3 + 2 * k] for r in body) - s["max_N"]) <= 5e-4, (k, s["max_N"])
    assert abs(min(r[4 + 2 * k] for r in body) - s["min_N"]) <= 5e-4, (k, s["min_N"])
for r in body:  # b's local maximum minus a's, in % of a's (printed to 3 decimals)
    assert abs(r[7] - 100 * (r[5] - r[3]) / r[3]) <= 2e-3, r
where = {r["source"]: r for r in record["span_extremes"]}
assert abs(where["a"]["max_N"] - sa["max_N"]) < 1e-9 and abs(where["b"]["min_N"] - sb["min_N"]) < 1e-9
assert where["a"]["max_there_percent"] is None and where["b"]["max_there_percent"] is not None
assert "## Where the extremes fall" in open(os.path.join(ab, "compare.md")).read()
assert '<h2 id="extremes">Where the extremes fall</h2>' in page
assert not os.path.exists("am/span_extremes.csv")  # a run and a measurement: no supports to share

# The measurement: made with a lag of 3.7 m and an offset of 8 N; found: 3.691 m and +7.86 N.
# Lag within 0.05 m: five times the error found, a fifth of the 0.25 m sample spacing. Offset
# within 1 N: 3 sigma of the noise's mean over the 60 m section (240 samples of 5 N: 0.32 N).
m = json.load(open("am/compare.json"))["measurement"]
p = m["pantographs"][0]
assert p["name"] == "pantograph" and p["column"] == "force [N]" and p["distance_m"] == 0, p
assert abs(m["lag_m"] - 3.7) <= 0.05 and abs(p["offset_N"] - 8.0) <= 1.0, m
assert m["correlation"] > 0.99 and m["covers_section"] and abs(p["lag_alone_m"] - m["lag_m"]) < 1e-9, m
figures = {r["key"]: r for r in json.load(open("am/compare.json"))["figures"]}
assert abs(figures["mean_N"]["differences"][0][0] - p["offset_N"]) < 1e-9

# The same measurement by time (t = x / v, the speed in a comment) and in kN: the same lag.
rows = [l.split(",")[:2] for l in open(os.environ["measured"]).read().splitlines()[3:]]
with open("by-time.csv", "w") as f:
    f.write("# speed [km/h]: 300\nt [s],force [kN]\n")
    f.writelines("%.6f,%.6f\n" % (float(x) / (300 / 3.6), float(v) / 1e3) for x, v in rows)
again = measurement.align(measurement.Measurement("by-time.csv"), interaction_plots.Run("a"))
assert abs(again["lag_m"] - m["lag_m"]) < 1e-3, again
assert abs(again["pantographs"][0]["offset_N"] - p["offset_N"]) < 1e-3, again

# The run's filter (zero-phase Butterworth at the cut-off) and statistics, reproduced.
run = interaction_plots.Run("a")
name, p = run.pantograph()
again = measurement.filter_like_run(run.time, p["contact_force"], run.summary["analysis"]["cutoff_hz"])
assert abs(again - p["contact_force_filtered"]).max() < 1e-6, abs(again - p["contact_force_filtered"]).max()
stats = measurement.force_figures(p["position"], p["contact_force_filtered"], p["contact_force"],
                                  run.x_from, run.x_to)
for key in ("mean_N", "std_N", "max_N", "min_N", "loss_of_contact_percent", "samples"):
    assert abs(stats[key] - sa[key]) <= 1e-9 * max(1, abs(sa[key])), (key, stats[key], sa[key])
PY

# Bad inputs: exit 2, one line naming the file and why, nothing left behind.
mkdir notrun mine && touch mine/notes.txt
printf 'x,force [N]\n' > nounits.csv
seq 0 1 100 | sed 's/$/,120/' >> nounits.csv
before=$(ls -A)
# shellcheck source=tests/output/compare_checks.sh
source "$PCSIM_SOURCE_DIR/tests/output/compare_checks.sh"
bad "notrun: not a pcsim run result folder: it has no summary.json" a notrun -o x
bad "missing: not found" a missing -o x
bad "missing.csv: not found" a --measurement missing.csv -o x
bad "nounits.csv: header column 'x' has no unit" a --measurement nounits.csv -o x
bad "nounits.csv: a file, not a run result folder (a measurement is given with --measurement)" a nounits.csv
bad "needs two run result folders" a -o x
bad "'a' is or holds a, an input" a b -o a
bad "'mine' is not empty and was not written by pcsim" a b -o mine
bad "takes no --set" a b --set simulation.speed_kmh=250
[ -f a/summary.json ] && [ -f mine/notes.txt ] || fail "an input or a user's folder was touched"
echo "compare checks passed"
