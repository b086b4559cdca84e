#!/usr/bin/python3
"""Plots of `pcsim run` results (results.h5 + summary.json in each output folder).

    interaction_plots.py force    RUN [RUN ...] -o force.png    [--labels A,B] [--pantograph NAME] [--raw] [--xlim X0 X1]
    interaction_plots.py spectrum RUN [RUN ...] -o spectrum.png [--labels A,B] [--pantograph NAME]
    interaction_plots.py uplift   RUN [RUN ...] -o uplift.png   [--labels A,B]

force:    contact force along the track (position of the contact point); with one run the raw
          and the low-pass filtered force, with several the filtered forces overlaid (--raw adds
          the raw ones); the analysis section is shaded.
spectrum: single-sided amplitude spectrum (FFT, Hann window) of the raw contact force over
          the analysis section, 0 to the cut-off frequency (zero-padded 16x); dashed lines at
          the span-passing frequency v/L and its harmonics.
uplift:   one run: contact-wire uplift at the supports vs time (supports of the analysis
          section and their neighbours) and the maximum uplift per support; several runs: the
          maximum uplift per support of every run, and the uplift history at the support of
          the largest uplift in the section of every run.
Uplift is stored in metres (results.h5 /supports/uplift) and shown in mm.
"""
import argparse
import os

import numpy as np

import pcsim_post


class Run:
    """A pcsim run result folder."""

    def __init__(self, folder, label=None):
        import h5py
        pcsim_post.need_run_folder(folder, ("summary.json", "results.h5"))
        self.folder = folder
        self.summary = pcsim_post.load_json(os.path.join(folder, "summary.json"))
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
        if name not in self.pantographs:
            pcsim_post.fail("run %s has no pantograph '%s' (it has: %s)"
                            % (self.folder, name, ", ".join(self.pantographs)))
        return name, self.pantographs[name]

    def in_section(self, x):
        return self.x_from - 1e-9 <= x <= self.x_to + 1e-9


def load_runs(folders, labels):
    labels = labels.split(",") if labels else [None] * len(folders)
    if len(labels) != len(folders):
        pcsim_post.fail("--labels: %d labels for %d runs" % (len(labels), len(folders)))
    return [Run(f, l) for f, l in zip(folders, labels)]


def draw_forces(ax, runs, names, raw=False):
    """The filtered contact force of pantographs 'names' of every run on 'ax' (the raw one too
    with one run or raw), the analysis section shaded."""
    ax.axvspan(runs[0].x_from, runs[0].x_to, color="0.85", zorder=0, label="analysis section")
    cutoff = runs[0].summary["analysis"]["cutoff_hz"]
    for run in runs:
        for pname in names:
            name, p = run.pantograph(pname)
            tag = run.label if len(names) == 1 else "%s %s" % (run.label, name)
            if len(runs) == 1 or raw:
                ax.plot(p["position"], p["contact_force"], lw=0.5, alpha=0.6, label="%s raw" % tag)
            ax.plot(p["position"], p["contact_force_filtered"], lw=1.1,
                    label="%s filtered %g Hz" % (tag, cutoff))
    ax.set_xlabel("contact point position x (m)")
    ax.set_ylabel("contact force (N)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right", ncol=2)


def force_figure(runs, pantograph=None, raw=False, xlim=None, title=None):
    plt = pcsim_post.pyplot()
    fig, ax = plt.subplots(figsize=(11, 4.2))
    names = [pantograph] if pantograph else list(runs[0].pantographs) if len(runs) == 1 else [None]
    draw_forces(ax, runs, names, raw)
    ax.set_title(title or "Contact force, %s" % ", ".join(r.label for r in runs))
    if xlim:
        ax.set_xlim(*xlim)
    fig.tight_layout()
    return fig


def draw_spectrum(ax, runs, pantograph=None):
    """The amplitude spectrum of the raw contact force of every run over the analysis section."""
    fmax = runs[0].summary["analysis"]["cutoff_hz"]
    for run in runs:
        name, p = run.pantograph(pantograph)
        inside = (p["position"] >= run.x_from) & (p["position"] <= run.x_to)
        t = run.time[inside]
        f = p["contact_force"][inside]
        if len(t) < 4:
            pcsim_post.fail("run %s has fewer than 4 samples in the analysis section" % run.folder)
        dt = np.min(np.diff(t))  # uniform grid (the TS may have changed the step)
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
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def spectrum_figure(runs, pantograph=None, title=None):
    plt = pcsim_post.pyplot()
    fig, ax = plt.subplots(figsize=(9, 4.2))
    draw_spectrum(ax, runs, pantograph)
    ax.set_title(title or "Contact force spectrum over the analysis section")
    fig.tight_layout()
    return fig


