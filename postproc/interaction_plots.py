#!/usr/bin/python3
"""Plots of `pcsim run` results (results.h5 + summary.json in each output folder).

    interaction_plots.py force    OUT_DIR [OUT_DIR ...] -o force.png    [--labels A,B] [--pantograph NAME] [--raw]
    interaction_plots.py spectrum OUT_DIR [OUT_DIR ...] -o spectrum.png [--labels A,B] [--pantograph NAME]
    interaction_plots.py uplift   OUT_DIR -o uplift.png

force:    contact force along the track (position of the contact point); with one run the raw
          and the 20 Hz filtered force, with several the filtered forces overlaid (--raw adds
          the raw ones); the analysis section is shaded.
spectrum: single-sided amplitude spectrum (FFT, Hann window) of the raw contact force over
          the analysis section, 0-20 Hz (zero-padded 16x); dashed lines at the span-passing frequency v/L
          and its harmonics.
uplift:   contact-wire uplift at the supports vs time (supports of the analysis section and
          their neighbours) and the maximum uplift per support.
"""
import argparse
import json
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


class Run:
    def __init__(self, folder, label=None):
        self.folder = folder
        with open(os.path.join(folder, "summary.json")) as f:
            self.summary = json.load(f)
        self.label = label or self.summary.get("scene", os.path.basename(folder.rstrip("/")))
        with h5py.File(os.path.join(folder, "results.h5"), "r") as h:
            self.time = h["/time"][()]
            self.x_from = float(h["/"].attrs["analysis_from_x"])
            self.x_to = float(h["/"].attrs["analysis_to_x"])
            self.speed = float(h["/"].attrs["speed_m_s"])
            self.support_x = h["/supports/x"][()]
            self.uplift = h["/supports/uplift"][()]
            self.pantographs = {}
            for name in h["/pantographs"]:
                g = h["/pantographs/" + name]
                self.pantographs[name] = {k: g[k][()] for k in
                                          ("position", "contact_force", "contact_force_filtered")}

    def pantograph(self, name=None):
        if name is None:
            name = next(iter(self.pantographs))
        return name, self.pantographs[name]


def load_runs(folders, labels):
    labels = labels.split(",") if labels else [None] * len(folders)
    if len(labels) != len(folders):
        raise SystemExit("--labels: %d labels for %d runs" % (len(labels), len(folders)))
    return [Run(f, l) for f, l in zip(folders, labels)]


def shade_section(ax, run):
    ax.axvspan(run.x_from, run.x_to, color="0.85", zorder=0, label="analysis section")


def plot_force(a):
    runs = load_runs(a.runs, a.labels)
    fig, ax = plt.subplots(figsize=(11, 4.2))
    shade_section(ax, runs[0])
    names = [a.pantograph] if a.pantograph else list(runs[0].pantographs) if len(runs) == 1 else [None]
    for run in runs:
        for pname in names:
            name, p = run.pantograph(pname)
            tag = run.label if len(names) == 1 else "%s %s" % (run.label, name)
            if len(runs) == 1 or a.raw:
                ax.plot(p["position"], p["contact_force"], lw=0.5, alpha=0.6,
                        label="%s raw" % tag)
            ax.plot(p["position"], p["contact_force_filtered"], lw=1.1,
                    label="%s filtered %g Hz" % (tag, runs[0].summary["analysis"]["cutoff_hz"]))
    ax.set_xlabel("contact point position x (m)")
    ax.set_ylabel("contact force (N)")
    ax.set_title(a.title or "Contact force, %s" % ", ".join(r.label for r in runs))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right", ncol=2)
    if a.xlim:
        ax.set_xlim(*a.xlim)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


def plot_spectrum(a):
    runs = load_runs(a.runs, a.labels)
    fig, ax = plt.subplots(figsize=(9, 4.2))
    fmax = runs[0].summary["analysis"]["cutoff_hz"]
    for run in runs:
        name, p = run.pantograph(a.pantograph)
        inside = (p["position"] >= run.x_from) & (p["position"] <= run.x_to)
        t = run.time[inside]
        f = p["contact_force"][inside]
        # Uniform grid (the TS may have changed the step).
        dt = np.min(np.diff(t))
        tg = np.arange(t[0], t[-1], dt)
        fg = np.interp(tg, t, f)
        window = np.hanning(len(fg))
        fg = (fg - fg.mean()) * window
        nfft = 16 * len(fg)  # zero padding: interpolates the spectrum between the 1/T lines
        amp = 2 * np.abs(np.fft.rfft(fg, nfft)) / np.sum(window)
        freq = np.fft.rfftfreq(nfft, dt)
        keep = freq <= fmax
        ax.plot(freq[keep], amp[keep], lw=1.0, label=run.label)
    span = runs[0].support_x[1] - runs[0].support_x[0]
    fs = runs[0].speed / span
    for k in range(1, int(fmax / fs) + 1):
        ax.axvline(k * fs, color="0.5", ls="--", lw=0.6)
    ax.set_xlim(0, fmax)
    ax.set_xlabel("frequency (Hz)  (dashed: span passing v/L = %.2f Hz and harmonics)" % fs)
    ax.set_ylabel("amplitude (N)")
    ax.set_title(a.title or "Contact force spectrum over the analysis section")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


def plot_uplift(a):
    run = Run(a.runs[0], a.labels)
    xs = run.support_x
    up = 1e3 * run.uplift
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.2), gridspec_kw={"width_ratios": [3, 2]})
    show = [i for i, x in enumerate(xs) if run.x_from - 60.5 <= x <= run.x_to + 60.5]
    for i in show:
        inside = run.x_from - 1e-9 <= xs[i] <= run.x_to + 1e-9
        ax1.plot(run.time, up[:, i], lw=1.3 if inside else 0.7, ls="-" if inside else ":",
                 label="support x = %.0f m%s" % (xs[i], " (section)" if inside else ""))
    ax1.set_xlabel("time (s)")
    ax1.set_ylabel("contact-wire uplift at the support (mm)")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=7)
    peak = up.max(axis=0)
    colors = ["C3" if run.x_from - 1e-9 <= x <= run.x_to + 1e-9 else "C0" for x in xs]
    ax2.bar(xs, peak, width=25, color=colors)
    ax2.set_xlabel("support position x (m)  (red: analysis section)")
    ax2.set_ylabel("max uplift (mm)")
    ax2.grid(alpha=0.3, axis="y")
    fig.suptitle(a.title or "Uplift at the supports, %s (max in section %.1f mm)"
                 % (run.label, 1e3 * run.summary["max_uplift_at_support_m"]))
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="plot", required=True)
    for name, fn in (("force", plot_force), ("spectrum", plot_spectrum), ("uplift", plot_uplift)):
        p = sub.add_parser(name)
        p.add_argument("runs", nargs="+" if name != "uplift" else 1, help="pcsim run output folder(s)")
        p.add_argument("-o", "--output", required=True, help="PNG file")
        p.add_argument("--labels", help="comma-separated labels, one per run")
        p.add_argument("--title")
        if name != "uplift":
            p.add_argument("--pantograph", help="pantograph name (default: the first)")
        if name == "force":
            p.add_argument("--raw", action="store_true", help="also the raw force with several runs")
            p.add_argument("--xlim", type=float, nargs=2)
        p.set_defaults(fn=fn)
    a = ap.parse_args()
    a.fn(a)


if __name__ == "__main__":
    main()
