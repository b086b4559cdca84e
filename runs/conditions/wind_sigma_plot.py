#!/usr/bin/env python3
"""Post-processing of runs/conditions/wind_dynamic_study.sh: reads
<out>/still/ and <out>/v<speed>-s<seed>/ (summary.json, and results.h5's
snapshots for the contact point's lateral position), writes
<out>/wind_sigma.csv and <out>/wind_sigma.png (sigma of the contact force
and the contact point's largest lateral position against the mean wind
speed, every seed and their mean)."""
import csv
import glob
import json
import os
import re
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PERMISSIBLE = 0.40  # [m] conditions.wind.working_half_width's default (docs/conditions.md)


def figures(folder):
    p = json.load(open(os.path.join(folder, "summary.json")))["pantographs"][0]
    lateral = float("nan")
    path = os.path.join(folder, "results.h5")
    if os.path.exists(path):
        with h5py.File(path, "r") as f:
            if "/snapshots/pantograph_points" in f:
                # row 1: the contact point (x, y, z); y the contact wire's at x
                y = np.array(f["/snapshots/pantograph_points"])[:, 1, 1]
                lateral = float(np.max(np.abs(y)))
    return (p["mean_N"], p["std_N"], p["max_N"], p["min_N"], p["loss_of_contact_percent"],
            lateral)


def main(folder):
    rows = [(0.0, 0, *figures(os.path.join(folder, "still")))]
    for path in glob.glob(os.path.join(folder, "v*-s*", "summary.json")):
        m = re.match(r"v([0-9.]+)-s(\d+)", os.path.basename(os.path.dirname(path)))
        rows.append((float(m.group(1)), int(m.group(2)), *figures(os.path.dirname(path))))
    rows.sort()
    with open(os.path.join(folder, "wind_sigma.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["speed_m_s", "seed", "mean_N", "std_N", "max_N", "min_N", "loss_percent",
                    "contact_point_max_lateral_m"])
        w.writerows(rows)
    speeds = sorted({r[0] for r in rows})
    def mean_of(col):
        return [np.mean([r[col] for r in rows if r[0] == v]) for v in speeds]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    ax.plot([r[0] for r in rows], [r[3] for r in rows], "o", alpha=0.6, label="one seed")
    ax.plot(speeds, mean_of(3), "k-", label="mean over the seeds")
    ax.set_xlabel("mean cross-wind speed [m/s]")
    ax.set_ylabel("standard deviation of the contact force [N]")
    ax.set_title("EN 50318, 300 km/h, turbulent cross-wind")
    ax.grid(True, alpha=0.3)
    ax.legend()
    bx.plot([r[0] for r in rows], [r[7] for r in rows], "o", alpha=0.6, label="one seed")
    bx.plot(speeds, mean_of(7), "k-", label="mean over the seeds")
    bx.axhline(PERMISSIBLE, color="r", label="permissible lateral position")
    bx.set_xlabel("mean cross-wind speed [m/s]")
    bx.set_ylabel("contact point's largest lateral position [m]")
    bx.set_title("contact point on the head (snapshots)")
    bx.grid(True, alpha=0.3)
    bx.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "wind_sigma.png"), dpi=120)
    for r in rows:
        print("V %4.1f m/s seed %d: mean %.2f N, sigma %.2f N, max %.1f N, min %.1f N, "
              "loss %.2f %%, contact point's largest lateral position %.4f m" % r)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/conditions/wind")
