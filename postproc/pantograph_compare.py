#!/usr/bin/python3
"""Thesis comparison of the pantograph models (Table 2.2, Fig. 2.22).

usage:
  pantograph_compare.py modes RIGID_MODES FLEXIBLE_MODES [--markdown]
      modes of the rigid model (linearised at the equilibrium) and of the flexible-bar model
      side by side with thesis Table 2.2 (rigid and flexible); RIGID_MODES, FLEXIBLE_MODES
      are `pcsim pantograph` modes study folders (summary.json).
  pantograph_compare.py frf -o PNG --rigid-frf D --rigid-sweep D --flexible-frf D
                        --flexible-sweep D [--amplitude 10]
      Fig. 2.22: |y10/F| of the four models (rigid and flexible, each linearised (2.36) and
      nonlinear (harmonic sweeps, peak-to-peak / 2A)); prints the resonance peaks.
"""
import argparse
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import pcsim_post

# Thesis Table 2.2 with the motions of Tables 2.3-2.4: (motion, flexible model (ANSYS),
# rigid model (MATLAB)). Mode 6 is "Flex. barra 5 y mov. mec." in Table 2.2 and "Flexión de
# la barra 4" in Table 2.3; the text: bending of bar 4 with motion of the frame.
THESIS_TABLE_22 = [
    ("head rotation", 0.77339, 0.6551),
    ("frame", 1.2448, 1.2439),
    ("head vertical", 5.6362, 5.6231),
    ("head horizontal", 7.777, 7.8705),
    ("bending of bar 5", 21.7733, None),
    ("bending of bar 4", 25.2445, None),
]


def load_modes(folder, f_max=30.0):
    """{motion label: (undamped Hz, damping ratio of the damped mode)} up to f_max."""
    pcsim_post.need_run_folder(folder, ("summary.json",), "pcsim pantograph (study: modes)")
    s = pcsim_post.load_json(os.path.join(folder, "summary.json"))
    zeta = {m["label"]: m["damping_ratio"] for m in s["damped_modes"]}
    return {m["label"]: (m["frequency_hz"], zeta.get(m["label"]))
            for m in s["undamped_modes"] if m["frequency_hz"] <= f_max}


def modes_table(args):
    rigid, flex = load_modes(args.rigid), load_modes(args.flexible)
    thesis = {t[0]: t for t in THESIS_TABLE_22}
    def order(l):  # by the pcsim flexible frequency, else the rigid, else the thesis's
        return flex[l][0] if l in flex else (rigid[l][0] if l in rigid else thesis[l][1])

    labels = sorted(set(flex) | set(rigid) | set(thesis), key=order)
    head = ["motion", "thesis rigid (Hz)", "pcsim rigid (Hz)", "thesis flexible (Hz)",
            "pcsim flexible (Hz)", "pcsim flexible vs rigid", "pcsim vs thesis flexible",
            "ζ rigid", "ζ flexible"]
    fmt = lambda v, f="%.4f": f % v if v is not None else "–"
    rows = []
    for l in labels:
        tr = thesis[l][2] if l in thesis else None
        tf = thesis[l][1] if l in thesis else None
        pr, zr = rigid.get(l, (None, None))
        pf, zf = flex.get(l, (None, None))
        rows.append([l, fmt(tr), fmt(pr), fmt(tf), fmt(pf),
                     "%+.2f %%" % (100 * (pf / pr - 1)) if pr and pf else "–",
                     "%+.1f %%" % (100 * (pf / tf - 1)) if tf and pf else "–",
                     fmt(zr), fmt(zf)])
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for r in rows:
            print("| " + " | ".join(r) + " |")
    else:
        for r in [head] + rows:
            print("  ".join("%-18s" % c for c in r))


def resonance_peaks(f, h, fmin, fmax):
    """Local maxima of |H| between fmin and fmax (grid values)."""
    peaks = []
    for i in range(1, len(f) - 1):
        if fmin <= f[i] <= fmax and h[i] > h[i - 1] and h[i] >= h[i + 1]:
            peaks.append((f[i], h[i]))
    return peaks


def frf_figure(args):
    fig, ax = plt.subplots(figsize=(8, 5))
    curves = []
    for label, folder, kind, style in (
        ("rigid, linearised (2.36)", args.rigid_frf, "frf", "k-"),
        ("flexible, linearised (2.36)", args.flexible_frf, "frf", "b-"),
        ("rigid, nonlinear (sweep %g N)" % args.amplitude, args.rigid_sweep, "sweep", "ko"),
        ("flexible, nonlinear (sweep %g N)" % args.amplitude, args.flexible_sweep, "sweep", "bs"),
    ):
        if kind == "frf":
            pcsim_post.need_run_folder(folder, ("frf.h5",), "pcsim pantograph (study: frf)")
            with h5py.File(os.path.join(folder, "frf.h5"), "r") as f:
                fr, h = f["frequency_hz"][:], f["direct/abs"][:]
            ax.loglog(fr, h, style, lw=1.2, label=label)
        else:
            pcsim_post.need_run_folder(folder, ("sweep.h5",), "pcsim pantograph (study: sweep)")
            with h5py.File(os.path.join(folder, "sweep.h5"), "r") as f:
                fr, h = f["frequency_hz"][:], f["nonlinear/A_%g" % args.amplitude][:]
            ax.loglog(fr, h, style, ms=4, mfc="none", label=label)
        curves.append((label, fr, h))
    ax.set_xlim(0.5, 30)
    ax.set_xlabel("f (Hz)")
    ax.set_ylabel("|y10 / F| (m/N)")
    ax.set_title("Receptance of the head, four models (Fig. 2.22)")
    ax.grid(True, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    for label, fr, h in curves:
        print("%-34s peaks: %s" % (label, ", ".join("%.2f Hz (%.2e m/N)" % p
                                                   for p in resonance_peaks(fr, h, 0.5, 30))))
    print(args.output)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    m = sub.add_parser("modes", help="Table 2.2: modes of the rigid and flexible models")
    m.add_argument("rigid", help="pcsim pantograph modes folder of the rigid model")
    m.add_argument("flexible", help="pcsim pantograph modes folder of the flexible model")
    m.add_argument("--markdown", action="store_true", help="print a Markdown table")
    f = sub.add_parser("frf", help="Fig. 2.22: FRFs of the four models")
    f.add_argument("-o", "--output", required=True, help="PNG file to write")
    for key in ("rigid-frf", "rigid-sweep", "flexible-frf", "flexible-sweep"):
        f.add_argument("--" + key, required=True, metavar="DIR",
                       help="pcsim pantograph %s study folder of the %s model"
                       % (key.split("-")[1], key.split("-")[0]))
    f.add_argument("--amplitude", type=float, default=10.0,
                   help="force amplitude of the sweep to plot [N] (10)")
    args = ap.parse_args()
    if args.command == "modes":
        modes_table(args)
    else:
        frf_figure(args)


if __name__ == "__main__":
    pcsim_post.main(main)
