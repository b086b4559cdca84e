#!/usr/bin/python3
"""Plots of a `pcsim sweep` result: every EN 50318 figure against the swept value.

    sweep_plots.py SWEEP_DIR [-o sweep.png] [--x KEY]

Six panels: mean contact force Fm; standard deviation sigma; Fm + 3 sigma and Fm - 3 sigma;
actual maximum and minimum; maximum uplift at a support; loss of contact. The x axis is the
first swept key (or --x); one line per combination of the other swept keys and per
pantograph (a sweep of a case table, `pcsim sweep --cases`: points, one colour per pantograph,
the other keys not held fixed). Where EN 50318 gives acceptance ranges at a case's speed
(meshes/en50318-ranges.json), the range is drawn as a grey bar at that case.
"""
import argparse
import os

import pcsim_post

PANELS = [("mean contact force Fm", ["mean_N"]), ("standard deviation sigma", ["std_N"]),
          ("Fm + 3 sigma, Fm - 3 sigma", ["stat_max_N", "stat_min_N"]),
          ("actual maximum, minimum", ["max_N", "min_N"]),
          ("maximum uplift at a support", ["uplift_mm"]), ("loss of contact", ["loss_of_contact_percent"])]


def numeric(values):
    try:
        return [float(v) for v in values]
    except ValueError:
        return None


def series(summary, x_key, ref):
    """{label: [(x, case speed, {figure key: value})]} over the successful cases."""
    table = "cases_table" in summary
    out = {}
    for case in summary["cases"]:
        s = case.get("summary")
        if case["status"] != 0 or not s:
            continue
        others = "" if table else ", ".join("%s=%s" % (k, v) for k, v in case["values"].items()
                                            if k != x_key)
        for p in s.get("pantographs", []):
            if p.get("complete") is False:
                continue
            label = ", ".join(t for t in (others, p["name"] if len(s["pantographs"]) > 1 else "") if t)
            figures = {f["key"]: f["value"] for f in pcsim_post.assess(s, p, ref)}
            judged = s.get("assessment", {}).get("pantographs", {}).get(p["name"], {})
            failed = {c["figure"] for c in judged.get("criteria", []) if c.get("verdict") == "fail"}
            out.setdefault(label, []).append((case["values"][x_key], s.get("speed_kmh", 0.0), figures,
                                              failed))
    return out


def draw_range(ax, x, rng, label):
    """An acceptance range at x: a grey bar (a thick tick for a range of one value, e.g. 0 %)."""
    if rng[1] > rng[0]:
        ax.plot([x, x], rng, lw=9, color="0.5", alpha=0.35, solid_capstyle="butt", zorder=0, label=label)
    else:
        ax.plot([x], [rng[0]], marker="_", ms=18, mew=4, color="0.5", alpha=0.5, ls="none", zorder=0,
                label=label)


def sweep_figure(summary, x_key=None, ref=None):
    plt = pcsim_post.pyplot()
    ref = ref or pcsim_post.reference()
    keys = list(summary["swept"])
    x_key = x_key or keys[0]
    if x_key not in summary["swept"]:
        pcsim_post.fail("--x %s: not a swept key (swept: %s)" % (x_key, ", ".join(keys)))
    order = summary["swept"][x_key]
    as_numbers = numeric(order)
    position = (lambda v: float(v)) if as_numbers else (lambda v: order.index(v))
    units = {f["key"]: f["unit"] for f in ref["figures"]}
    lines = series(summary, x_key, ref)
    fig, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    for ax, (title, fig_keys) in zip(axes.flat, PANELS):
        drawn, fail_shown = set(), False
        for k, (label, points) in enumerate(sorted(lines.items())):
            points.sort(key=lambda p: position(p[0]))
            xs = [position(p[0]) for p in points]
            for j, key in enumerate(fig_keys):
                ys = [p[2].get(key) for p in points]
                style = ("o" if j == 0 else "s") if "cases_table" in summary else ("o-" if j == 0 else "s--")
                ax.plot(xs, ys, style, ms=4, color="C%d" % k,
                        label=(label or "pcsim") if j == 0 else None)
                bad = [(x, y) for x, y, p in zip(xs, ys, points) if key in p[3] and y is not None]
                if bad:  # a criterion of the case's set fails on this figure
                    ax.plot(*zip(*bad), "x", ms=9, mew=2, color="red", ls="none",
                            label=None if fail_shown else "fails its criteria set")
                    fail_shown = True
                for x, (_, speed, _, _) in zip(xs, points):
                    rng = (pcsim_post.ranges_at(ref, speed) or {}).get(key)
                    if rng and (x, key) not in drawn:
                        draw_range(ax, x, rng, None if drawn else "%s range" % ref["edition"])
                        drawn.add((x, key))
        ax.set_title("%s (%s)" % (title, units[fig_keys[0]]), fontsize=10)
        ax.set_xlabel(x_key)
        ax.grid(alpha=0.3)
        if not as_numbers:
            ax.set_xticks(range(len(order)), order)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    axes.flat[0].legend(handles, labels, fontsize=7)
    title = "EN 50318 figures of the sweep of %s" % ", ".join(keys)
    highest = summary.get("highest_passing_speed_kmh")
    if highest:
        title += "; highest speed every case passes up to: " + ", ".join(
            "%s %s" % (p, "none" if v is None else "%g km/h" % v) for p, v in highest.items())
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n\n", 2)[2],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sweep", metavar="SWEEP_DIR", help="pcsim sweep result folder")
    ap.add_argument("-o", "--output", help="PNG file (default: SWEEP_DIR/sweep.png)")
    ap.add_argument("--x", metavar="KEY", help="swept key on the x axis (default: the first)")
    a = ap.parse_args()
    pcsim_post.need_run_folder(a.sweep, ("summary.json",), "pcsim sweep")
    summary = pcsim_post.load_json(os.path.join(a.sweep, "summary.json"))
    if "swept" not in summary:
        pcsim_post.fail("%s is not a pcsim sweep result (its summary.json has no 'swept')" % a.sweep)
    output = a.output or os.path.join(a.sweep, "sweep.png")
    sweep_figure(summary, a.x).savefig(output, dpi=100)
    print("sweep_plots: wrote %s" % output)


if __name__ == "__main__":
    pcsim_post.main(main)
