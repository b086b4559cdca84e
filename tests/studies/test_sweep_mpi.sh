#!/bin/bash
# pcsim sweep under mpirun (docs/cluster.md), on the short three-span scene
# (cases of ~0.5 s); a case table of four cases, one of which (contact
# stiffness 1e12 N/m with -ts_hht_max_reject 0) fails at its second step:
#  1. the same sweep (a) without mpirun, (b) `mpirun -n 2` (two groups of one
#     rank), (c) `mpirun -n 2 ... -sweep_ranks_per_case 2` (one group of two):
#     exit 3 (the failed case), the failure journaled with its error, the
#     other cases finished; the tables' figures equal;
#  2. sweep.h5 opens with h5py: one dataset per column, each with its unit;
#  3. -sweep_ranks_per_case 3 on 2 ranks: exit 2, one message naming the
#     option, nothing written; a case that fails on one rank of its group
#     alone ends the job within a time limit (no hang);
#  4. SIGTERM to the ranks while cases run: exit 143, the group journals
#     merged into journal.jsonl; SIGKILL (no chance to merge): the group
#     journals kept; each time the same command resumes the sweep and its
#     tables equal those of the sweep run without mpirun; SIGTERM to mpirun
#     (which forwards it), resumed without mpirun;
#  5. a modal sweep of four cases on one design without mpirun, cache folder
#     empty: it says up front that it needs one basis, to compute; then under
#     `mpirun -n 2` (one basis, served by the cache): a group's cases after
#     its first take the static configuration and the basis the first kept
#     in memory; the tables equal byte for byte. (Not from an empty cache
#     under mpirun: both groups would compute the basis at once and the later
#     rename makes the other's kept basis another file's: read again.)
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
mpirun=$PCSIM_SOURCE_DIR/scripts/mpirun.sh
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
fail() { echo "FAIL: $*"; exit 1; }
cat > cases.csv <<'CSV'
simulation.speed_kmh,contact.stiffness
180,50000
190,50000
200,1e12
210,50000
CSV
sweep=(sweep "$scene" --set simulation.dt=0.0005 --cases cases.csv --no-report
  -ts_hht_max_reject 0)
expect() {  # expect STATUS NAME COMMAND...: runs it, its output in NAME.log
  local status=$1 name=$2 code=0
  shift 2
  "$@" > "$name.log" 2>&1 || code=$?
  [ $code -eq "$status" ] || { cat "$name.log"; fail "$name: exit $code, not $status"; }
}

# 1. Local, two groups of one rank, one group of two ranks.
expect 3 local "$PCSIM_BIN" "${sweep[@]}" -o local -j 2
expect 3 groups "$mpirun" -n 2 "$PCSIM_BIN" "${sweep[@]}" -o groups
expect 3 pair "$mpirun" -n 2 "$PCSIM_BIN" "${sweep[@]}" -o pair -sweep_ranks_per_case 2
grep -q "2 group(s) of 1 rank(s)" groups.log && grep -q "1 group(s) of 2 rank(s)" pair.log ||
  fail "no MPI mode: $(head -3 groups.log pair.log)"
[ ! -e groups/journal-0.jsonl ] && [ ! -e pair/journal-0.jsonl ] || fail "group journals left"
# Figures compared at full precision (the journals' summaries). One rank per
# case computes what `pcsim run` computes on one rank: bit-equal. A case on
# two ranks sums in another order and solves with the domain decomposition
# (tests/contact/test_run_ranks.sh): round-off amplified by the dynamics,
# measured 1.4e-10 to 2e-10 relative here (three runs); the tolerance is 1e-9. sweep.csv
# (6 significant digits) is equal for one rank per case; with two ranks a
# value may round the other way: equal to 1e-5.
"$PCSIM_PYTHON" - <<'PY' || fail "the three sweeps differ"
import csv, json
def journal(d):
    entries = [json.loads(l) for l in open(f"{d}/journal.jsonl")]
    assert entries[0]["cases"] == 4, entries[0]
    return {e["case"]: e for e in entries[1:]}
def figures(e):
    return {(p["name"], k): v for p in e["summary"]["pantographs"] for k, v in p.items()
            if isinstance(v, float)}
ref = journal("local")
assert sorted(e["status"] for e in ref.values()) == [0, 0, 0, 3], ref
def cells(d):
    return [[float(c) if c.replace(".", "").replace("e-", "").isdigit() else c for c in row]
            for row in csv.reader(open(f"{d}/sweep.csv"))]
def close(a, b, tolerance):
    if isinstance(a, float) and isinstance(b, float):
        return abs(a - b) <= tolerance * max(abs(a), abs(b))
    return a == b
