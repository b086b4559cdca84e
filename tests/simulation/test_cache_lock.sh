#!/bin/bash
# Two processes that start on the same uncached modal design (two sweep
# groups, two users' runs) compute its modes once (output::CacheLock): the
# first takes the cache entry's lock and computes, the second waits, says so,
# and reads the first one's file; their results are equal bit for bit (the
# cache keeps the doubles as computed).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
first=
trap '[ -z "$first" ] || kill "$first" 2> /dev/null || true; rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }
# 4 spans, modes below 30 Hz: a few seconds of SLEPc, long enough for the
# second process (its statics take ~0.2 s) to arrive while the first computes.
run=("$PCSIM_BIN" run "$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml"
  --set catenary.model=modal --set catenary.design.spans.count=4
  --set catenary.max_frequency_hz=30 --cache cache --no-report -pcsim_accuracy_pilot false)

"${run[@]}" -o first > first.log 2>&1 &
first=$!
for _ in $(seq 600); do
  grep -q "computing the catenary's modes" first.log && break
  kill -0 "$first" 2> /dev/null || { cat first.log; fail "the first run ended early"; }
  sleep 0.1
done
grep -q "computing the catenary's modes" first.log || { cat first.log; fail "no mode computation"; }
"${run[@]}" -o second > second.log 2>&1 || { cat second.log; fail "second run"; }
wait "$first" || { cat first.log; fail "first run"; }
first=

grep -q "waiting for another process computing the same modes" second.log ||
  { cat first.log second.log; fail "the second run did not wait for the first"; }
! grep -q "computing the catenary's modes" second.log ||
  { cat second.log; fail "the second run computed the modes too"; }
"$PCSIM_PYTHON" - <<'PY'
import json
first, second = (json.load(open(f"{n}/summary.json")) for n in ("first", "second"))
assert first["modal"]["cache_hit"] is False, first["modal"]
assert second["modal"]["cache_hit"] is True, second["modal"]
PY
"$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/tests/contact/compare_runs.py" first second 0 > compare.log ||
  { cat compare.log; fail "the two runs differ"; }
echo "cache lock: the modes computed once, the second run waited and read them"
