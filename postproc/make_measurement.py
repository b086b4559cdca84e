#!/usr/bin/python3
"""A synthetic "measurement" CSV made from a `pcsim run` result, to try `pcsim compare --measurement`.

    make_measurement.py RUN [-o FILE.csv] [--lag M] [--offset N[,N...]] [--noise N]
                        [--spacing M] [--seed S] [--pantograph NAME[,NAME...]] [--supports K]

One row every --spacing m of the first pantograph's travel (one instant of the train): each
pantograph's raw contact force averaged over --spacing m around its position at that
instant, with a force offset (one for all, or one per pantograph), white Gaussian noise
(standard deviation --noise, independent per pantograph) and one position lag: x is the
first pantograph's position plus the lag (an odometer reading lag m ahead). Without
--pantograph the run's first pantograph in an unnamed 'force [N]' column; with it, a
'force NAME [N]' column per pantograph named. The uplift histories of the K supports
nearest to the analysis section's middle are added as 'uplift X [mm]' columns (the
support's own position X, no lag). Format: docs/assessment.md "Measurements".
"""
import argparse
import os

import numpy as np

import interaction_plots
import pcsim_post


def sample_averages(position, force, x, spacing):
    """The force averaged over [x - spacing/2, x + spacing/2], as an acquisition system
    integrates between samples (point samples would alias the contact's high frequencies)."""
    integral = np.concatenate(([0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(position))))
    return (np.interp(x + 0.5 * spacing, position, integral)
            - np.interp(x - 0.5 * spacing, position, integral)) / spacing


def arguments():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n\n", 2)[2],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", metavar="RUN", help="pcsim run result folder")
    ap.add_argument("-o", "--output", help="CSV file to write (default: RUN-synthetic.csv)")
    ap.add_argument("--lag", type=float, default=3.7, help="position lag (m, default 3.7)")
    ap.add_argument("--offset", default="8", metavar="N[,N...]",
                    help="force offset (N, default 8), or one per pantograph")
    ap.add_argument("--noise", type=float, default=5.0, help="noise standard deviation (N, default 5)")
    ap.add_argument("--spacing", type=float, default=0.25, help="sample spacing (m, default 0.25)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the noise (default 1)")
    ap.add_argument("--pantograph", metavar="NAME[,NAME...]",
                    help="pantographs, one named column each (default: the first, 'force [N]')")
    ap.add_argument("--supports", type=int, default=2, help="uplift columns (default 2)")
    a = ap.parse_args()
    a.names = a.pantograph.split(",") if a.pantograph else [None]
    try:
        a.offsets = [float(v) for v in a.offset.split(",")]
    except ValueError:
        pcsim_post.fail("--offset %s: numbers expected" % a.offset)
    if len(a.offsets) == 1:
        a.offsets *= len(a.names)
    if len(a.offsets) != len(a.names):
        pcsim_post.fail("--offset: %d offsets for %d pantographs" % (len(a.offsets), len(a.names)))
    return a


def main():
    a = arguments()
    run = interaction_plots.Run(a.run)
    output = a.output or os.path.normpath(a.run) + "-synthetic.csv"
    names = [run.pantograph(n)[0] for n in a.names]
    first = run.pantographs[names[0]]
    position, order = np.unique(first["position"], return_index=True)  # standing still: one row
    true_x = np.arange(position[0] + a.spacing, position[-1] - a.spacing, a.spacing)
    time_at = np.interp(true_x, position, run.time[order])
    rng = np.random.default_rng(a.seed)
    forces = []
    for name, offset in zip(names, a.offsets):
        p = run.pantographs[name]
        own, own_order = np.unique(p["position"], return_index=True)
        at = np.interp(time_at, run.time, p["position"])  # its position at the row's instant
        forces.append(sample_averages(own, p["contact_force"][own_order], at, a.spacing)
                      + offset + rng.normal(0.0, a.noise, len(true_x)))
    middle = 0.5 * (run.x_from + run.x_to)
    chosen = sorted(np.argsort(np.abs(run.support_x - middle))[:a.supports])
    columns = [true_x + a.lag] + forces + [1e3 * np.interp(time_at, run.time, run.uplift[:, i])
                                           for i in chosen]
    header = ["x [m]"] + ["force [N]" if n is None else "force %s [N]" % n for n in a.names]
    header += ["uplift %g [mm]" % run.support_x[i] for i in chosen]
    with open(output, "w") as f:
        f.write("# synthetic measurement from %s, pantograph %s (postproc/make_measurement.py):\n"
                "# lag %g m, force offset %s N, noise %g N (seed %d), every %g m\n"
                % (os.path.basename(os.path.normpath(a.run)), ", ".join("'%s'" % n for n in names),
                   a.lag, ", ".join("%g" % o for o in a.offsets), a.noise, a.seed, a.spacing))
        f.write(",".join(header) + "\n")
        for row in zip(*columns):
            f.write(",".join("%.3f" % v for v in row) + "\n")
    print("make_measurement: wrote %s (%d rows)" % (output, len(true_x)))

if __name__ == "__main__":
    pcsim_post.main(main)
