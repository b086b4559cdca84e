"""Each CPU's speed over time, for reading step times (docs/benchmarks.md,
"The machine's two CPUs at different speeds").

usage: /usr/bin/python3 runs/bench/cpu_speeds.py [ROUNDS] [PAUSE_S]

For ROUNDS rounds (10 by default), PAUSE_S seconds apart (2 by default),
the same fixed loop of integer arithmetic is timed on each CPU this
process may run on, pinned to it in turn: its mean time over a quarter of
a second. A virtual machine's CPUs are
threads of its host: where a host's core is shared, one CPU runs the loop
slower than another at the same moment, and which one changes with time.
The table gives each round's loop time per CPU and the ratio of the
slowest to the fastest; a summary line gives the ratio's median and range.
A run's step times (summary.json step_time.by_cpu, the console's `steps by
CPU`) compare only on CPUs of the same speed.
"""

import argparse
import os
import statistics
import sys
import time


def loop_seconds():
    start = time.perf_counter()
    total = 0
    for i in range(300000):
        total += i * i
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description="each CPU's speed over time")
    parser.add_argument("rounds", nargs="?", type=int, default=10)
    parser.add_argument("pause", nargs="?", type=float, default=2.0, metavar="PAUSE_S")
    args = parser.parse_args()
    if args.rounds < 1 or args.pause < 0:
        parser.error("ROUNDS must be at least 1 and PAUSE_S not negative")
    rounds, pause = args.rounds, args.pause
    cpus = sorted(os.sched_getaffinity(0))
    print("| round | s | " + " | ".join("CPU %d ms" % c for c in cpus) + " | slowest / fastest |")
    print("|---:|---:|" + "---:|" * len(cpus) + "---:|")
    ratios = []
    start = time.time()
    try:
        for r in range(rounds):
            times = []
            for c in cpus:
                os.sched_setaffinity(0, {c})
                loop_seconds()  # the CPU's caches and clock settled
                # The mean over 0.25 s: a host that takes the CPU away for
                # some milliseconds at a time slows a run on average, which
                # the fastest of a few short loops would not show.
                samples, begin = [], time.perf_counter()
                while time.perf_counter() - begin < 0.25:
                    samples.append(loop_seconds())
                times.append(statistics.mean(samples))
            ratios.append(max(times) / min(times))
            print("| %d | %.1f | %s | %.2f |" % (r + 1, time.time() - start,
                                                 " | ".join("%.2f" % (1e3 * t) for t in times),
                                                 ratios[-1]))
            sys.stdout.flush()
            if r + 1 < rounds:
                time.sleep(pause)
    finally:
        os.sched_setaffinity(0, set(cpus))
    print("slowest / fastest CPU: median %.2f, %.2f to %.2f over %d rounds"
          % (statistics.median(ratios), min(ratios), max(ratios), rounds))


if __name__ == "__main__":
    main()
