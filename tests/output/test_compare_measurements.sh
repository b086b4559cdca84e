#!/bin/bash
# pcsim compare against a measurement of two pantographs, and a measurement by time with a
# varying speed (postproc/measurement.py, measurement_csv.py, make_measurement.py):
#  - a run of the two-pantograph 55 m-span scene (tests/simulation/data/
#    span55-two-pantographs-short.yaml: 'leading' and 'trailing', 100 m apart, 320 km/h,
#    analysis section 165-275 m); make_measurement.py makes a synthetic measurement of both
#    (columns 'force leading [N]', 'force trailing [N]': lag 3.7 m, offsets +8 N and -6 N,
#    5 N of noise each); pcsim compare finds the one lag and each offset, lists the figures
#    of both pantographs, one force panel per pantograph;
#  - the same rows by time with a speed column that varies +-25 % along the line (times
#    from the trapezoid rule, so the positions integrate back to the file's): the same lag
#    and offsets as by position;
#  - bad inputs: one line naming the file, the column and the reason, exit 2, nothing left
#    behind.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }
scene=$PCSIM_SOURCE_DIR/tests/simulation/data/span55-two-pantographs-short.yaml
post=$PCSIM_SOURCE_DIR/postproc

"$PCSIM_BIN" run "$scene" --no-report -o r > r.log 2>&1 || { cat r.log; fail "run"; }
"$PCSIM_PYTHON" "$post/make_measurement.py" r -o two.csv --pantograph leading,trailing \
  --lag 3.7 --offset 8,-6 --noise 5 > make.log 2>&1 || { cat make.log; fail "make_measurement"; }
"$PCSIM_BIN" compare r --measurement two.csv -o rm > rm.log 2>&1 || { cat rm.log; fail "compare r two.csv"; }

"$PCSIM_PYTHON" - "$post" <<'PY' || fail "compare results"
import csv, json, math, sys
import numpy as np
from PIL import Image
sys.path.insert(0, sys.argv[1])
import interaction_plots, measurement

record = json.load(open("rm/compare.json"))
m = record["measurement"]
by_name = {p["name"]: p for p in m["pantographs"]}
assert [p["column"] for p in m["pantographs"]] == ["force leading [N]", "force trailing [N]"], m
assert abs(by_name["trailing"]["distance_m"] + 100.0) < 1e-6, by_name  # 5 m against 105 m
print("two pantographs: lag %.4f m, offsets %+.3f N, %+.3f N, own lags %.4f m, %.4f m"
      % (m["lag_m"], by_name["leading"]["offset_N"], by_name["trailing"]["offset_N"],
         by_name["leading"]["lag_alone_m"], by_name["trailing"]["lag_alone_m"]))
# Made with a lag of 3.7 m and offsets of +8 N and -6 N; found: 3.6954 m (own lags 3.6972 m and
# 3.6925 m), +7.90 N and -5.74 N. Lags within 0.05 m: ten times the error found, a fifth of the
# 0.25 m sample spacing. Offsets within 0.75 N: 3 sigma of the noise's mean over the 110 m
# section (440 samples of 5 N: 0.24 N).
assert abs(m["lag_m"] - 3.7) <= 0.05, m
for name, offset in (("leading", 8.0), ("trailing", -6.0)):
    p = by_name[name]
    assert abs(p["offset_N"] - offset) <= 0.75 and abs(p["lag_alone_m"] - 3.7) <= 0.05, p
    assert p["correlation"] > 0.99 and p["covers_section"], p
assert m["covers_section"] and m["correlation"] > 0.99, m
for name, p in by_name.items():
    mean = next(r for r in record["figures"] if r["pantograph"] == name and r["key"] == "mean_N")
    assert abs(mean["differences"][0][0] - p["offset_N"]) < 1e-9, (mean, p)
rows = list(csv.reader(open("rm/compare.csv")))
assert rows[0] == ["pantograph", "figure", "unit", "r", "two", "two - r", "two - r [%]"], rows[0]
assert [r[0] for r in rows[1:]].count("leading") == [r[0] for r in rows[1:]].count("trailing") == 8, rows
assert all(r[4] for r in rows[1:]), rows  # the measurement has every figure of both
text = open("rm/compare.md").read()
assert "Pantograph 'trailing' (column 'force trailing [N]'): force offset" in text, text
image = Image.open("rm/force_uplift.png")  # three panels: leading, trailing, uplift
assert image.size[1] >= 3 * 3.2 * 110 - 2, image.size

# The trailing pantograph alone: x is then its own position (100 m behind), and the run's
# leading pantograph is left out; the same lag and offset as with both (the same tolerances).
with open("trailing.csv", "w") as f:
    f.write("x [m],force trailing [N]\n")
    f.writelines("%.3f,%s\n" % (float(l.split(",")[0]) - 100, l.split(",")[2])
                 for l in open("two.csv").read().splitlines()[3:])
alone = measurement.align(measurement.Measurement("trailing.csv"), interaction_plots.Run("r"))
p = alone["pantographs"][0]
assert p["name"] == "trailing" and p["distance_m"] == 0 and len(alone["pantographs"]) == 1, p
assert abs(alone["lag_m"] - 3.7) <= 0.05 and abs(p["offset_N"] + 6.0) <= 0.75, (alone["lag_m"], p)

