#!/usr/bin/python3
"""Sanity checks and event counts of a `pcsim run` result (results.h5).

    interaction_check.py OUT_DIR [--json FILE]

Prints: non-finite values per dataset (must be 0), per pantograph the time and the
number of intervals with zero raw contact force (loss of contact), and for the droppers
the number of slackening events (a dropper force going from > 0 to exactly 0 between two
recorded steps), the number of droppers that slacken at least once and the total
slack time (dropper-seconds). Exit status 1 when a dataset holds NaN/Inf.
"""
import argparse
import json
import os
import sys

import h5py
import numpy as np

import pcsim_post


def zero_runs(mask):
    """Number of maximal runs of True in a boolean array."""
    m = np.asarray(mask, dtype=np.int8)
    return int(np.sum(np.diff(np.concatenate(([0], m))) == 1))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run", metavar="RUN_DIR", help="pcsim run output folder")
    ap.add_argument("--json", metavar="FILE", help="also write the counts to this JSON file")
    a = ap.parse_args()
    pcsim_post.need_run_folder(a.run, ("results.h5",))
    report = {"run": a.run, "non_finite": {}, "pantographs": {}, "droppers": {}}
    with h5py.File(os.path.join(a.run, "results.h5"), "r") as h:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f":
                report["non_finite"][name] = int(np.sum(~np.isfinite(obj[()])))
        h.visititems(visit)
        t = h["/time"][()]
        dt = np.diff(t, append=t[-1])
        for name in h["/pantographs"]:
            f = h["/pantographs/%s/contact_force" % name][()]
            x = h["/pantographs/%s/position" % name][()]
            lost = f <= 0
            report["pantographs"][name] = {
                "loss_time_s": float(np.sum(dt[lost])),
                "loss_intervals": zero_runs(lost),
                "first_loss_x_m": float(x[lost][0]) if lost.any() else None,
            }
        if "/droppers/force" in h:
            d = h["/droppers/force"][()]
            slack = d <= 0.0
            events = np.sum(slack[1:] & ~slack[:-1], axis=0) + slack[0]
            report["droppers"] = {
                "count": int(d.shape[1]),
                "slack_at_start": int(np.sum(slack[0])),
                "slackening_events": int(np.sum(events)),
                "droppers_slackening": int(np.sum(events > 0)),
                "slack_time_dropper_s": float(np.sum(dt[:, None] * slack)),
                "min_force_N": float(d.min()),
                "max_force_N": float(d.max()),
            }
    bad = {k: v for k, v in report["non_finite"].items() if v}
    print("%s: %d float datasets, %d non-finite values%s" % (
        a.run, len(report["non_finite"]), sum(bad.values()),
        "" if not bad else " in " + ", ".join(bad)))
    for name, p in report["pantographs"].items():
        print("  pantograph %-10s zero contact force: %.4f s in %d interval(s)%s" % (
            name, p["loss_time_s"], p["loss_intervals"],
            "" if p["first_loss_x_m"] is None else ", first at x = %.1f m" % p["first_loss_x_m"]))
    d = report["droppers"]
    if d:
        print("  droppers: %d, slackening events %d (%d droppers), slack time %.3f dropper-s, "
              "force %.1f .. %.1f N" % (d["count"], d["slackening_events"],
                                        d["droppers_slackening"], d["slack_time_dropper_s"],
                                        d["min_force_N"], d["max_force_N"]))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(report, f, indent=2)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    pcsim_post.main(main)
