#!/usr/bin/python3
"""Slack events and energy of the chatter study (runs/hard/chatter_study.sh).

  postproc/chatter.py RESULTS_DIR [--plot FILE]

For each run folder in RESULTS_DIR (undamped-dt*, damped-*): dropper slack
events (taut -> slack transitions) in the first and second half of the run,
the largest dropper force, and the energy balance at the end. Prints a
Markdown table; --plot draws E - E0, W_ext and the balance residual over time
and the cumulative slack events.
"""
import argparse
import os
import sys

import h5py
import numpy as np


def study(folder):
    with h5py.File(os.path.join(folder, "results.h5"), "r") as f:
        t = f["time"][()]
        taut = f["droppers/force"][()] > 1e-9
        max_force = float(np.max(f["droppers/force"][()]))
    events = (taut[:-1] & ~taut[1:]).sum(axis=1)
    half = t[1:] < 0.5 * t[-1]
    with h5py.File(os.path.join(folder, "energy.h5"), "r") as f:
        energy = {k: f[k][()] for k in ("time", "energy_change", "work_external",
                                        "work_dissipated", "balance_residual")}
    return dict(t=t, events=events, first=int(events[half].sum()), second=int(events[~half].sum()),
                max_force=max_force, energy=energy, dt=float(t[1] - t[0]))


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", help="folder of the study's runs (runs/hard/chatter_study.sh)")
    ap.add_argument("--plot", help="PNG file for the energy and slack-event plot")
    args = ap.parse_args()
    if not os.path.isdir(args.results):
        print(f"chatter.py: error: no folder '{args.results}'", file=sys.stderr)
        return 2
    runs = {}
    for name in sorted(os.listdir(args.results)):
        if os.path.isfile(os.path.join(args.results, name, "energy.h5")):
            runs[name] = study(os.path.join(args.results, name))
    print("| run | dt (ms) | slack events, 1st half | 2nd half | max dropper force (N) | "
          "W_ext (J) | W_diss (J) | E - E0 (J) | residual at the end (J) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, r in runs.items():
        e = r["energy"]
        print(f"| {name} | {1e3 * r['dt']:.2f} | {r['first']} | {r['second']} | "
              f"{r['max_force']:.0f} | {e['work_external'][-1]:.1f} | "
              f"{e['work_dissipated'][-1]:.1f} | {e['energy_change'][-1]:.1f} | "
              f"{e['balance_residual'][-1]:.2f} |")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (a, b) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
        for name, r in runs.items():
            e = r["energy"]
            line, = a.plot(e["time"], e["energy_change"], lw=0.8, label=f"{name}: E - E0")
            a.plot(e["time"], e["balance_residual"], lw=0.8, ls="--", color=line.get_color())
            b.plot(r["t"][1:], np.cumsum(r["events"]), lw=0.8, label=name)
        a.set_ylabel("energy [J] (dashed: balance residual)")
        a.legend(fontsize=7)
        b.set_ylabel("cumulative slack events")
        b.set_xlabel("time [s]")
        b.legend(fontsize=7)
        fig.tight_layout()
        os.makedirs(os.path.dirname(os.path.abspath(args.plot)), exist_ok=True)
        fig.savefig(args.plot, dpi=90)
    return 0


if __name__ == "__main__":
    sys.exit(main())
