"""How often the machine stops a thread that never yields (docs/benchmarks.md,
"What a modal run's slow steps are").

usage: /usr/bin/python3 runs/bench/stall_probe.py [SECONDS] [--cpu N] [--stall-every S --stall-ms T]

One thread reads the monotonic clock in a loop for SECONDS (10 by default),
pinned to CPU N if given. A gap between two reads longer than 0.1 ms is a
stall. For each stall, the thread's count of involuntary context switches
(getrusage) tells whether the kernel gave its CPU to another task. A stall
without such a switch is time the thread lost with no task taking its
place: an interrupt, or a virtual machine's processor held by its host. The
table gives the stalls per minute above each threshold, and how many of
them had no context switch. A modal step's 99.99th percentile is the
slowest step or two of its run. A stall that falls in a step adds its
length to that step: a run that steps for T seconds meets about T times
the stalls per second of them.

--stall-every S --stall-ms T makes a stall of T ms every S seconds (the
thread spins on another clock meanwhile): known stalls without a context
switch, for tests/output/test_stall_probe.sh.
"""
import argparse
import os
import resource
import time

THRESHOLDS_MS = (0.1, 0.2, 0.5, 1.0, 2.0, 5.0)


def involuntary_switches():
    return resource.getrusage(resource.RUSAGE_THREAD).ru_nivcsw


def probe(seconds, stall_every=0.0, stall_s=0.0):
    """[(gap ns, involuntary switch in it)] of the gaps above 0.1 ms, and the reads."""
    clock = time.perf_counter_ns
    gaps = []
    start = clock()
    end = start + int(seconds * 1e9)
    next_stall = start + int(stall_every * 1e9) if stall_every > 0 else end + 1
    reads = 0
    # The switch counts read after the last two clock reads: a gap between
    # two clock reads lies between the count before the first and the count
    # after the second (the getrusage call is inside the gap, not beside it).
    before = involuntary_switches()
    last = clock()
    after = involuntary_switches()
    while last < end:
        if last >= next_stall:  # a known stall: no read of this clock for stall_s
            until = time.monotonic() + stall_s
            while time.monotonic() < until:
                pass
            next_stall += int(stall_every * 1e9)
        now = clock()
        count = involuntary_switches()
        if now - last > 100_000:
            gaps.append((now - last, count != before))
        before, after = after, count
        last = now
        reads += 1
    return gaps, reads


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("seconds", nargs="?", type=float, default=10.0)
    parser.add_argument("--cpu", type=int, help="pin the thread to this CPU")
    parser.add_argument("--stall-every", type=float, default=0.0, help="seconds (tests)")
    parser.add_argument("--stall-ms", type=float, default=0.0, help="ms (tests)")
    args = parser.parse_args()
    if args.seconds <= 0:
        parser.error("SECONDS must be positive")
    if args.cpu is not None:
        os.sched_setaffinity(0, {args.cpu})
    load = os.getloadavg()[0]
    gaps, reads = probe(args.seconds, args.stall_every, args.stall_ms / 1e3)
    per_minute = 60.0 / args.seconds
    print(f"{args.seconds:g} s spinning, {reads} clock reads, load average {load:.2f} before")
    print("| stall above | stalls per minute | without a context switch, per minute |")
    print("|---|---:|---:|")
    for ms in THRESHOLDS_MS:
        above = [switched for gap, switched in gaps if gap > ms * 1e6]
        quiet = sum(1 for switched in above if not switched)
        print(f"| {ms:g} ms | {len(above) * per_minute:.1f} | {quiet * per_minute:.1f} |")
    unswitched = [gap for gap, switched in gaps if not switched]
    longest = max(gap for gap, _ in gaps) / 1e6 if gaps else 0.0
    print(f"longest stall {longest:.3f} ms, longest without a context switch "
          f"{(max(unswitched) / 1e6 if unswitched else 0.0):.3f} ms")


if __name__ == "__main__":
    main()
