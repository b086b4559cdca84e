#!/usr/bin/python3
"""Static shape of the catenary and its first frequencies.

usage: /usr/bin/python3 postproc/plot_catenary.py OUT_DIR [-o catenary.png]

OUT_DIR is the folder written by `pcsim modes` (or `pcsim static`: then the
frequency table is left out). Draws the deformed messenger and contact wires
and the droppers (side view, exaggerated vertical scale, plus plan view with
the stagger) and a table of the catenary frequencies.
"""
import argparse
import json
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pcsim_post  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", metavar="OUT_DIR", help="pcsim static or pcsim modes result folder")
    parser.add_argument("-o", "--output", default=None, help="PNG file (default: OUT_DIR/catenary.png)")
    args = parser.parse_args()
    pcsim_post.need_run_folder(args.out_dir, ("static_mesh.h5",), "pcsim static or pcsim modes")
    mesh_path = os.path.join(args.out_dir, "static_mesh.h5")
    with h5py.File(mesh_path, "r") as f:
        pos = f["/nodes/position"][:]
        cables = f["/cables/connectivity"][:]
        wire_of_cable = f["/cables/wire"][:]
        wire_names = [n.decode() if isinstance(n, bytes) else str(n) for n in f["/wires/name"][:]]
        bars = f["/bars/connectivity"][:] if "/bars/connectivity" in f else np.zeros((0, 2), int)
    summary = {}
    summary_path = os.path.join(args.out_dir, "summary.json")
    if os.path.exists(summary_path):
        with open(summary_path) as fh:
            summary = json.load(fh)
    freqs = summary.get("catenary_frequencies_hz", [])

    fig = plt.figure(figsize=(13, 7.5))
    grid = fig.add_gridspec(2, 2, width_ratios=[4, 1], height_ratios=[2, 1])
    side = fig.add_subplot(grid[0, 0])
    plan = fig.add_subplot(grid[1, 0], sharex=side)
    colors = ["tab:red", "tab:blue", "tab:green", "tab:purple"]
    for w, name in enumerate(wire_names):
        segs = cables[wire_of_cable == w]
        if len(segs) == 0:
            continue
        order = np.argsort(pos[segs[:, 0], 0])
        nodes = np.append(segs[order, 0], segs[order[-1], 1])
        side.plot(pos[nodes, 0], pos[nodes, 2], color=colors[w % 4], lw=1.2, label=f"{name} wire")
        plan.plot(pos[nodes, 0], pos[nodes, 1], color=colors[w % 4], lw=1.2, label=f"{name} wire")
    for a, b in bars:
        side.plot(pos[[a, b], 0], pos[[a, b], 2], color="0.45", lw=0.6)
    side.plot([], [], color="0.45", lw=0.6, label="droppers")
    side.set_ylabel("height z [m]")
    side.set_title(f"Static configuration after form-finding: {summary.get('scene', '')}")
    side.legend(loc="upper right", fontsize=8)
    side.grid(alpha=0.3)
    plan.set_xlabel("x along the track [m]")
    plan.set_ylabel("lateral y [m]")
    plan.set_title("Plan view (stagger)")
    plan.grid(alpha=0.3)

    table_ax = fig.add_subplot(grid[:, 1])
    table_ax.axis("off")
    if freqs:
        rows = [[str(i + 1), f"{f:.4f}"] for i, f in enumerate(freqs[:20])]
        table = table_ax.table(cellText=rows, colLabels=["mode", "f [Hz]"], loc="upper center")
        table.auto_set_font_size(False)
        table.set_fontsize(8)
        table_ax.set_title("Catenary frequencies (SLEPc)")
    info = []
    if "max_height_error_m" in summary:
        info.append(f"height error {summary['max_height_error_m']:.1e} m")
    if "max_tension_error_rel" in summary:
        info.append(f"tension error {summary['max_tension_error_rel']:.1e}")
    if "dofs" in summary:
        info.append(f"{summary['dofs']} DOFs, {summary.get('ranks', 1)} rank(s)")
    table_ax.text(0.5, 0.02, "\n".join(info), ha="center", va="bottom", fontsize=8,
                  transform=table_ax.transAxes)
    fig.tight_layout()
    output = args.output or os.path.join(args.out_dir, "catenary.png")
    fig.savefig(output, dpi=110)
    print(f"plot_catenary: wrote {output}")


if __name__ == "__main__":
    pcsim_post.main(main)