def uplift_one(run, title=None):
    plt = pcsim_post.pyplot()
    xs, up = run.support_x, 1e3 * run.uplift
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.2), gridspec_kw={"width_ratios": [3, 2]})
    for i, x in enumerate(xs):
        if not run.x_from - 60.5 <= x <= run.x_to + 60.5:
            continue
        inside = run.in_section(x)
        ax1.plot(run.time, up[:, i], lw=1.3 if inside else 0.7, ls="-" if inside else ":",
                 label="support x = %.0f m%s" % (x, " (section)" if inside else ""))
    ax1.set_xlabel("time (s)")
    ax1.set_ylabel("contact-wire uplift at the support (mm)")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=7)
    colors = ["C3" if run.in_section(x) else "C0" for x in xs]
    ax2.bar(xs, up.max(axis=0), width=0.4 * (xs[1] - xs[0]) if len(xs) > 1 else 10, color=colors)
    ax2.set_xlabel("support position x (m)  (red: analysis section)")
    ax2.set_ylabel("max uplift (mm)")
    ax2.grid(alpha=0.3, axis="y")
    fig.suptitle(title or "Uplift at the supports, %s (max in section %.1f mm)"
                 % (run.label, 1e3 * run.summary["max_uplift_at_support_m"]))
    fig.tight_layout()
    return fig


def uplift_many(runs, title=None):
    plt = pcsim_post.pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.2), gridspec_kw={"width_ratios": [3, 2]})
    for k, run in enumerate(runs):
        up = 1e3 * run.uplift
        section = [i for i, x in enumerate(run.support_x) if run.in_section(x)]
        worst = max(section, key=lambda i: up[:, i].max()) if section else int(np.argmax(up.max(axis=0)))
        ax1.plot(run.time, up[:, worst], lw=1.0, color="C%d" % k,
                 label="%s, support x = %.0f m" % (run.label, run.support_x[worst]))
    draw_max_uplift(ax2, runs)
    ax1.set_xlabel("time (s)")
    ax1.set_ylabel("uplift at the support of the largest uplift (mm)")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=7)
    fig.suptitle(title or "Uplift at the supports, %s" % ", ".join(r.label for r in runs))
    fig.tight_layout()
    return fig


def draw_max_uplift(ax, runs):
    """The largest uplift at every support of every run (mm), the analysis section shaded."""
    for k, run in enumerate(runs):
        largest = run.summary.get("max_uplift_at_support_m")
        ax.plot(run.support_x, 1e3 * run.uplift.max(axis=0), "o-", ms=3, color="C%d" % k,
                label=run.label + (" (max in section %.1f mm)" % (1e3 * largest) if largest is not None else ""))
    ax.axvspan(runs[0].x_from, runs[0].x_to, color="0.85", zorder=0)
    ax.set_xlabel("support position x (m)  (shaded: analysis section)")
    ax.set_ylabel("max uplift (mm)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)


def uplift_figure(runs, title=None):
    return uplift_one(runs[0], title) if len(runs) == 1 else uplift_many(runs, title)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n\n", 2)[2],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="plot", required=True, metavar="PLOT",
                            help="force, spectrum or uplift (see below)")
    for name in ("force", "spectrum", "uplift"):
        p = sub.add_parser(name, help="%s plot" % name)
        p.add_argument("runs", nargs="+", metavar="RUN", help="pcsim run output folder(s)")
        p.add_argument("-o", "--output", required=True, help="PNG file to write")
        p.add_argument("--labels", help="comma-separated labels, one per run (default: scene names)")
        p.add_argument("--title", help="title of the plot (default: one naming the runs)")
        if name != "uplift":
            p.add_argument("--pantograph", metavar="NAME", help="pantograph name (default: the first)")
        if name == "force":
            p.add_argument("--raw", action="store_true", help="also the raw force with several runs")
            p.add_argument("--xlim", type=float, nargs=2, metavar=("X0", "X1"),
                           help="range of positions shown (m)")
    a = ap.parse_args()
    runs = load_runs(a.runs, a.labels)
    if a.plot == "force":
        fig = force_figure(runs, a.pantograph, a.raw, a.xlim, a.title)
    elif a.plot == "spectrum":
        fig = spectrum_figure(runs, a.pantograph, a.title)
    else:
        fig = uplift_figure(runs, a.title)
    fig.savefig(a.output, dpi=110)


if __name__ == "__main__":
    pcsim_post.main(main)
