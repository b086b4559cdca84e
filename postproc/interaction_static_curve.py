#!/usr/bin/python3
"""Static contact force vs working height of a pantograph model at a fixed bellows torque.

    interaction_static_curve.py PCSIM_BIN MODEL.yaml -o curve.png [--json curve.json]
        [--F0 120] [--h0 1.2] [--heights 1.15:1.24:0.005] [--forces 0,40,...,320]

For every (F, h) of the grid, `pcsim pantograph` computes the static equilibrium
(`static_equilibrium(F, h)`, thesis 2.12-2.14) and reports the bellows torque M0(F, h) it
needs (summary.json: equilibrium.bellows_torque_Nm); a one-step time study is used only
to get that summary. The reference torque is M0ref = M0(F0, h0) (the torque the
interaction run keeps fixed). For every height h, the static contact force at M0ref is
found by interpolating M0(., h) in F (monotone). The slope dF/dh at h0 is the pantograph's
static height stiffness: the contact force lost per metre the wire is lifted.
"""
import argparse
import json
import os
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pcsim_post  # noqa: E402


def bellows_torque(pcsim, model, force, height, workdir):
    scene = os.path.join(workdir, "scene.yaml")
    with open(scene, "w") as f:
        f.write("name: static_curve\npantograph: {model: %s}\n"
                "equilibrium: {contact_force: %r, working_height: %r}\n"
                "study: {type: time, schemes: [rk4], dt: 1.0e-4, t_end: 1.0e-4, "
                "force: {type: constant, value: %r}}\n"
                % (os.path.abspath(model), force, height, force))
    out = os.path.join(workdir, "out")
    subprocess.run([pcsim, "pantograph", scene, "-o", out, "--overwrite"], check=True,
                   stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["equilibrium"]["bellows_torque_Nm"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pcsim", metavar="PCSIM_BIN", help="the pcsim executable")
    ap.add_argument("model", metavar="MODEL.yaml", help="pantograph model file (meshes/pantographs/)")
    ap.add_argument("-o", "--output", required=True, help="PNG file of the curve")
    ap.add_argument("--json", metavar="FILE", help="also write the curve to this JSON file")
    ap.add_argument("--F0", type=float, default=120.0, help="reference static force [N] (120)")
    ap.add_argument("--h0", type=float, default=1.2, help="reference working height [m] (1.2)")
    ap.add_argument("--heights", default="1.15:1.24:0.005",
                    help="working heights FROM:TO:STEP [m] (1.15:1.24:0.005)")
    ap.add_argument("--forces", default="0,40,80,120,160,200,240,280,320",
                    help="comma-separated force grid [N] (0,40,...,320)")
    a = ap.parse_args()
    pcsim_post.need_file(a.pcsim, "pcsim executable")
    pcsim_post.need_file(a.model, "pantograph model")
    lo, hi, step = (float(v) for v in a.heights.split(":"))
    heights = np.round(np.arange(lo, hi + step / 2, step), 6)
    forces = np.array([float(v) for v in a.forces.split(",")])
    with tempfile.TemporaryDirectory() as tmp:
        m_ref = bellows_torque(a.pcsim, a.model, a.F0, a.h0, tmp)
        torque = np.array([[bellows_torque(a.pcsim, a.model, F, h, tmp) for F in forces]
                           for h in heights])
    static_force = []
    for row in torque:
        order = np.argsort(row)
        if not (np.all(np.diff(row) > 0) or np.all(np.diff(row) < 0)):
            raise SystemExit("M0 is not monotone in F at some height: %s" % row)
        if not row.min() <= m_ref <= row.max():
            static_force.append(np.nan)  # outside the force grid
            continue
        static_force.append(float(np.interp(m_ref, row[order], forces[order])))
    static_force = np.array(static_force)
    i0 = int(np.argmin(np.abs(heights - a.h0)))
    slope = np.gradient(static_force, heights)[i0]
    result = {"model": a.model, "F0_N": a.F0, "h0_m": a.h0, "M0_ref_Nm": m_ref,
              "heights_m": heights.tolist(), "forces_grid_N": forces.tolist(),
              "bellows_torque_Nm": torque.tolist(),
              "static_force_at_M0ref_N": [None if np.isnan(v) else v for v in static_force],
              "dF_dh_at_h0_N_per_m": float(slope)}
    print("M0(F0 = %g N, h0 = %g m) = %.2f N m; static force at fixed M0:" % (a.F0, a.h0, m_ref))
    for h, F in zip(heights, static_force):
        print("  h = %.3f m  F = %7.1f N" % (h, F))
    print("dF/dh at h0 = %.0f N/m" % slope)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(result, f, indent=2)
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    ax.plot(heights, static_force, "o-", ms=3)
    ax.axvline(a.h0, color="0.5", ls="--", lw=0.7)
    ax.axhline(a.F0, color="0.5", ls="--", lw=0.7)
    ax.set_xlabel("working height h (m)")
    ax.set_ylabel("static contact force (N)")
    ax.set_title("Static force at fixed M0 = %.0f N m (dF/dh = %.0f N/m at h0)" % (m_ref, slope),
                 fontsize=10)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


if __name__ == "__main__":
    pcsim_post.main(main)
