#!/bin/bash
# runs/bench/stall_probe.py counts a spinning thread's stalls and tells those
# without an involuntary context switch (docs/benchmarks.md, "What a modal
# run's slow steps are"). Known stalls: 1.5 ms without a read of the
# probe's clock every 0.1 s over 2 s (19 or 20 of them). Each must be
# counted above 1 ms and without an involuntary switch. The bound asks for
# 5 of them: on a busy machine (tests side by side) a preemption can fall
# in a known stall and make it a switched one; a probe that missed the
# stalls or counted them as switches gives 0.
set -euo pipefail
: "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
out=$("$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/runs/bench/stall_probe.py" 2 --stall-every 0.1 --stall-ms 1.5)
echo "$out"
row=$(echo "$out" | grep '^| 1 ms |')
quiet=$(echo "$row" | awk -F'|' '{gsub(/ /, "", $4); print $4}')
longest=$(echo "$out" | sed -n 's/.*longest without a context switch \([0-9.]*\) ms/\1/p')
# 5 stalls in 2 s are 150 a minute.
awk -v q="$quiet" -v l="$longest" 'BEGIN {
  if (q + 0 < 150) { print "stalls above 1 ms without a switch: " q " a minute, expected >= 150"; exit 1 }
  if (l + 0 < 1.5) { print "longest stall without a switch " l " ms, expected >= 1.5 (the known stalls)"; exit 1 }
}'
# Bad input: a negative duration is refused (argparse: one message, exit 2).
if "$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/runs/bench/stall_probe.py" -- -1 2>/dev/null; then
  echo "a negative duration was accepted"; exit 1
fi
echo "stall probe: ok"
