#!/bin/bash
# pcsim sweep's journal, resume and stop (docs/scene-format.md, "A sweep's
# journal, resume and stop"), on the short three-span scene (cases of ~1 s):
#  1. an uninterrupted sweep of four cases: journal.jsonl holds the header
#     and one line per case, the tables are made from it;
#  2. the same sweep SIGKILLed (the sweep, then its cases) once two cases are
#     in its journal: a rerun with another swept value is refused (exit 2, one
#     line, the journal untouched); the same command resumes it (only the
#     unfinished cases run) and gives sweep.csv and sweep.md equal to (1)'s;
#  3. SIGINT to a sweep: exit 130, no case process left, the journal
#     readable; --overwrite with another definition starts anew;
#  4. failed cases (solver options that starve the linear solve) are
#     journaled with their error, the sweep goes on, exit 3.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
fail() { echo "FAIL: $*"; exit 1; }
sweep=("$PCSIM_BIN" sweep "$scene" --set simulation.dt=0.0005 --no-report -j 1)
speeds=simulation.speed_kmh=180,190,200,210
lines() { cat "$1"/journal.jsonl 2> /dev/null | wc -l; }

# 1. Uninterrupted.
"${sweep[@]}" -o ref --set "$speeds" > ref.log 2>&1 || { cat ref.log; fail "the sweep failed"; }
[ "$(lines ref)" -eq 5 ] || fail "journal: $(cat ref/journal.jsonl)"
echo "ok   uninterrupted: journal of 4 cases, $(grep -c '^| 0' ref/sweep.md) table rows"

# 2. SIGKILL once two cases are in the journal, then resume.
"${sweep[@]}" -o k --set "$speeds" > k1.log 2>&1 &
pid=$!
for _ in $(seq 1 1200); do [ "$(lines k.partial)" -ge 3 ] && break; sleep 0.05; done
children=$(pgrep -P $pid || true)
kill -9 $pid
[ -z "$children" ] || kill -9 $children 2> /dev/null || true
wait $pid 2> /dev/null || true
finished=$(($(lines k.partial) - 1))
[ "$finished" -ge 2 ] && [ "$finished" -lt 4 ] || fail "$finished cases finished before the kill"
cp k.partial/journal.jsonl before.jsonl
set +e
"${sweep[@]}" -o k --set simulation.speed_kmh=180,190,200,220 > changed.log 2> changed.err
code=$?
set -e
[ $code -eq 2 ] && [ "$(wc -l < changed.err)" -eq 1 ] && grep -q "another definition" changed.err ||
  { cat changed.log changed.err; fail "a changed definition: exit $code"; }
cmp -s before.jsonl k.partial/journal.jsonl || fail "the refused rerun changed the journal"
echo "ok   changed definition refused: $(cat changed.err)"
"${sweep[@]}" -o k --set "$speeds" > k2.log 2>&1 || { cat k2.log; fail "the resumed sweep failed"; }
grep -qF "$finished case(s) finished (journal kept), $((4 - finished)) to run" k2.log ||
  fail "no resume line: $(cat k2.log)"
[ "$(grep -c '^  \[' k2.log)" -eq $((4 - finished)) ] || fail "cases rerun: $(cat k2.log)"
head -n $((finished + 1)) k/journal.jsonl | cmp -s - <(head -n $((finished + 1)) before.jsonl) ||
  fail "the finished cases' journal lines changed"
cmp ref/sweep.csv k/sweep.csv && cmp ref/sweep.md k/sweep.md || fail "tables differ"
echo "ok   SIGKILL after $finished cases, resumed: $((4 - finished)) rerun, tables equal"

# 3. SIGINT while cases run (job control: a background job keeps SIGINT).
set -m
"${sweep[@]}" -o s --set "$speeds" -j 2 > s.log 2>&1 &
pid=$!
set +m
for _ in $(seq 1 1200); do
  cases=$(pgrep -P $pid -f " run " || true)
  [ "$(echo $cases | wc -w)" -ge 2 ] && break
  sleep 0.05
done
kill -INT $pid
set +e
wait $pid
code=$?
set -e
[ $code -eq 130 ] || { cat s.log; fail "sweep after SIGINT: exit $code"; }
[ -n "$cases" ] || fail "no running case seen"
for c in $cases; do ! kill -0 "$c" 2> /dev/null || fail "case process $c left running"; done
"$PCSIM_PYTHON" -c "
import json, sys
[json.loads(l) for l in open('s.partial/journal.jsonl')]" || fail "journal after SIGINT"
"${sweep[@]}" -o s --set simulation.speed_kmh=180,200 --overwrite > s2.log 2>&1 ||
  { cat s2.log; fail "--overwrite"; }
! grep -q "resumed" s2.log && [ "$(lines s)" -eq 3 ] || fail "--overwrite: $(cat s2.log)"
echo "ok   SIGINT: 130, no case left running; --overwrite starts anew"

# 4. Failed cases.
set +e
"${sweep[@]}" -o f --set simulation.speed_kmh=180,200 -ksp_type cg -pc_type none -ksp_max_it 2 \
  > f.log 2>&1
code=$?
set -e
[ $code -eq 3 ] || { cat f.log; fail "failed cases: exit $code"; }
"$PCSIM_PYTHON" - <<'PY' || fail "failed cases in the journal"
import csv, json
entries = [json.loads(l) for l in open("f/journal.jsonl")][1:]
assert [e["status"] for e in entries] == [3, 3], entries
assert all("did not converge" in e["error"] and e["summary"] is None for e in entries), entries
rows = list(csv.DictReader(open("f/sweep.csv")))
assert [r["status"] for r in rows] == ["failed (exit 3)"] * 2, rows
PY
echo "ok   failed cases journaled with their error, the sweep went on, exit 3"