# The same rows by time, the speed varying +-25 % (240-400 km/h) every 70 m: t from the
# trapezoid rule, t0 = x0 / v0, so that x = v0 t0 + the trapezoid integral of v dt is the
# file's x again.
lines = open("two.csv").read().splitlines()
table = np.array([[float(c) for c in l.split(",")] for l in lines[3:]])
x = table[:, 0]
v = 320 / 3.6 * (1 + 0.25 * np.sin(2 * math.pi * (x - x[0]) / 70.0))
t = x[0] / v[0] + np.concatenate(([0.0], np.cumsum(2 * np.diff(x) / (v[1:] + v[:-1]))))
with open("by-time.csv", "w") as f:
    f.write("# the rows of two.csv by time, the speed varying\n")
    f.write("t [s],speed [m/s]," + lines[2].split(",", 1)[1] + "\n")
    f.writelines("%.8f,%.6f,%s\n" % (ti, vi, ",".join("%.3f" % c for c in row[1:]))
                 for ti, vi, row in zip(t, v, table))
by_time = measurement.Measurement("by-time.csv")
# 0.7 um apart at most (times printed to 1e-8 s: 1 um at 400 km/h per row); within 10 um.
assert np.abs(by_time.x - x).max() < 1e-5, np.abs(by_time.x - x).max()
run = interaction_plots.Run("r")
again = measurement.align(by_time, run)
print("by time, varying speed: lag %.4f m, offsets %+.3f N, %+.3f N"
      % (again["lag_m"], again["pantographs"][0]["offset_N"], again["pantographs"][1]["offset_N"]))
# By position 3.6954 m, +7.899 N, -5.737 N; by time 3.6932 m, +7.856 N, -5.651 N. The filter
# works in time, so its cut-off in space follows the speed (+-25 %): the filtered forces, and
# so the lag and the means, move a little. Lag within 0.01 m (five times the 0.0022 m found,
# a 25th of the spacing), offsets within 0.3 N (3.5 times the 0.086 N found, an eighth of the
# noise's own 0.24 N).
by_position = json.load(open("rm/compare.json"))["measurement"]
assert abs(again["lag_m"] - by_position["lag_m"]) <= 0.01, (again["lag_m"], by_position)
for p, q in zip(again["pantographs"], by_position["pantographs"]):
    assert abs(p["offset_N"] - q["offset_N"]) <= 0.3, (p["name"], p["offset_N"], q)
PY

# Bad inputs: exit 2, one line naming the file, the column and why, nothing left behind.
header() { { echo "$1"; tail -n +4 two.csv; } > "$2"; }
header "x [m],force leading [N],force middle [N],uplift 110 [mm],uplift 165 [mm]" unknown.csv
header "x [m],force leading [N],force leading [N],uplift 110 [mm],uplift 165 [mm]" twice.csv
header "x [m],force leading [N],force trailing,uplift 110 [mm],uplift 165 [mm]" nounit.csv
header "x [m],force [N],force trailing [N],uplift 110 [mm],uplift 165 [mm]" unnamed.csv
{ echo "# speed [km/h]: 320"; echo "t [s],speed [km/h],force leading [N]";
  for i in $(seq 1 100); do echo "$i.0,320,120"; done; } > speed-twice.csv
{ echo "t [s],speed [km/h],force leading [N]";
  for i in $(seq 1 100); do echo "$i.0,$((60 - i)),120"; done; } > standstill.csv
{ echo "x [m],speed [km/h],force leading [N]";
  for i in $(seq 1 100); do echo "$i.0,320,120"; done; } > speed-by-x.csv
before=$(ls -A)
# shellcheck source=tests/output/compare_checks.sh
source "$PCSIM_SOURCE_DIR/tests/output/compare_checks.sh"
bad "unknown.csv: column 'force middle \[N\]': the run r has no pantograph 'middle' (it has: leading, trailing)" \
  r --measurement unknown.csv -o x
bad "twice.csv: header column 3 'force leading \[N\]' repeats column 2 'force leading \[N\]'" \
  r --measurement twice.csv -o x
bad "nounit.csv: header column 'force trailing' has no unit (write e.g. 'force trailing \[N\]')" \
  r --measurement nounit.csv -o x
bad "unnamed.csv: header column 'force \[N\]' (the first pantograph) together with other force columns" \
  r --measurement unnamed.csv -o x
bad "speed-twice.csv: the speed is given twice, by column 'speed \[km/h\]' and by comment line '# speed \[km/h\]: 320'" \
  r --measurement speed-twice.csv -o x
bad "standstill.csv: line 61: column 'speed \[km/h\]' is 0: the speed must be positive" \
  r --measurement standstill.csv -o x
bad "speed-by-x.csv: header column 'speed \[km/h\]' goes with a time column 't \[s\]', not with a position column" \
  r --measurement speed-by-x.csv -o x
sed -n 1,203p two.csv > short.csv  # 50 m of rows, 109-159 m (no `tail | head`: under pipefail tail may die of SIGPIPE)
before=$(ls -A)
bad "short.csv: does not cover the run's analysis section 165-275 m at any lag within 27.5 m" \
  r --measurement short.csv -o x
echo "compare measurement checks passed"
