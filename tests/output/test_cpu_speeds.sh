#!/bin/bash
# runs/bench/cpu_speeds.py times one loop on each CPU the process may use
# (docs/benchmarks.md, "The machine's two CPUs at different speeds"). The
# speeds are the machine's, so the checks are the table's own: a column per
# CPU of the affinity, each round's ratio the slowest time over the fastest
# (to the table's two decimals), exactly 1.00 on one CPU, and bad input
# refused (argparse: one message, exit 2).
set -euo pipefail
: "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
probe="$PCSIM_SOURCE_DIR/runs/bench/cpu_speeds.py"
check() {  # $1: the probe's output, $2: the CPUs expected
  echo "$1"
  echo "$1" | awk -F'|' -v cpus="$2" '
    /^\| round/ { columns = NF - 5; if (columns != cpus) { print "CPU columns " columns ", expected " cpus; exit 1 } }
    /^\| [0-9]+ \|/ {
      rows++; lo = 1e30; hi = 0
      for (i = 4; i < NF - 1; i++) { t = $i + 0; if (t <= 0) { print "no time in: " $0; exit 1 }
                                     if (t < lo) lo = t; if (t > hi) hi = t }
      r = $(NF - 1) + 0
      # the times are rounded to 0.01 ms (loops of ~8 ms): their ratio to ~0.003
      if (r < 1 || (r - hi / lo) > 0.01 || (hi / lo - r) > 0.01) { print "ratio " r " against " hi / lo; exit 1 }
    }
    END { if (rows != 2) { print "rounds " rows ", expected 2"; exit 1 } }'
  echo "$1" | grep -q "^slowest / fastest CPU: median [0-9.]*, [0-9.]* to [0-9.]* over 2 rounds$"
}
check "$(taskset -c 0 "$PCSIM_PYTHON" "$probe" 2 0)" 1
one=$(taskset -c 0 "$PCSIM_PYTHON" "$probe" 2 0 | tail -1)
[[ "$one" == "slowest / fastest CPU: median 1.00, 1.00 to 1.00 over 2 rounds" ]] || { echo "one CPU: $one"; exit 1; }
check "$("$PCSIM_PYTHON" "$probe" 2 0)" "$(nproc)"
for bad in "0" "2 -1" "x"; do
  rc=0
  # shellcheck disable=SC2086  # the words of a case are its arguments
  "$PCSIM_PYTHON" "$probe" $bad > /dev/null 2>&1 || rc=$?
  [[ $rc == 2 ]] || { echo "arguments '$bad': exit $rc, expected 2"; exit 1; }
done
echo "cpu speeds: ok"
