#!/usr/bin/env python3
"""Post-processing of runs/conditions/blowoff_study.sh: reads every
<out>/v<speed>/static.h5 (/blow_off), writes <out>/blowoff.csv and
<out>/blowoff.png (lateral position vs wind speed, the permissible one, the
independent estimate) and prints the speed at which the contact wire leaves
the permissible lateral position (linear interpolation between the speeds)."""
import csv
import glob
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blowoff_estimate import SPAN, estimate  # noqa: E402


def read(folder):
    rows = []
    for path in glob.glob(os.path.join(folder, "v*", "static.h5")):
        speed = float(os.path.basename(os.path.dirname(path))[1:])
        with h5py.File(path, "r") as f:
            if "blow_off" not in f:  # no wind: the bare line
                y = np.array(f["/nodes/values"])[:, 1]
                rows.append(dict(speed=speed, max_excursion=float(np.max(np.abs(y))),
                                 mid_span=0.0, permissible=0.40, x_max=float("nan")))
                continue
            b = f["blow_off"]
            x, lat, sup = np.array(b["x"]), np.array(b["lateral"]), np.array(b["at_support"])
            # interior mid-spans (spans 2..9): away from the anchored ends
            mid = (sup == 0) & (x > SPAN) & (x < x.max() - SPAN)
            bare = np.array(b["lateral_bare"])
            rows.append(dict(speed=speed, max_excursion=float(b["max_excursion"][0]),
                             mid_span=float(np.mean(lat[mid] - bare[mid])),
                             permissible=float(b["permissible"][0]), x_max=float("nan")))
    return sorted(rows, key=lambda r: r["speed"])


def crossing(rows):
    for a, b in zip(rows, rows[1:]):
        lim = b["permissible"]
        if a["max_excursion"] <= lim < b["max_excursion"]:
            w = (lim - a["max_excursion"]) / (b["max_excursion"] - a["max_excursion"])
            return a["speed"] + w * (b["speed"] - a["speed"])
    return None


def main(folder):
    rows = read(folder)
    for r in rows:
        r["estimate_mid_span"] = estimate(r["speed"])["contact_mid"] if r["speed"] > 0 else 0.0
    with open(os.path.join(folder, "blowoff.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["speed_m_s", "max_excursion_m", "mid_span_deflection_m",
                    "estimate_mid_span_deflection_m", "permissible_m"])
        for r in rows:
            w.writerow([r["speed"], r["max_excursion"], r["mid_span"], r["estimate_mid_span"],
                        r["permissible"]])
    v = crossing(rows)
    speeds = [r["speed"] for r in rows]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(speeds, [r["max_excursion"] for r in rows], "o-",
            label="largest lateral position of the contact wire (pcsim)")
    ax.plot(speeds, [r["mid_span"] for r in rows], "s-", label="mid-span deflection (pcsim)")
    ax.plot(speeds, [r["estimate_mid_span"] for r in rows], "k--",
            label="mid-span deflection (independent estimate)")
    ax.axhline(rows[-1]["permissible"], color="r", label="permissible lateral position")
    if v is not None:
        ax.axvline(v, color="r", ls=":", label="leaves it at %.1f m/s" % v)
    ax.set_xlabel("mean cross-wind speed [m/s]")
    ax.set_ylabel("lateral position / deflection [m]")
    ax.set_title("EN 50318 line: static blow-off of the contact wire")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "blowoff.png"), dpi=120)
    for r in rows:
        rel = r["mid_span"] / r["estimate_mid_span"] - 1 if r["estimate_mid_span"] else 0.0
        print("V %4.1f m/s: largest lateral position %.4f m, mid-span deflection %.4f m "
              "(estimate %.4f m, %+.2f %%)" % (r["speed"], r["max_excursion"], r["mid_span"],
                                             r["estimate_mid_span"], 100 * rel))
    print("leaves the permissible %.2f m at %s" % (
        rows[-1]["permissible"], "%.1f m/s" % v if v else "no speed of the sweep"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/conditions/blowoff")
