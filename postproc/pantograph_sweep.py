#!/usr/bin/python3
"""Nonlinear "FRF" from harmonic sweeps (peak-to-peak / 2A in steady state), thesis 2.3.3.

usage: pantograph_sweep.py OUTDIR [OUTDIR2 ...] -o PNG [--frf FRF_OUTDIR]
"""
import argparse
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np  # noqa: F401

import pcsim_post


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdirs", nargs="+", metavar="OUTDIR",
                    help="pcsim pantograph result folder(s) of sweep studies")
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--frf", default=None, metavar="FRF_OUTDIR",
                    help="frf study folder to overlay |H33|")
    args = ap.parse_args()
    for d in args.outdirs:
        pcsim_post.need_run_folder(d, ("sweep.h5",), "pcsim pantograph (study: sweep)")
    if args.frf:
        pcsim_post.need_run_folder(args.frf, ("frf.h5",), "pcsim pantograph (study: frf)")
    fig, axes = plt.subplots(len(args.outdirs), 1, figsize=(8, 4 * len(args.outdirs)), squeeze=False)
    for ax, d in zip(axes[:, 0], args.outdirs):
        with h5py.File(os.path.join(d, "sweep.h5"), "r") as f:
            fr = f["frequency_hz"][:]
            for group, style in (("nonlinear", "-o"), ("linear", "--")):
                if group not in f:
                    continue
                for name in sorted(f[group].keys(), key=lambda s: float(s[2:])):
                    ax.semilogy(fr, f[group][name][:], style, ms=3, label=f"{group} A = {name[2:]} N")
        if args.frf:
            with h5py.File(os.path.join(args.frf, "frf.h5"), "r") as f:
                ax.semilogy(f["frequency_hz"][:], f["direct/abs"][:], "k:", label="linear |H33| (2.36)")
        ax.set_title(os.path.basename(d.rstrip("/")))
        ax.set_xlabel("f (Hz)")
        ax.set_ylabel("peak-to-peak / 2A (m/N)")
        ax.grid(True, which="both")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(args.output)


if __name__ == "__main__":
    pcsim_post.main(main)
