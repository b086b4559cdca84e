#!/usr/bin/python3
"""Energy balance of a pantograph time run (thesis 2.3.1, eqs 2.30-2.34).

usage: pantograph_energy.py OUTDIR -o PNG [--scheme rk4]
Top: T+V relative to t=0, work of the damper and of the external forces.
Bottom: balance [T+V]_t - [T+V]_0 - W_damper - W_ext, and its ratio to the range of T+V.
"""
import argparse
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import pcsim_post


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir", metavar="OUTDIR", help="pcsim pantograph result folder of a time study")
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--scheme", default="rk4", help="group of time.h5 to plot (rk4, hht, ...; rk4)")
    args = ap.parse_args()
    pcsim_post.need_run_folder(args.outdir, ("time.h5",), "pcsim pantograph (study: time)")
    with h5py.File(os.path.join(args.outdir, "time.h5"), "r") as f:
        if args.scheme not in f:
            pcsim_post.fail("--scheme %s: not in time.h5 (it has: %s)" % (args.scheme, ", ".join(f)))
        g = f[args.scheme]["energy"]
        t = f[args.scheme]["t"][:]
        T, V = g["kinetic"][:], g["potential"][:]
        Wd, We, B = g["work_dissipative"][:], g["work_external"][:], g["balance"][:]
    E = T + V
    rng = E.max() - E.min()
    fig, ax = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ax[0].plot(t, E - E[0], label="[T+V]_t - [T+V]_0")
    ax[0].plot(t, Wd, label="W_damper")
    ax[0].plot(t, We, label="W_ext (bellows torque, contact force)")
    ax[0].set_ylabel("J")
    ax[0].legend(fontsize=8)
    ax[0].grid(True)
    ax[1].plot(t, B, "k")
    ax[1].set_ylabel("balance (J)")
    ax[1].set_xlabel("t (s)")
    ax[1].grid(True)
    ax[1].set_title(f"max |balance| / range(T+V) = {np.abs(B).max() / rng:.2e}")
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(args.output, "max|balance| =", np.abs(B).max(), "J, range =", rng, "J")


if __name__ == "__main__":
    pcsim_post.main(main)