for d, tolerance in (("groups", 0.0), ("pair", 1e-9)):
    got = journal(d)
    assert got.keys() == ref.keys(), (d, got.keys())
    worst = 0.0
    for name, e in ref.items():
        g = got[name]
        assert g["status"] == e["status"], (d, name, g["status"])
        if e["status"] != 0:
            assert "did not converge" in g["error"] and g["summary"] is None, (d, g)
            continue
        a, b = figures(e), figures(g)
        assert a.keys() == b.keys() and a, (d, name)
        for k in a:
            worst = max(worst, abs(a[k] - b[k]) / max(abs(a[k]), 1e-300))
    assert worst <= tolerance, (d, worst)
    print(f"     {d}: largest relative difference of the figures {worst:.2g}")
    csv_tolerance = 0.0 if tolerance == 0 else 1e-5
    a, b = cells("local"), cells(d)
    assert len(a) == len(b) and all(len(r) == len(s) for r, s in zip(a, b)), d
    assert all(close(x, y, csv_tolerance) for r, s in zip(a, b) for x, y in zip(r, s)), d
PY
cmp local/sweep.md groups/sweep.md || fail "sweep.md of two groups differs"
grep -q "did not converge" groups/cases/03.log || fail "no error in the case's log"
echo "ok   local, 2 groups x 1 rank, 1 group x 2 ranks: equal tables, the failed case journaled"

# 2. The HDF5 table.
"$PCSIM_PYTHON" - <<'PY' || fail "sweep.h5"
import csv, math
import h5py
rows = list(csv.DictReader(open("groups/sweep.csv")))
with h5py.File("groups/sweep.h5", "r") as f:
    def walk(name, obj):
        if isinstance(obj, h5py.Dataset):
            assert "unit" in obj.attrs and "description" in obj.attrs, name
            assert len(obj) == len(rows), name
    f.visititems(walk)
    text = lambda name: [v.decode() for v in f[name][:]]
    assert text("case") == [r["case"] for r in rows]
    assert text("status") == [r["status"] for r in rows], text("status")
    assert text("values/contact.stiffness") == [r["contact.stiffness"] for r in rows]
    assert f["figures/std_N"].attrs["unit"] == "N" and f["speed_kmh"].attrs["unit"] == "km/h"
    failed = [i for i, r in enumerate(rows) if r["status"] != "ok"]
    assert failed == [2] and f["exit_status"][2] == 3 and "did not converge" in text("error")[2]
    for i, r in enumerate(rows):
        v = f["figures/std_N"][i]
        assert math.isnan(v) if i in failed else abs(v - float(r["std_N"])) <= 5e-6 * abs(v), i
PY
echo "ok   sweep.h5: one dataset per column with its unit, the same values as sweep.csv"

# 3. A group size that does not divide the ranks.
expect 2 bad "$mpirun" -n 2 "$PCSIM_BIN" "${sweep[@]}" -o bad -sweep_ranks_per_case 3
[ "$(grep -c "pcsim: error" bad.log)" -eq 1 ] && grep -q "'-sweep_ranks_per_case'" bad.log ||
  { cat bad.log; fail "not one message naming the option"; }
[ -z "$(ls -d bad* 2> /dev/null | grep -v bad.log)" ] || fail "left behind: $(ls -d bad*)"
echo "ok   -sweep_ranks_per_case 3 on 2 ranks: $(grep "pcsim: error" bad.log)"

# 3b. A case that fails on one rank of its group alone
# (-pcsim_debug_case_fail_rank 1: before the case starts) while the other
# rank runs it and waits in its collectives: the failed rank ends the job
# after 10 s with its message, no hang (the time limit turns one into a
# failure). Until 2026-12-06 the failed rank went on to the case's agreement
# while the other was in the case's collectives: a mismatched collective, and
# the job ended by MPI_Abort with errorcode 59 and no message.
code=0
timeout 120 "$mpirun" -n 2 "$PCSIM_BIN" "${sweep[@]}" -o alone -sweep_ranks_per_case 2 \
  -pcsim_debug_case_fail_rank 1 > alone.log 2>&1 || code=$?
[ $code -ne 124 ] || { cat alone.log; fail "a case failed on one rank: the sweep hung"; }
[ $code -ne 0 ] || { cat alone.log; fail "a case failed on one rank: exit 0"; }
grep -q "debug failure of a case on group rank 1" alone.log &&
  grep -q "other ranks did not stop within 10 s; ending the job" alone.log ||
  { cat alone.log; fail "a case failed on one rank: no message"; }
echo "ok   a case failed on one rank of its group: the job ended (exit $code), no hang"

