"""Compares the time series of two `pcsim run` results (results.h5), for the
restart tests (test_run_restart*.sh).

  compare_runs.py A B TOL

Every per-step dataset (time, each pantograph's position, contact force,
wire height and coordinates, the uplift at the supports, the dropper forces)
must have the same shape in both, and differ by at most TOL relative to the
largest magnitude of that dataset in A. Prints the largest differences; exit
0 when all hold.
"""
import sys

import h5py
import numpy as np


def series(h5):
    names = ["/time", "/supports/uplift"]
    if "/droppers/force" in h5:
        names.append("/droppers/force")
    for p in h5["/pantographs"]:
        names += [f"/pantographs/{p}/{s}" for s in ("position", "contact_force", "wire_height", "q")]
    return names


def main():
    a_dir, b_dir, tol = sys.argv[1], sys.argv[2], float(sys.argv[3])
    failures = []
    with h5py.File(f"{a_dir}/results.h5", "r") as a, h5py.File(f"{b_dir}/results.h5", "r") as b:
        for name in series(a):
            x, y = a[name][()], b[name][()]
            if x.shape != y.shape:
                failures.append(f"{name}: shapes {x.shape} and {y.shape}")
                continue
            scale = np.max(np.abs(x)) or 1.0
            rel = np.max(np.abs(x - y)) / scale if x.size else 0.0
            print(f"  {name}: {x.shape}, largest difference {rel:.2e} relative")
            if not rel <= tol:
                failures.append(f"{name}: differs by {rel:.2e} relative (tolerance {tol:.0e})")
    if failures:
        sys.exit(f"{a_dir} and {b_dir} differ:\n  " + "\n  ".join(failures))


if __name__ == "__main__":
    main()
