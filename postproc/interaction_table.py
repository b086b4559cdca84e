#!/usr/bin/python3
"""EN 50318 table of `pcsim run` results: ours beside the acceptance range.

    interaction_table.py OUT_DIR|summary.json [...] [--markdown] [--no-ranges]
                         [--labels A,B,...] [--pantograph NAME] [--change]

Each argument is a run's output folder (or its summary.json). One column per run (and
per pantograph when a run has several). With ranges (default), each value is followed by
a mark: `ok` inside the EN 50318 range of the run's speed, `OUT` outside; runs at speeds
without ranges get no marks. The figures and ranges are those of meshes/en50318-ranges.json
(EN 50318:2002 at 250 and 300 km/h), the file pcsim itself reads. Exit status 0 whatever the
marks are.
"""
import argparse
import os

import pcsim_post


def load(path):
    if os.path.isdir(path):
        path = os.path.join(path, "summary.json")
    if not os.path.isfile(path):
        pcsim_post.fail("%s not found (give pcsim run result folders or their summary.json)" % path)
    return pcsim_post.load_json(path)


def columns(paths, labels, only, ref):
    cols = []
    for i, path in enumerate(paths):
        s = load(path)
        base = labels[i] if labels else s.get("scene", os.path.basename(path.rstrip("/")))
        pants = [p for p in s["pantographs"] if only is None or p["name"] == only]
        for p in pants:
            if p.get("complete") is False:
                continue
            values = {f["key"]: f["value"] for f in pcsim_post.assess(s, p, ref)}
            label = base if len(s["pantographs"]) == 1 else "%s/%s" % (base, p["name"])
            cols.append((label, s["speed_kmh"], values))
    return cols


def print_table(table, markdown):
    if markdown:
        print("| " + " | ".join(table[0]) + " |")
        print("|" + "---|" * len(table[0]))
        for r in table[1:]:
            print("| " + " | ".join(r) + " |")
        return
    widths = [max(len(r[i]) for r in table) for i in range(len(table[0]))]
    for k, r in enumerate(table):
        print("  ".join(c.ljust(w) if i == 0 else c.rjust(w)
                        for i, (c, w) in enumerate(zip(r, widths))))
        if k == 0:
            print("  ".join("-" * w for w in widths))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", metavar="RUN", help="pcsim run output folders or summary.json files")
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    ap.add_argument("--no-ranges", action="store_true", help="values only, no EN 50318 ranges")
    ap.add_argument("--labels", help="comma-separated column labels, one per run (default: scene names)")
    ap.add_argument("--pantograph", metavar="NAME", help="only this pantograph (default: all)")
    ap.add_argument("--change", action="store_true",
                    help="append to every column after the first its change vs the first (%%)")
    a = ap.parse_args()
    labels = a.labels.split(",") if a.labels else None
    if labels and len(labels) != len(a.runs):
        pcsim_post.fail("--labels: %d labels for %d runs" % (len(labels), len(a.runs)))
    ref = pcsim_post.reference()
    cols = columns(a.runs, labels, a.pantograph, ref)
    if not cols:
        pcsim_post.fail("no pantograph with statistics matched")
    speeds = sorted({round(c[1]) for c in cols if pcsim_post.ranges_at(ref, c[1])})
    show_ranges = not a.no_ranges and speeds
    header = ["quantity"]
    if show_ranges:
        header += ["%s %d km/h" % (ref["edition"], v) for v in speeds]
    header += [c[0] if "km/h" in c[0] else "%s (%d km/h)" % (c[0], round(c[1])) for c in cols]
    table = [header]
    n_out = 0
    for f in ref["figures"]:
        key, fmt = f["key"], "%.2f" if f["unit"] == "%" else "%.1f"
        row = ["%s (%s)" % (f["label"], f["unit"])]
        if show_ranges:
            row += ["%g - %g" % pcsim_post.ranges_at(ref, v)[key] for v in speeds]
        for label, speed, values in cols:
            cell = fmt % values[key]
            ref_value = cols[0][2][key]
            if a.change and values is not cols[0][2]:
                cell += " (%+.1f%%)" % (100 * (values[key] - ref_value) / abs(ref_value)) if ref_value else " (-)"
            ranges = pcsim_post.ranges_at(ref, speed)
            if show_ranges and ranges:
                lo, hi = ranges[key]
                inside = lo - 1e-9 <= values[key] <= hi + 1e-9
                n_out += not inside
                cell += " ok" if inside else " OUT"
            row.append(cell)
        table.append(row)
    print_table(table, a.markdown)
    if show_ranges:
        print("%s%d value(s) outside the %s ranges" % ("\n" if a.markdown else "", n_out, ref["edition"]))


if __name__ == "__main__":
    pcsim_post.main(main)
