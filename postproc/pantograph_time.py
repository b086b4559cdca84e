#!/usr/bin/python3
"""Time response of the pantograph alone (pcsim pantograph, study: time).

usage: pantograph_time.py OUTDIR [OUTDIR2 ...] -o PNG [--labels A,B] [--title T] [--xlim A B]
Plots the head height y10 (contact dof), the frame angle and the head rotation for every
scheme stored in OUTDIR/time.h5 (rk4, hht, and *_linear if present). Several OUTDIRs
(e.g. without/with friction) are overlaid.
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
                    help="pcsim pantograph result folder(s) of time studies")
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--labels", default=None, help="comma-separated labels, one per folder")
    ap.add_argument("--title", default="", help="title of the plot")
    ap.add_argument("--schemes", default=None, help="comma list of groups of time.h5 (default: all)")
    ap.add_argument("--xlim", type=float, nargs=2, default=None, metavar=("T0", "T1"),
                    help="time window to show [s]")
    args = ap.parse_args()
    for d in args.outdirs:
        pcsim_post.need_run_folder(d, ("time.h5",), "pcsim pantograph (study: time)")
    labels = args.labels.split(",") if args.labels else [os.path.basename(d.rstrip("/")) for d in args.outdirs]
    fig, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    for d, lab in zip(args.outdirs, labels):
        with h5py.File(os.path.join(d, "time.h5"), "r") as f:
            for scheme in f.keys():
                if args.schemes and scheme not in args.schemes.split(","):
                    continue
                g = f[scheme]
                t = g["t"][:]
                q = g["q"][:]
                names = [n.decode() if isinstance(n, bytes) else n for n in g["dof_names"][:]]
                y = g["contact_height"][:]
                style = "--" if "hht" in scheme else ("-." if "linear" in scheme else "-")
                axes[0].plot(t, 1e3 * (y - y[0]), style, label=f"{lab} {scheme}")
                axes[1].plot(t, np.degrees(q[:, 0] - q[0, 0]), style, label=f"{lab} {scheme}")
                if q.shape[1] > 3:
                    axes[2].plot(t, np.degrees(q[:, 3]), style, label=f"{lab} {scheme}")
                else:
                    axes[2].plot(t, g["contact_force"][:], style, label=f"{lab} {scheme}")
    axes[0].set_ylabel("contact height change (mm)")
    axes[1].set_ylabel("frame angle change (deg)")
    axes[2].set_ylabel("head rotation θ7 (deg)")
    axes[2].set_xlabel("t (s)")
    if args.xlim:  # zoom: y range of the data inside the window
        axes[2].set_xlim(*args.xlim)
        for a in axes:
            ys = [l.get_ydata()[(l.get_xdata() >= args.xlim[0]) & (l.get_xdata() <= args.xlim[1])]
                  for l in a.get_lines()]
            ys = np.concatenate([y for y in ys if len(y)])
            pad = 0.05 * (ys.max() - ys.min()) + 1e-12
            a.set_ylim(ys.min() - pad, ys.max() + pad)
    for a in axes:
        a.grid(True)
    axes[0].legend(fontsize=8)
    axes[0].set_title(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(args.output)


if __name__ == "__main__":
    pcsim_post.main(main)
