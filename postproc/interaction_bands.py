#!/usr/bin/python3
"""Where the contact force's standard deviation comes from: σ by frequency band.

usage: interaction_bands.py RUN[:C:W] [RUN[:C:W] ...] [--labels A,B] [--markdown]
                            [--pantograph NAME] [--model MODEL] [--dy5-dtheta S]

For each `pcsim run` output folder: the 20 Hz filtered contact force over the analysis
section, its mean and σ, and σ split into frequency bands by Parseval (σ² = Σ band
variances of the section's mean-removed signal, Hann-free rectangular window, so the
bands add up to σ exactly). For a DSA-380 pantograph (q[:, 0] = frame angle θ) also the
frame's mean angle and its motion: σ of θ and the fraction of the section's time the frame
descends (θ̇ < 0, where a one-way damper acts; dy5/dθ > 0 over the working range).

With RUN:C:W (damper constant C in N s/m, W = 1 for a one-way damper, 0 for two-way) also the
damper's mean lift: the time average over the section of the damper torque on the frame
(−c h² θ̇ while it acts, h = dl_a/dθ from the lever geometry of MODEL, A.13–A.19) divided
by dy5/dθ, i.e. the mean upward force it adds at the head. Two-way it averages to ~0 in a
stationary run; one-way it is c h² E[max(−θ̇, 0)] / (dy5/dθ) > 0 (a ratchet).
"""
import argparse
import os

import numpy as np

import pcsim_post

BANDS = [(0.0, 1.0), (1.0, 2.0), (2.0, 5.0), (5.0, 10.0), (10.0, 20.0)]
# dy5/dθ of meshes/pantographs/dsa380_rigid.yaml at the working height 1.2 m: `pcsim
# pantograph` static equilibria under 120 N at h = 1.19 and 1.21 m, Δh/Δθ (docs/interaction.md).
DY5_DTHETA = 1.595


def lever_arm(model, theta):
    """h(θ) = dl_a/dθ of the damper between point 13 and point 1p on bar 1 (A.14)."""
    import yaml
    with open(pcsim_post.need_file(model, "DSA-380 model")) as f:
        g = yaml.safe_load(f)["geometry"]
    a = theta + np.radians(g["theta_1p_deg"])
    dx = g["x1"] - g["x13"] + g["L1p"] * np.cos(a)
    dy = g["y1"] - g["y13"] + g["L1p"] * np.sin(a)
    return (-dx * g["L1p"] * np.sin(a) + dy * g["L1p"] * np.cos(a)) / np.hypot(dx, dy)


def analyse(folder, pantograph, damper=None, model=None, dy5_dtheta=DY5_DTHETA):
    import h5py
    pcsim_post.need_run_folder(folder, ("results.h5",))
    with h5py.File(os.path.join(folder, "results.h5"), "r") as h:
        names = list(h["/pantographs"])
        name = pantograph or names[0]
        g = h["/pantographs/" + name]
        t = h["/time"][()]
        x = g["position"][()]
        f = g["contact_force_filtered"][()]
        q = g["q"][()] if "q" in g else None
        a, b = h["/"].attrs["analysis_from_x"], h["/"].attrs["analysis_to_x"]
    s = (x >= a) & (x <= b)
    fs, ts = f[s], t[s]
    dt = ts[1] - ts[0]
    d = fs - fs.mean()
    spectrum = np.abs(np.fft.rfft(d)) ** 2
    freq = np.fft.rfftfreq(len(d), dt)
    # Parseval: Σ|X_k|² over the full two-sided spectrum = N Σ d²; rfft counts the
    # interior bins once, so weight them twice.
    weight = np.full(len(freq), 2.0)
    weight[0] = 1.0
    if len(d) % 2 == 0:
        weight[-1] = 1.0
    power = weight * spectrum / len(d) ** 2
    out = {"mean": fs.mean(), "std": fs.std(), "bands": []}
    for lo, hi in BANDS:
        sel = (freq >= lo) & (freq < hi)
        out["bands"].append(np.sqrt(power[sel].sum()))
    if q is not None and q.shape[1] >= 4:
        th = q[s, 0]
        thd = np.gradient(q[:, 0], t)[s]
        out["theta_mean_deg"] = np.degrees(th.mean())
        out["theta_std_mrad"] = 1e3 * th.std()
        out["descending"] = float((thd < 0).mean())
        if damper is not None:
            c, one_way = damper
            h = lever_arm(model, q[s, 0])
            acts = (thd < 0) if one_way else np.ones_like(thd, dtype=bool)
            torque = np.where(acts, -c * h * h * thd, 0.0)  # upward torque on the frame
            out["damper_lift"] = torque.mean() / dy5_dtheta
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", metavar="RUN[:C:W]",
                    help="pcsim run result folder; :C:W adds the damper's mean lift "
                         "(C damper constant [N s/m], W 1 one-way, 0 two-way)")
    ap.add_argument("--labels", default=None, help="comma-separated labels, one per run")
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    ap.add_argument("--pantograph", default=None, help="pantograph name (default: the first)")
    ap.add_argument("--model", default=os.path.join(pcsim_post.HERE, os.pardir, "meshes",
                                                    "pantographs", "dsa380_rigid.yaml"),
                    help="DSA-380 model file for the damper's lever geometry "
                         "(meshes/pantographs/dsa380_rigid.yaml)")
    ap.add_argument("--dy5-dtheta", type=float, default=DY5_DTHETA,
                    help="dy5/dθ [m/rad] that turns the damper torque into a force at the head "
                         "(%g)" % DY5_DTHETA)
    args = ap.parse_args()
    specs = [r.split(":") for r in args.runs]
    folders = [sp[0] for sp in specs]
    labels = args.labels.split(",") if args.labels else [os.path.basename(f.rstrip("/")) for f in folders]
    if len(labels) != len(folders):
        pcsim_post.fail("--labels: %d labels for %d runs" % (len(labels), len(folders)))
    head = ["run", "mean (N)", "σ (N)"] + ["σ %g-%g Hz" % b for b in BANDS] + [
        "θ mean (deg)", "σ θ (mrad)", "frame descending", "damper lift (N)"]
    rows = []
    for sp, lab in zip(specs, labels):
        damper = (float(sp[1]), sp[2] == "1") if len(sp) == 3 else None
        o = analyse(sp[0], args.pantograph, damper, args.model, args.dy5_dtheta)
        row = [lab, "%.1f" % o["mean"], "%.2f" % o["std"]] + ["%.2f" % v for v in o["bands"]]
        if "theta_mean_deg" in o:
            row += ["%.3f" % o["theta_mean_deg"], "%.2f" % o["theta_std_mrad"],
                    "%.0f %%" % (100 * o["descending"])]
        else:
            row += ["–", "–", "–"]
        row += ["%.1f" % o["damper_lift"] if "damper_lift" in o else "–"]
        rows.append(row)
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for row in rows:
            print("| " + " | ".join(row) + " |")
    else:
        for row in [head] + rows:
            print("  ".join("%-14s" % c for c in row))


if __name__ == "__main__":
    pcsim_post.main(main)
