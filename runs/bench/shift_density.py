"""How much of a moving window's shift matrix P could a sparse P skip
(docs/benchmarks.md, "The window's shift in single precision"): for each
threshold tau, the share of P's entries above tau times their row's 2-norm,
and the largest sum of the magnitudes left out, relative to its row's norm.
  /usr/bin/python3 runs/bench/shift_density.py CACHE/basis-HASH.h5
(a basis file of pcsim's cache folder, `--cache`, of a modal window run;
its `shift` dataset is P)."""
import sys

import h5py
import numpy as np

THRESHOLDS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)


def main(path):
    with h5py.File(path, "r") as f:
        if "shift" not in f:
            sys.exit(f"{path}: no 'shift' dataset (not a moving window's basis)")
        P = np.abs(f["shift"][...].astype(np.float64))
    norms = np.sqrt((P**2).sum(axis=1))
    norms[norms == 0] = 1.0
    print(f"P: {P.shape[0]} x {P.shape[1]}, row norms {norms.min():.2f} to {norms.max():.2f}")
    print("| tau | entries kept | largest sum left out / row norm |")
    print("|---|---:|---:|")
    for tau in THRESHOLDS:
        keep = P > tau * norms[:, None]
        left_out = np.where(keep, 0.0, P).sum(axis=1) / norms
        print(f"| {tau:g} | {100 * keep.mean():.1f} % | {left_out.max():.2e} |")
    nonzero = P > 0
    first = nonzero.argmax(axis=1)
    last = P.shape[1] - 1 - nonzero[:, ::-1].argmax(axis=1)
    print(f"columns from a row's first nonzero to its last: median {np.median(last - first + 1):.0f}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
