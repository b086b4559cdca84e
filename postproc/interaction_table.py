#!/usr/bin/python3
"""EN 50318 table of `pcsim run` results: ours beside the acceptance range.

    interaction_table.py OUT_DIR|summary.json [...] [--markdown] [--no-ranges]
                         [--labels A,B,...] [--pantograph NAME] [--change]

Each argument is a run's output folder (or its summary.json). One column per run (and
per pantograph when a run has several). With ranges (default), each value is followed by
a mark: `ok` inside the EN 50318 range of the run's speed (250 or 300 km/h), `OUT`
outside; runs at other speeds get no marks. Exit status 0 whatever the marks are.
"""
import argparse
import json
import os
import sys

# EN 50318:2002 acceptance ranges (shared/reference/en50318-reference-case.md).
RANGES = {
    250: {"mean_N": (110, 120), "std_N": (26, 31), "stat_max_N": (190, 210),
          "stat_min_N": (20, 40), "max_N": (175, 210), "min_N": (50, 75),
          "uplift_mm": (48, 55), "loss_of_contact_percent": (0, 0)},
    300: {"mean_N": (110, 120), "std_N": (32, 40), "stat_max_N": (210, 230),
          "stat_min_N": (-5, 20), "max_N": (190, 225), "min_N": (30, 55),
          "uplift_mm": (55, 65), "loss_of_contact_percent": (0, 0)},
}
ROWS = [("mean_N", "mean Fm (N)", "%.1f"), ("std_N", "std dev s (N)", "%.1f"),
        ("stat_max_N", "Fm + 3s (N)", "%.1f"), ("stat_min_N", "Fm - 3s (N)", "%.1f"),
        ("max_N", "actual max (N)", "%.1f"), ("min_N", "actual min (N)", "%.1f"),
        ("uplift_mm", "max uplift (mm)", "%.1f"),
        ("loss_of_contact_percent", "loss of contact (%)", "%.2f")]


def load(path):
    if os.path.isdir(path):
        path = os.path.join(path, "summary.json")
    with open(path) as f:
        return json.load(f)


def columns(paths, labels, only):
    cols = []
    for i, path in enumerate(paths):
        s = load(path)
        base = labels[i] if labels else s.get("scene", os.path.basename(path.rstrip("/")))
        pants = [p for p in s["pantographs"] if only is None or p["name"] == only]
        for p in pants:
            values = dict(p)
            values["uplift_mm"] = 1e3 * s["max_uplift_at_support_m"]
            label = base if len(s["pantographs"]) == 1 else "%s/%s" % (base, p["name"])
            cols.append((label, round(s["speed_kmh"]), values))
    return cols


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", help="output folders or summary.json files")
    ap.add_argument("--markdown", action="store_true", help="Markdown table")
    ap.add_argument("--no-ranges", action="store_true", help="values only, no EN 50318 ranges")
    ap.add_argument("--labels", help="comma-separated column labels (one per run)")
    ap.add_argument("--pantograph", help="only this pantograph")
    ap.add_argument("--change", action="store_true",
                    help="append to every column after the first its change vs the first (%%)")
    a = ap.parse_args()
    labels = a.labels.split(",") if a.labels else None
    if labels and len(labels) != len(a.runs):
        sys.exit("--labels: %d labels for %d runs" % (len(labels), len(a.runs)))
    cols = columns(a.runs, labels, a.pantograph)
    if not cols:
        sys.exit("no pantograph matched")
    speeds = sorted({c[1] for c in cols if c[1] in RANGES})
    show_ranges = not a.no_ranges and speeds
    header = ["quantity"]
    if show_ranges:
        header += ["EN 50318 %d km/h" % v for v in speeds]
    header += [c[0] if "km/h" in c[0] else "%s (%d km/h)" % (c[0], c[1]) for c in cols]
    table = [header]
    n_out = 0
    for key, name, fmt in ROWS:
        row = [name]
        if show_ranges:
            row += ["%g - %g" % RANGES[v][key] if key != "loss_of_contact_percent" else "0"
                    for v in speeds]
        for label, speed, values in cols:
            cell = fmt % values[key]
            ref = cols[0][2][key]
            if a.change and values is not cols[0][2]:
                cell += " (%+.1f%%)" % (100 * (values[key] - ref) / abs(ref)) if ref else " (-)"
            if show_ranges and speed in RANGES:
                lo, hi = RANGES[speed][key]
                inside = lo - 1e-9 <= values[key] <= hi + 1e-9
                n_out += not inside
                cell += " ok" if inside else " OUT"
            row.append(cell)
        table.append(row)
    if a.markdown:
        print("| " + " | ".join(table[0]) + " |")
        print("|" + "---|" * len(table[0]))
        for r in table[1:]:
            print("| " + " | ".join(r) + " |")
    else:
        widths = [max(len(r[i]) for r in table) for i in range(len(header))]
        for k, r in enumerate(table):
            print("  ".join(c.ljust(w) if i == 0 else c.rjust(w)
                            for i, (c, w) in enumerate(zip(r, widths))))
            if k == 0:
                print("  ".join("-" * w for w in widths))
    if show_ranges:
        print("%s%d value(s) outside the EN 50318 ranges" % ("\n" if a.markdown else "", n_out))


if __name__ == "__main__":
    main()
