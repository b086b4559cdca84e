#!/usr/bin/env bash
# Every hard case of runs/hard/ whole (or shortened, as CI runs them, with
# --short), its assertions checked (tests/hard/hard_cases.py), then the table
# and plots of docs/hard-cases.md regenerated from the results.
#   runs/hard/run_hard.sh [--short] [RESULTS_DIR]     (default out/hard)
# On 2 cores the whole cases take about 15 minutes, the short ones about 5.
set -euo pipefail
cd "$(dirname "$0")/../.."
full=--full
if [[ "${1:-}" == --short ]]; then full=; shift; fi
results=${1:-out/hard}
mkdir -p "$results"
failed=0
for case in $(/usr/bin/python3 tests/hard/hard_cases.py | sed 's/^cases: //'); do
  echo "== $case"
  if ! /usr/bin/python3 tests/hard/hard_cases.py "$case" $full --keep "$results" \
      > "$results/$case.log" 2>&1; then
    echo "   FAILED (see $results/$case.log)"
    failed=1
  fi
  grep -E "^  (ok|FAIL) " "$results/$case.log" | sed 's/^/   /'
done
/usr/bin/python3 postproc/hard_cases.py "$results" --plots docs/hard > "$results/table.md"
echo "table: $results/table.md (paste into docs/hard-cases.md); plots in docs/hard/"
exit $failed
