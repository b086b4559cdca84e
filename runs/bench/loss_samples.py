"""The samples behind a loss-of-contact difference between two runs of one
scene (docs/fidelity.md, "More run scenes at their defaults"): per
pantograph, over the analysis section (summary.json), the samples of the
unfiltered contact force at zero in each run, those where only one run is at
zero with both runs' forces there, the RMS and largest difference of the
force, and the mean difference on the last two samples before each loss of
the reference (the other run minus the reference).
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
        x, force = group["position"][()], group["contact_force"][()]
    inside = (x >= lo) & (x < hi)
    return x[inside], force[inside]


def main():
    reference, other = sys.argv[1], sys.argv[2]
    lo, hi = section(reference)
    with h5py.File(os.path.join(reference, "results.h5"), "r") as f:
        names = list(f["pantographs"])
    for name in names:
        x, f_ref = forces(reference, name, lo, hi)
        x_other, f_other = forces(other, name, lo, hi)
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
        for i in np.flatnonzero(zero_ref != zero_other):
            print(f"  x = {x[i]:.3f} m: reference {f_ref[i]:.2f} N, other {f_other[i]:.2f} N")


if __name__ == "__main__":
    main()
