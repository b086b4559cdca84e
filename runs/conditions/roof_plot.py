"""Plot of runs/conditions/roof_study.sh: the filtered contact force of the
EN 50318 run with a still base and with the roof's motion, along the track,
with each run's sigma (summary.json), their difference, and the roof's motion.
usage: /usr/bin/python3 roof_plot.py OUT_DIR ROOF_CSV
"""
import json
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

out, roof_csv = sys.argv[1], sys.argv[2]


def run(name):
    s = json.load(open(f"{out}/{name}/summary.json"))
    sigma = next(f["value"] for f in s["en50318"]["pantograph"]["figures"] if f["key"] == "std_N")
    with h5py.File(f"{out}/{name}/results.h5") as h:
        g = h["pantographs/pantograph"]
        return g["position"][:], g["contact_force_filtered"][:], sigma, s["speed_kmh"] / 3.6


fig, (top, middle, bottom) = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True,
                                          gridspec_kw={"height_ratios": [2, 1, 1]})
forces = {}
for name, label in (("still", "still base"), ("roof", "roof motion")):
    x, f, sigma, v = run(name)
    forces[name] = f
    top.plot(x, f, lw=0.8, label=f"{label}: sigma {sigma:.2f} N")
middle.plot(x, forces["roof"] - forces["still"], color="C3", lw=0.8)
middle.set_ylabel("roof - still [N]")
middle.grid(alpha=0.3)
roof = np.loadtxt(roof_csv, delimiter=",", comments="#")
bottom.plot(5.0 + v * roof[:, 0], 1e3 * roof[:, 1], color="k", lw=0.8)
top.set_ylabel("contact force, 20 Hz low-pass [N]")
top.set_title("EN 50318, 300 km/h: pantograph base moved by the vehicle")
top.legend(loc="upper right")
top.grid(alpha=0.3)
bottom.set_xlabel("pantograph position along the track [m]")
bottom.set_ylabel("roof z_b [mm]")
bottom.grid(alpha=0.3)
bottom.set_xlim(x.min(), x.max())
fig.tight_layout()
fig.savefig(f"{out}/roof.png", dpi=110)
print(f"{out}/roof.png")
