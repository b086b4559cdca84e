#!/usr/bin/python3
"""Receptance H33 of the linearised pantograph: direct (2.36) vs modal superposition (2.40).

usage: pantograph_frf.py OUTDIR [OUTDIR_RESTRAINED] -o PNG
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
    ap.add_argument("outdirs", nargs="+", metavar="OUTDIR",
                    help="pcsim pantograph result folder(s) of frf studies")
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    args = ap.parse_args()
    for d in args.outdirs:
        pcsim_post.need_run_folder(d, ("frf.h5",), "pcsim pantograph (study: frf)")
    fig, ax = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for d in args.outdirs:
        lab = os.path.basename(d.rstrip("/"))
        with h5py.File(os.path.join(d, "frf.h5"), "r") as f:
            fr = f["frequency_hz"][:]
            h = f["direct/real"][:] + 1j * f["direct/imag"][:]
            ax[0].loglog(fr, np.abs(h), label=f"{lab} direct (2.36)")
            ax[1].semilogx(fr, np.degrees(np.angle(h)), label=f"{lab} direct")
            if "modal" in f:
                hm = f["modal/real"][:] + 1j * f["modal/imag"][:]
                ax[0].loglog(fr[::8], np.abs(hm[::8]), "o", ms=3, mfc="none",
                             label=f"{lab} modal (2.40), max rel. diff {np.max(np.abs(h - hm) / np.abs(h)):.1e}")
                ax[1].semilogx(fr[::8], np.degrees(np.angle(hm[::8])), "o", ms=3, mfc="none")
    ax[0].set_ylabel("|H33| (m/N)")
    ax[1].set_ylabel("phase (deg)")
    ax[1].set_xlabel("f (Hz)")
    for a in ax:
        a.grid(True, which="both")
    ax[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(args.output)


if __name__ == "__main__":
    pcsim_post.main(main)