# 4. Stopped (SIGTERM to the ranks, as SLURM does at a time limit) and
# killed (SIGKILL), then resumed; twelve cases of ~1 s (with six, mpirun's
# forwarded SIGTERM came after the last case in 4 of 6 runs of 2026-12-01:
# the sweep had ended, nothing to stop).
cases=12
grid=(sweep "$scene" --set simulation.dt=0.0001 --set simulation.speed_kmh=180:290:10 --no-report)
expect 0 ref "$PCSIM_BIN" "${grid[@]}" -o ref -j 2
journaled() { cat "$1".partial/journal*.jsonl 2> /dev/null | grep -c '"case"' || true; }
stop_when_two_done() {  # stop_when_two_done SIGNAL FOLDER [mpirun]: the ranks (or mpirun) get it
  "$mpirun" -n 2 "$PCSIM_BIN" "${grid[@]}" -o "$2" > "$2-1.log" 2>&1 &
  local pid=$!
  for _ in $(seq 1 1200); do [ "$(journaled "$2")" -ge 2 ] && break; sleep 0.05; done
  kill -"$1" $([ "${3:-}" = mpirun ] && echo $pid || pgrep -P $pid) 2> /dev/null || true
  [ "$1" = KILL ] && kill -KILL $pid 2> /dev/null || true
  wait $pid 2> /dev/null || true
}
stop_when_two_done TERM term
grep -q "interrupted (SIGTERM)" term-1.log || { cat term-1.log; fail "no stop after SIGTERM"; }
[ -z "$(ls term.partial/journal-*.jsonl 2> /dev/null)" ] || fail "group journals not merged"
stop_when_two_done KILL killed
[ -n "$(ls killed.partial/journal-*.jsonl 2> /dev/null)" ] || fail "no group journal after SIGKILL"
stop_when_two_done TERM forwarded mpirun
grep -q "interrupted (SIGTERM)" forwarded-1.log || { cat forwarded-1.log; fail "mpirun's SIGTERM"; }
for d in term killed forwarded; do
  done_before=$(journaled $d)
  [ "$done_before" -ge 2 ] && [ "$done_before" -lt $cases ] || fail "$d: $done_before cases before"
  if [ $d = forwarded ]; then
    expect 0 $d-2 "$PCSIM_BIN" "${grid[@]}" -o $d -j 2
  else
    expect 0 $d-2 "$mpirun" -n 2 "$PCSIM_BIN" "${grid[@]}" -o $d
  fi
  grep -qF "$done_before case(s) finished (journal kept), $((cases - done_before)) to run" $d-2.log ||
    { cat $d-2.log; fail "$d: no resume line"; }
  [ "$(grep -c '^  \[' $d-2.log)" -eq $((cases - done_before)) ] || fail "$d: cases rerun"
  cmp ref/sweep.csv $d/sweep.csv && cmp ref/sweep.md $d/sweep.md || fail "$d: tables differ"
  echo "ok   $d after $done_before of $cases cases, resumed: $((cases - done_before)) run, tables equal"
done

# 5. Bases kept in memory by the groups.
cat > modal.yaml <<YAML
base: $scene
name: modal
set: {catenary.model: modal, catenary.max_frequency_hz: 120}
YAML
modal=(sweep modal.yaml --set "pantographs[0].static_force=100,110,120,130" --no-report
  --cache modal-cache)
expect 0 modal-local "$PCSIM_BIN" "${modal[@]}" -o modal-local -j 2
grep -qF "modal bases: 4 case(s) on 1 catenary design(s): 0 served by the cache folder, 1 to compute" modal-local.log ||
  { cat modal-local.log; fail "modal: no line on the bases"; }
expect 0 modal-mpi "$mpirun" -n 2 "$PCSIM_BIN" "${modal[@]}" -o modal-mpi
grep -qF "1 served by the cache folder, 0 to compute" modal-mpi.log || fail "modal: cache"
"$PCSIM_PYTHON" - <<'PY' || fail "modal: kept"
import json
kept = {}
for d in ("modal-mpi", "modal-local"):
    for line in open(f"{d}/journal.jsonl"):
        j = json.loads(line)
        if "case" in j:
            s = j["summary"]
            kept.setdefault(d, []).append(s["modal"]["basis_kept_in_memory"] and s["statics_kept_in_memory"])
# the first case of each group (a group may run one case, another three)
assert kept["modal-mpi"].count(False) == 2, kept
assert not any(kept["modal-local"]), kept  # a process per case
PY
cmp modal-mpi/sweep.csv modal-local/sweep.csv || fail "modal: tables differ"
echo "ok   modal sweep: one basis to compute, kept by each group for its second case; tables equal"
