#!/usr/bin/env python3
"""Post-processing of runs/conditions/wind_dynamic_study.sh: reads
<out>/still/summary.json and <out>/v<speed>-s<seed>/summary.json, writes
<out>/wind_sigma.csv and <out>/wind_sigma.png (sigma of the contact force
against the mean wind speed, every seed and their mean)."""
import csv
import glob
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def figures(path):
    p = json.load(open(path))["pantographs"][0]
    return p["mean_N"], p["std_N"], p["max_N"], p["min_N"], p["loss_of_contact_percent"]


def main(folder):
    rows = [(0.0, 0, *figures(os.path.join(folder, "still", "summary.json")))]
    for path in glob.glob(os.path.join(folder, "v*-s*", "summary.json")):
        m = re.match(r"v([0-9.]+)-s(\d+)", os.path.basename(os.path.dirname(path)))
        rows.append((float(m.group(1)), int(m.group(2)), *figures(path)))
    rows.sort()
    with open(os.path.join(folder, "wind_sigma.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["speed_m_s", "seed", "mean_N", "std_N", "max_N", "min_N", "loss_percent"])
        w.writerows(rows)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    speeds = sorted({r[0] for r in rows})
    means = [sum(r[3] for r in rows if r[0] == v) / sum(1 for r in rows if r[0] == v)
             for v in speeds]
    ax.plot([r[0] for r in rows], [r[3] for r in rows], "o", alpha=0.6, label="one seed")
    ax.plot(speeds, means, "k-", label="mean over the seeds")
    ax.set_xlabel("mean cross-wind speed [m/s]")
    ax.set_ylabel("standard deviation of the contact force [N]")
    ax.set_title("EN 50318, 300 km/h, turbulent cross-wind (category II)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "wind_sigma.png"), dpi=120)
    for r in rows:
        print("V %4.1f m/s seed %d: mean %.2f N, sigma %.2f N, max %.1f N, min %.1f N, "
              "loss %.2f %%" % r)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/conditions/wind")
