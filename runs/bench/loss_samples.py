"""The samples behind a loss-of-contact difference between two runs of one
scene (docs/fidelity.md, "More run scenes at their defaults" and "What is
left in the loss of contact"): per
pantograph, over the analysis section (summary.json), the samples of the
unfiltered contact force at zero in each run, those where only one run is at
zero with both runs' forces there, the RMS and largest difference of the
force, and the mean difference on the last two samples before each loss of
the reference (the other run minus the reference); and, over the
interruptions the two runs share (overlapping in time), the mean shift of
their starts and ends and of their durations, each instant placed between
samples by extending the force's line through the two samples in contact
next to it down to zero (the penalty force is linear in the penetration,
which changes smoothly), so that shifts finer than a time step show.
  /usr/bin/python3 runs/bench/loss_samples.py REFERENCE_RUN OTHER_RUN
(result folders of pcsim run, e.g. OUT/SCENE/linear and OUT/SCENE/modal of
runs/bench_fast_level.sh)."""
import json
import os
import sys

import h5py
import numpy as np


def section(run):
    with open(os.path.join(run, "summary.json")) as f:
        analysis = json.load(f)["analysis"]
    return analysis["from_x"], analysis["to_x"]


def forces(run, name, lo, hi):
    with h5py.File(os.path.join(run, "results.h5"), "r") as f:
        group = f[f"pantographs/{name}"]
        x, force, t = group["position"][()], group["contact_force"][()], f["time"][()]
    inside = (x >= lo) & (x < hi)
    return x[inside], force[inside], t[inside]


def crossing(t, force, i, j):
    """The instant the force's line through samples i (next to the gap) and
    j (one further from it) reaches zero, kept between sample i and its
    neighbour in the gap; the midpoint when the line does not fall towards
    the gap."""
    gap_side = 2 * i - j
    slope = (force[i] - force[j]) / (t[i] - t[j])
    towards_gap = slope * (t[gap_side] - t[i]) < 0
    if not towards_gap:
        return 0.5 * (t[i] + t[gap_side])
    instant = t[i] - force[i] / slope
    return min(max(instant, min(t[i], t[gap_side])), max(t[i], t[gap_side]))


def interruptions(t, force):
    """(start, end) instants of each loss of contact with two samples in
    contact on either side."""
    zero = force <= 0
    found = []
    k = 2
    while k < len(force) - 2:
        if zero[k] and not zero[k - 1]:
            last = k
            while last + 1 < len(force) and zero[last + 1]:
                last += 1
            if not zero[k - 2] and last + 2 < len(force) and not zero[last + 2]:
                found.append((crossing(t, force, k - 1, k - 2),
                              crossing(t, force, last + 1, last + 2)))
            k = last + 1
        k += 1
    return found


def shared_shifts(t, f_ref, f_other):
    """Mean shifts [ms] of start, end and duration over the interruptions
    that overlap one of the other run's, and their count."""
    ref, other = interruptions(t, f_ref), interruptions(t, f_other)
    starts, ends = [], []
    for a0, a1 in ref:
        match = [(b0, b1) for b0, b1 in other if b0 < a1 and b1 > a0]
        if len(match) == 1:
            starts.append(match[0][0] - a0)
            ends.append(match[0][1] - a1)
    if not starts:
        return None
    starts, ends = 1e3 * np.array(starts), 1e3 * np.array(ends)
    return len(ref), len(other), len(starts), starts.mean(), ends.mean(), (ends - starts).mean()


def main():
    reference, other = sys.argv[1], sys.argv[2]
    lo, hi = section(reference)
    with h5py.File(os.path.join(reference, "results.h5"), "r") as f:
        names = list(f["pantographs"])
    for name in names:
        x, f_ref, t = forces(reference, name, lo, hi)
        x_other, f_other, _ = forces(other, name, lo, hi)
        if len(x) != len(x_other) or not np.array_equal(x, x_other):
            sys.exit(f"{name}: the runs' samples differ in position")
        zero_ref, zero_other = f_ref <= 0, f_other <= 0
        diff = f_other - f_ref
        print(f"{name}: x {lo:g}-{hi:g} m, {len(x)} samples; at zero: {zero_ref.sum()} "
              f"(reference), {zero_other.sum()} (other); force difference RMS "
              f"{np.sqrt(np.mean(diff ** 2)):.2f} N, largest {np.abs(diff).max():.2f} N")
        # The last sample in contact before each loss (the one before it too).
        before = np.flatnonzero(~zero_ref[:-1] & zero_ref[1:])
        before = before[before >= 1]
        if len(before):
            print(f"  before the reference's {len(before)} losses: other minus reference "
                  f"{diff[before].mean():+.2f} N on the last sample, "
                  f"{diff[before - 1].mean():+.2f} N on the one before")
        shifts = shared_shifts(t, f_ref, f_other)
        if shifts:
            print("  interruptions: %d (reference), %d (other), %d shared; other minus "
                  "reference, mean: start %+.3f ms, end %+.3f ms, duration %+.3f ms" % shifts)
        for i in np.flatnonzero(zero_ref != zero_other):
            print(f"  x = {x[i]:.3f} m: reference {f_ref[i]:.2f} N, other {f_other[i]:.2f} N")


if __name__ == "__main__":
    main()
