#!/usr/bin/python3
"""Table and plots of the hard cases (docs/hard-cases.md) from their result folders.

  postproc/hard_cases.py RESULTS_DIR [--plots DIR]

RESULTS_DIR holds one folder per case as written by
tests/hard/hard_cases.py --keep RESULTS_DIR (runs/hard/run_hard.sh). Prints
the Markdown table on stdout; with --plots, writes energy and contact-force
plots of the cases named in PLOTTED.
"""
import argparse
import json
import os
import sys

import h5py
import numpy as np

PLOTTED = ["undamped", "wave-095", "gap-landing", "rejection"]


def slack_events(f):
    if "droppers/force" not in f:
        return 0
    taut = f["droppers/force"][()] > 1e-9
    return int(np.sum(taut[:-1] & ~taut[1:]))


def row(case, folder):
    with open(os.path.join(folder, "summary.json")) as s:
        summary = json.load(s)
    with h5py.File(os.path.join(folder, "results.h5"), "r") as f:
        events = slack_events(f)
        forces = [g["contact_force"][()] for g in f["pantographs"].values()]
        uplift = 1e3 * float(np.max(f["supports/uplift"][()]))
    en = summary.get("en50318", {})
    sigmas, losses = [], []
    for p in en.values():
        fig = {x["key"]: x["value"] for x in p.get("figures", [])} if "figures" in p else p
        sigmas.append(fig.get("std_N", float("nan")))
        losses.append(fig.get("loss_of_contact_percent", float("nan")))
    e = summary.get("energy", {})
    ratio = e.get("max_balance_residual_J", float("nan")) / max(e.get("turnover_J", 1.0), 1e-30)
    fmt = lambda xs, f: " / ".join(f.format(x) for x in xs) if xs else "–"
    return (f"| {case} | {summary['newton_iterations_per_step']:.2f} | {fmt(sigmas, '{:.1f}')} | "
            f"{fmt(losses, '{:.2f}')} | {events} | {max(float(np.max(x)) for x in forces):.0f} | "
            f"{uplift:.0f} | {e.get('work_external_J', 0):.1f} | {e.get('work_dissipated_J', 0):.1f} | "
            f"{ratio:.1e} | {summary.get('rejected_steps', 0)} | {summary['time_per_step_ms']:.2f} |")


def plot(case, folder, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    with h5py.File(os.path.join(folder, "energy.h5"), "r") as f:
        t = f["time"][()]
        a.plot(t, f["energy_change"][()], label="E - E0")
        a.plot(t, f["work_external"][()], label="W_ext")
        a.plot(t, f["work_dissipated"][()], label="W_diss")
        a.plot(t, f["balance_residual"][()], label="E - E0 - W_ext - W_diss")
    a.set_ylabel("energy [J]")
    a.legend(fontsize=8)
    a.set_title(f"hard case {case}")
    with h5py.File(os.path.join(folder, "results.h5"), "r") as f:
        t = f["time"][()]
        for name, g in f["pantographs"].items():
            b.plot(t, g["contact_force"][()], lw=0.6, label=name)
    b.set_xlabel("time [s]")
    b.set_ylabel("contact force [N]")
    fig.tight_layout()
    path = os.path.join(out_dir, f"{case}.png")
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", help="results folder of tests/hard/hard_cases.py --keep")
    ap.add_argument("--plots", help="folder for the PNG plots of the worst cases")
    args = ap.parse_args()
    if not os.path.isdir(args.results):
        print(f"hard_cases.py: error: no folder '{args.results}'", file=sys.stderr)
        return 2
    print("| case | Newton its/step | σ (N) | loss of contact (%) | slack events | max force (N) | "
          "max uplift (mm) | W_ext (J) | W_diss (J) | balance residual / turnover | rejected steps | ms/step |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case in sorted(os.listdir(args.results)):
        folder = os.path.join(args.results, case)
        if os.path.isfile(os.path.join(folder, "summary.json")):
            print(row(case, folder))
            if args.plots and case in PLOTTED:
                os.makedirs(args.plots, exist_ok=True)
                plot(case, folder, args.plots)
    return 0


if __name__ == "__main__":
    sys.exit(main())
