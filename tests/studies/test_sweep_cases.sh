#!/bin/bash
# `pcsim sweep SCENE --cases FILE.csv` (docs/studies.md):
#  1. three cases of a table (two keys: the static force and the speed) on the
#     short three-span scene: sweep.csv holds each case's values and figures,
#     summary.json the table's columns and its '# sample:' record, the mean
#     contact force follows the static force; postproc/sensitivity.py reads it;
#  2. a bad table (missing file, ragged row, unknown key, bad value, a quote
#     not closed, no case, a swept --set as well) is exit 2 with one message
#     naming the file and the reason, before any case, nothing left behind.
#  3. -ts_max_time past one case's run (a faster case runs shorter): exit 2
#     before any case, one message naming the option and that case (an
#     option bad in itself names no case).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
fail() { echo "FAIL: $*"; exit 1; }

cat > cases.csv <<'CSV'
# sample: {"design":"lhs","seed":4,"note":"written by hand for the test"}
pantographs[0].static_force,simulation.speed_kmh
110,180

120, 200
130,220
CSV
"$PCSIM_BIN" sweep "$scene" --cases cases.csv -o sw -j 2 --no-report > sweep.log 2>&1 ||
  { cat sweep.log; fail "the sweep failed"; }
[ -d sw/cases/01 ] && [ -d sw/cases/02 ] && [ -d sw/cases/03 ] || fail "case folders: $(ls sw/cases)"
"$PCSIM_PYTHON" - sw <<'PY' || fail "the results"
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/sweep.csv")))
want = [("110", "180"), ("120", "200"), ("130", "220")]
got = [(r["pantographs[0].static_force"], r["simulation.speed_kmh"]) for r in rows]
assert got == want, got
for r, (force, speed) in zip(rows, want):
    assert r["status"] == "ok" and abs(float(r["speed_kmh"]) - float(speed)) < 1e-9, r
    for key in ("mean_N", "std_N", "stat_max_N", "max_N", "min_N", "uplift_mm"):
        assert r[key] != "", (key, r)
    mean = float(r["mean_N"])
    # no aerodynamic force in this scene: the mean contact force is the static force
    assert abs(mean - float(force)) < 0.05 * float(force), (force, mean)
    print("case %s: F0 %s N, %s km/h -> Fm %.2f N, sigma %s N" % (r["case"], force, speed, mean, r["std_N"]))
s = json.load(open(sys.argv[1] + "/summary.json"))
t = s["cases_table"]
assert t["columns"] == ["pantographs[0].static_force", "simulation.speed_kmh"] and t["rows"] == 3, t
assert t["lines"] == [3, 5, 6] and t["file"] == "cases.csv", t
assert s["sample"]["design"] == "lhs" and s["sample"]["seed"] == 4, s["sample"]
assert [c["values"]["simulation.speed_kmh"] for c in s["cases"]] == ["180", "200", "220"]
print("ok   sweep --cases: 3 cases, values and figures in sweep.csv, the table recorded")
PY
[ -s sw/sweep.png ] || fail "no sweep.png"
"$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/postproc/sensitivity.py" sw --bootstrap 50 > sens.log 2>&1 ||
  { cat sens.log; fail "sensitivity.py"; }
grep -q "binned (lhs)" sw/sensitivity.csv && [ -s sw/sensitivity.png ] && [ -s sw/scatter.png ] ||
  fail "sensitivity outputs: $(ls sw)"
echo "ok   sensitivity.py on it: sensitivity.csv/.md/.png, scatter.png"

# 2. Bad tables.
bad() {  # bad NAME "CSV TEXT" "EXPECTED WORDS" [more pcsim arguments]
  local name=$1 text=$2 words=$3; shift 3
  [ "$name" = missing ] || printf '%s\n' "$text" > "$name.csv"
  set +e
  "$PCSIM_BIN" sweep "$scene" --cases "$name.csv" -o "out-$name" "$@" > out.log 2> err.log
  local code=$?
  set -e
  [ "$code" -eq 2 ] || { cat out.log err.log; fail "$name: exit $code, not 2"; }
  [ "$(wc -l < err.log)" -eq 1 ] || fail "$name: not one line: $(cat err.log)"
  grep -qF "$name.csv" err.log && grep -qF -- "$words" err.log || fail "$name: message: $(cat err.log)"
  ! ls -d out-"$name"* > /dev/null 2>&1 || fail "$name: left $(ls -d out-"$name"*)"
  ! grep -q "\[1/" out.log || fail "$name: a case ran"
  echo "ok   $name: exit 2, $(cat err.log)"
}
header='pantographs[0].static_force,simulation.speed_kmh'
bad missing "" "cannot be read"
bad ragged "$header
110,180
120" "line 3 has 1 field(s), the header 2"
bad unknown "pantographs[0].static_forc,simulation.speed_kmh
110,180" "unknown key"
bad value "$header
110,180
abc,200" "line 3 (case 02): key 'pantographs[0].static_force': must be a number"
bad quote "$header
\"110,180" "a quote is not closed"
bad empty "$header" "no cases"
bad hole "$header
110," "line 2: no value"
bad twice "$header,simulation.speed_kmh
110,180,190" "the column is given twice"
bad swept "$header
110,180" "cannot sweep too" --set simulation.end_x=60,80

# 3. A command-line limit that one case refuses: -ts_max_time 1 s is within
#    the 180 km/h case's run (1.338 s) and past the 360 km/h one's (0.669 s):
#    exit 2 before any case, the message names that case.
printf '%s\n' "$header" "110,180" "110,360" > limit.csv
set +e
"$PCSIM_BIN" sweep "$scene" --cases limit.csv -o out-limit -ts_max_time 1 > out.log 2> err.log
code=$?
set -e
[ "$code" -eq 2 ] || { cat out.log err.log; fail "limit: exit $code, not 2"; }
[ "$(wc -l < err.log)" -eq 1 ] || fail "limit: not one line: $(cat err.log)"
grep -qF "command line: key '-ts_max_time': 1 s is past the scene's end: its run lasts 0.669 s" err.log &&
  grep -qF "(case 02)" err.log || fail "limit: message: $(cat err.log)"
! ls -d out-limit* > /dev/null 2>&1 || fail "limit: left $(ls -d out-limit*)"
! grep -q "\[1/" out.log || fail "limit: a case ran"
echo "ok   limit: exit 2, $(cat err.log)"
# An option bad in itself is no case's: its message names none.
set +e
"$PCSIM_BIN" sweep "$scene" --cases limit.csv -o out-limit -ts_max_time abc > out.log 2> err.log
code=$?
set -e
[ "$code" -eq 2 ] && [ "$(wc -l < err.log)" -eq 1 ] || { cat err.log; fail "limit abc: exit $code"; }
grep -qF "key '-ts_max_time': must be a number (got 'abc')" err.log && ! grep -qF "(case" err.log ||
  fail "limit abc: message: $(cat err.log)"
! ls -d out-limit* > /dev/null 2>&1 || fail "limit abc: left $(ls -d out-limit*)"
echo "ok   limit abc: exit 2, $(cat err.log)"
