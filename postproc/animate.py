#!/usr/bin/python3
"""GIF animation of a `pcsim run` with snapshots: the wires and the pantographs, side view.

    animate.py RUN_DIR [-o RUN_DIR/animation.gif] [--scale 1] [--fps 10] [--max-frames 200]
               [--xlim X0 X1]

The run needs snapshots (scene: output.snapshot_every > 0). Each frame draws the wires
(static mesh static_mesh.h5 plus the snapshot's displacements, vertical displacements
multiplied by --scale) and every pantograph at its contact point. Needs matplotlib and
Pillow (Debian: python3-matplotlib python3-pil).
"""
import argparse
import os

import numpy as np

import pcsim_post


def read_snapshots(results):
    """(times, displacements k x n x 3) of results.h5 (/snapshots/time and
    /snapshots/displacement: docs/results-format.md)."""
    if "/snapshots/time" not in results:
        pcsim_post.fail("the run has no snapshots (set output.snapshot_every > 0 in the scene)")
    times = results["/snapshots/time"][()]
    return times, results["/snapshots/displacement"]


def read_mesh(path):
    import h5py
    with h5py.File(pcsim_post.need_file(path, "mesh file"), "r") as f:
        bars = f["/bars/connectivity"][()] if "/bars/connectivity" in f else np.zeros((0, 2), int)
        kinds = f["/wires/kind"][()]  # messenger 0, contact 1, stitch 2, other 3
        contact = int(np.flatnonzero(kinds == 1)[0]) if np.any(kinds == 1) else len(kinds) - 1
        return f["/nodes/position"][()], f["/cables/connectivity"][()], f["/cables/wire"][()], bars, contact


def wire_paths(cables, wire_of_cable, position):
    """{wire: its nodes in x order}."""
    paths = {}
    for w in np.unique(wire_of_cable):
        nodes = np.unique(cables[wire_of_cable == w].ravel())
        paths[int(w)] = nodes[np.argsort(position[nodes, 0])]
    return paths


def animate(folder, output, scale, fps, max_frames, xlim):
    import h5py
    from matplotlib.animation import FuncAnimation, PillowWriter
    plt = pcsim_post.pyplot()
    position, cables, wire_of_cable, bars, contact = read_mesh(os.path.join(folder, "static_mesh.h5"))
    results = h5py.File(os.path.join(folder, "results.h5"), "r")
    times, displacements = read_snapshots(results)
    t = results["/time"][()]
    pantographs = {name: (results["/pantographs/%s/position" % name][()],
                          results["/pantographs/%s/wire_height" % name][()])
                   for name in results["/pantographs"]}
    frames = np.unique(np.linspace(0, len(times) - 1, min(len(times), max_frames)).astype(int))
    paths = wire_paths(cables, wire_of_cable, position)
    contact_nodes = paths[contact]
    fig, ax = plt.subplots(figsize=(11, 3.6))
    lines = {w: ax.plot([], [], lw=1.0)[0] for w in paths}
    bar_lines = ax.plot([], [], color="0.55", lw=0.5)[0]
    heads = {name: ax.plot([], [], "^", ms=10, label=name)[0] for name in pantographs}
    ax.set_xlim(*(xlim or (position[:, 0].min(), position[:, 0].max())))
    z = position[:, 2]
    ax.set_ylim(z.min() - 0.3, z.max() + 0.3)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)%s" % (", displacements x %g" % scale if scale != 1 else ""))
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    title = ax.set_title("t = 0 s")

    def draw(k):
        d = np.asarray(displacements[frames[k]])
        p = position + d * np.array([1.0, 1.0, scale])
        for w, nodes in paths.items():
            lines[w].set_data(p[nodes, 0], p[nodes, 2])
        xs = np.column_stack([p[bars, 0], np.full(len(bars), np.nan)]).ravel()
        zs = np.column_stack([p[bars, 2], np.full(len(bars), np.nan)]).ravel()
        bar_lines.set_data(xs, zs)
        i = min(np.searchsorted(t, times[frames[k]]), len(t) - 1)
        for name, (x, zw) in pantographs.items():
            static_z = np.interp(x[i], position[contact_nodes, 0], position[contact_nodes, 2])
            heads[name].set_data([x[i]], [static_z + scale * (zw[i] - static_z)])
        title.set_text("%s, t = %.3f s" % (os.path.basename(folder.rstrip("/")), times[frames[k]]))
        return list(lines.values()) + [bar_lines, title] + list(heads.values())

    fig.tight_layout()
    FuncAnimation(fig, draw, frames=len(frames), blit=False).save(output, writer=PillowWriter(fps=fps))
    print("animate: wrote %s (%d frames)" % (output, len(frames)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n\n", 2)[2],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", metavar="RUN_DIR", help="pcsim run result folder with snapshots")
    ap.add_argument("-o", "--output", help="GIF file (default: RUN_DIR/animation.gif)")
    ap.add_argument("--scale", type=float, default=1.0, help="factor on the vertical displacements (1)")
    ap.add_argument("--fps", type=int, default=10, help="frames per second of the GIF (10)")
    ap.add_argument("--max-frames", type=int, default=200, help="at most this many frames (200)")
    ap.add_argument("--xlim", type=float, nargs=2, metavar=("X0", "X1"), help="x range shown (m)")
    a = ap.parse_args()
    pcsim_post.need_run_folder(a.run, ("results.h5", "static_mesh.h5"))
    try:
        import PIL  # noqa: F401
    except ImportError:
        pcsim_post.fail("Pillow is not installed for the GIF writer (Debian: python3-pil)")
    animate(a.run, a.output or os.path.join(a.run, "animation.gif"), a.scale, a.fps, a.max_frames,
            a.xlim)


if __name__ == "__main__":
    pcsim_post.main(main)
