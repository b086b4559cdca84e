#!/usr/bin/python3
"""Runs against runs, or runs against a measurement: EN 50318 figures, traces, spectra, inputs.

    compare.py RUN_A [RUN_B ...] [--measurement FILE.csv] [-o DIR] [--labels A,B,...]
               [--max-lag M]

`pcsim compare` calls this script. The first run is the reference: every other source
(run or measurement) gets its differences from it. DIR (default out/compare-A-B) receives
  compare.csv, compare.md  the EN 50318 figures of every pantograph, one column per source,
                           then per other source its difference from the first (absolute, %)
  compare.json             the same figures, the inputs that differ, the measurement's lag
                           and offset
  force_uplift.png         filtered contact force by position, one panel per pantograph, and
                           the largest uplift at every support
  spectra.png              contact force spectrum over the analysis section, one panel per
                           pantograph
  inputs.diff              the composed inputs that differ (scene, design, pantograph models)
  span_extremes.csv        runs on the same supports: every run's largest and smallest filtered
                           force per span of the analysis section, and each other run's
                           difference from the first's (compare.md: where each run's extremes
                           fall, span_extremes.py)
  report.html              all of it in one page
A measurement (docs/assessment.md "Measurements") is filtered like the first run, aligned to
its pantographs by cross-correlation (one lag for the file) and compared with them: each force
column with the run's pantograph it names ('force [N]': the first), each with its offset.
"""
import argparse
import difflib
import json
import os
import sys

import interaction_plots
import measurement as measured
import pcsim_post
import report
import span_extremes

DPI = 110


def folder_label(path):
    base = os.path.basename(os.path.normpath(path))
    return os.path.splitext(base)[0] if base.endswith(".csv") else base


def load_sources(a):
    """The runs, then the measurement aligned to the first run, each with its label."""
    paths = a.runs + ([a.measurement] if a.measurement else [])
    labels = a.labels.split(",") if a.labels else [folder_label(p) for p in paths]
    if len(labels) != len(paths):
        pcsim_post.fail("--labels: %d labels for %d sources" % (len(labels), len(paths)))
    labels = [l if labels.count(l) == 1 else "%s (%d)" % (l, i + 1) for i, l in enumerate(labels)]
    if len(paths) < 2:
        pcsim_post.fail("nothing to compare %s with: give a second run or --measurement FILE.csv"
                        % paths[0])
    sources = [interaction_plots.Run(p, l) for p, l in zip(a.runs, labels)]
    for run in sources:
        if run.summary.get("complete") is False:
            pcsim_post.fail("%s is the result of an interrupted run (no statistics)" % run.folder)
    if a.measurement:
        sources.append(measured.MeasuredRun(measured.Measurement(a.measurement), sources[0],
                                            labels[-1], a.max_lag))
    return sources


def single_pantographs(sources):
    """True if every source has one pantograph: then they are compared whatever their names."""
    return all(len(s.summary["pantographs"]) == 1 for s in sources)


def pantograph_names(sources):
    if single_pantographs(sources):
        return [sources[0].summary["pantographs"][0]["name"]]
    names = []
    for s in sources:
        names += [p["name"] for p in s.summary["pantographs"] if p["name"] not in names]
    return names


def figures_of(source, name, ref, single):
    """{key: assessed figure} of pantograph 'name' of a source ({} if it has no statistics);
    single: every source has one pantograph, compared whatever its name."""
    for p in source.summary["pantographs"]:
        if (p["name"] == name or single) and p.get("complete") is not False:
            return {f["key"]: f for f in pcsim_post.assess(source.summary, p, ref)}
    return {}


def difference(value, reference):
    if value is None or reference is None:
        return None, None
    return value - reference, (100.0 * (value - reference) / abs(reference) if reference else None)


def figure_rows(sources, ref):
    """[{pantograph, key, label, unit, values: [per source], differences: [(abs, %) per other]}]"""
    rows = []
    for name in pantograph_names(sources):
        by_source = [figures_of(s, name, ref, single_pantographs(sources)) for s in sources]
        for f in ref["figures"]:
            values = [b[f["key"]]["value"] if f["key"] in b else None for b in by_source]
            if all(v is None for v in values):
                continue
            rows.append({"pantograph": name, "key": f["key"], "label": f["label"], "unit": f["unit"],
                         "values": values,
                         "differences": [difference(v, values[0]) for v in values[1:]]})
    return rows


def cell(value, unit, signed=False):
    if value is None:
        return ""
    return ("%+.2f" if signed else "%.2f") % value if unit == "%" or abs(value) < 10 else \
        ("%+.1f" if signed else "%.1f") % value


def table_cells(rows, sources):
    """Header and rows of the figures table as text."""
    header = ["pantograph", "figure", "unit"] + [s.label for s in sources]
    for s in sources[1:]:
        header += ["%s - %s" % (s.label, sources[0].label), "%s - %s [%%]" % (s.label, sources[0].label)]
    body = []
    for r in rows:
        line = [r["pantograph"], r["label"], r["unit"]] + [cell(v, r["unit"]) for v in r["values"]]
        for absolute, percent in r["differences"]:
            line += [cell(absolute, r["unit"], True), cell(percent, "%", True)]
        body.append(line)
    return header, body


def runs_of(sources):
    return [s for s in sources if not hasattr(s, "alignment")]


def input_rows(sources):
    """[{role, differs, cells: [per run], contents: [per run]}] of the runs' recorded inputs."""
    recorded = []
    for s in runs_of(sources):
        inputs = (s.summary.get("provenance") or {}).get("inputs") or []
        recorded.append({i["role"]: i for i in inputs})
    roles = []
    for r in recorded:
        roles += [role for role in r if role not in roles]
    rows = []
    for role in roles:
        entries = [r.get(role) for r in recorded]
        hashes = [e["sha256"] if e else None for e in entries]
        rows.append({"role": role, "differs": len(set(hashes)) > 1,
                     "cells": ["%s (%s)" % (os.path.basename(e["path"]), e["sha256"][:12]) if e
                               else "none" for e in entries],
                     "contents": [e.get("content", "") if e else "" for e in entries]})
    return rows


def input_diff(rows, sources):
    """A unified diff of every differing input from the first source's."""
    out, sources = [], runs_of(sources)
    for r in (r for r in rows if r["differs"]):
        for s, content in list(zip(sources, r["contents"]))[1:]:
            out += difflib.unified_diff(r["contents"][0].splitlines(True), content.splitlines(True),
                                        "%s: %s" % (sources[0].label, r["role"]),
                                        "%s: %s" % (s.label, r["role"]))
    return "".join(l if l.endswith("\n") else l + "\n" for l in out)


def markdown(header, body):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(c or " " for c in r) + " |" for r in body]) + "\n"


def measurement_lines(sources):
    m = getattr(sources[-1], "alignment", None)
    if not m:
        return []
    lines = ["Measurement %s against %s: lag %.3f m (searched within %.1f m; mean correlation %.4f of "
             "the filtered forces)%s. Force offset: mean measured minus mean computed over the "
             "analysis section." % (sources[-1].folder, sources[0].label, m["lag_m"], m["max_lag_m"],
                                    m["correlation"], "" if m["covers_section"] else
                                    "; it does not cover the whole analysis section")]
    for p in m["pantographs"]:
        lines.append("Pantograph '%s' (column '%s'): force offset %+.2f N, correlation %.4f, "
                     "its own best lag %.3f m." % (p["name"], p["column"], p["offset_N"],
                                                   p["correlation"], p["lag_alone_m"]))
    return lines


def markdown_page(sources, header, body, inputs, extremes_table=None):
    s0 = sources[0].summary
    text = ["# pcsim compare: %s" % ", ".join(s.label for s in sources), "",
            "Sources: %s." % "; ".join("%s = %s" % (s.label, s.folder) for s in sources),
            "Analysis section %.0f-%.0f m, contact force low-pass %g Hz (of %s)."
            % (s0["analysis"]["from_x"], s0["analysis"]["to_x"], s0["analysis"]["cutoff_hz"],
               sources[0].label), ""]
    text += ["- " + l for l in measurement_lines(sources)]
    text += ["", "## EN 50318 figures", "", markdown(header, body)]
    if extremes_table:
        text += ["## Where the extremes fall", "", extremes_table[0], "",
                 markdown(extremes_table[1], extremes_table[2])]
    text += ["## Inputs", "", markdown(["input", "differs"] + [s.label for s in runs_of(sources)],
                                       [[r["role"], "yes" if r["differs"] else "no"] + r["cells"]
                                        for r in inputs])]
    differ = [r["role"] for r in inputs if r["differs"]]
    text.append("Inputs that differ between the runs: %s.\n" % (", ".join(differ) if differ else "none"))
    return "\n".join(text)


def force_uplift_figure(sources, names):
    """One force panel per pantograph and the largest uplift at the supports, x shared."""
    plt = pcsim_post.pyplot()
    with_uplift = [s for s in sources if len(s.support_x)]
    fig, axes = plt.subplots(len(names) + 1, 1, figsize=(11, 3.2 * (len(names) + 1)), sharex=True,
                             squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        having = [s for s in sources if name in s.pantographs or single_pantographs(sources)]
        interaction_plots.draw_forces(ax, having, [None if single_pantographs(sources) else name])
        ax.set_title("Contact force of '%s' by position" % name)
    interaction_plots.draw_max_uplift(axes[-1, 0], with_uplift)
    axes[-1, 0].set_title("Largest uplift at the supports")
    for ax in axes[:-1, 0]:
        ax.set_xlabel("")
    fig.tight_layout()
    return fig


def spectra_figure(sources, names):
    plt = pcsim_post.pyplot()
    fig, axes = plt.subplots(len(names), 1, figsize=(9, 3.6 * len(names)), squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        single = single_pantographs(sources)
        interaction_plots.draw_spectrum(ax, [s for s in sources if name in s.pantographs or single],
                                        None if single else name)
        ax.set_title("Contact force spectrum of '%s' over the analysis section" % name)
    fig.tight_layout()
    return fig


def report_page(sources, header, body, inputs, diff, images, extremes_table=None):
    parts = ["<p>%s</p>" % report.esc("; ".join("%s = %s" % (s.label, s.folder) for s in sources))]
    parts += ["<p>%s</p>" % report.esc(l) for l in measurement_lines(sources)]
    parts += ["<p>Contents: <a href=\"#figures\">EN 50318 figures</a>, <a href=\"#plots\">plots</a>, "
              "<a href=\"#inputs\">inputs</a>.</p>", "<h2 id=\"figures\">EN 50318 figures</h2>",
              report.table(header, body, [[None] * 3 + ["num"] * (len(h) - 3) for h in body]),
              ] + span_extremes_html(extremes_table) + ["<h2 id=\"plots\">Plots</h2>"] + images
    parts += ["<h2 id=\"inputs\">Inputs</h2>",
              report.table(["input", "differs"] + [s.label for s in runs_of(sources)],
                           [[r["role"], "yes" if r["differs"] else "no"] + r["cells"] for r in inputs],
                           [[None, "fail" if r["differs"] else None] + [None] * len(r["cells"])
                            for r in inputs])]
    if diff:
        parts.append("<details open><summary>the composed inputs that differ</summary><pre>%s</pre>"
                     "</details>" % report.esc(diff))
    for s in sources:
        if s.summary.get("provenance"):
            parts.append("<details><summary>command line of %s</summary><pre>%s</pre></details>"
                         % (report.esc(s.label), report.esc(s.summary["provenance"].get("command_line", ""))))
    return report.page("pcsim compare: %s" % " vs ".join(s.label for s in sources), "\n".join(parts))


def span_extremes_html(table):
    """The table of where the extremes fall (span_extremes.table_cells), as a heading, text and
    table; none without it."""
    if not table:
        return []
    text, header, body = table
    return ["<h2 id=\"extremes\">Where the extremes fall</h2>", "<p>%s</p>" % report.esc(text),
            report.table(header, body, [[None] * 2 + ["num"] * (len(h) - 2) for h in body])]


def output_folder(a):
    folder = a.output or os.path.join("out", "compare-" + "-".join(folder_label(p) for p in
                                                                  a.runs + [a.measurement or ""] if p))
    if os.path.isdir(folder) and set(os.listdir(folder)) - {".pcsim-result"}:
        if not os.path.isfile(os.path.join(folder, ".pcsim-result")):
            pcsim_post.fail("%s holds files that pcsim did not write: give another folder" % folder)
    return folder


def span_extremes_of(sources, names):
    """(csv lines, summary rows, table cells) of where the runs' extremes fall; empty where
    there are fewer than two runs or their supports differ."""
    runs = runs_of(sources)
    if len(runs) < 2 or not span_extremes.comparable(runs):
        return [], [], None
    single = single_pantographs(sources)
    table = span_extremes.span_table(
        runs, names, lambda r, n: next(iter(r.pantographs.values())) if single else r.pantographs.get(n))
    labels = [r.label for r in runs]
    rows = span_extremes.summary_rows(table, labels)
    return span_extremes.csv_lines(table, labels), rows, span_extremes.table_cells(rows, labels[0])


def write_all(folder, files, figures):
    """Writes every file (text, or a figure as PNG); exit 5 if one cannot be written."""
    try:
        os.makedirs(folder, exist_ok=True)
        for name, text in files.items():
            with open(os.path.join(folder, name), "w") as f:
                f.write(text)
        for name, fig in figures.items():
            fig.savefig(os.path.join(folder, name), dpi=DPI)
    except OSError as e:
        print("cannot write in %s: %s" % (folder, e.strerror), file=sys.stderr)
        sys.exit(5)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n\n", 2)[2],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", metavar="RUN", help="pcsim run result folders (the first: reference)")
    ap.add_argument("--measurement", metavar="FILE.csv", help="a measured contact force to compare")
    ap.add_argument("-o", "--output", metavar="DIR", help="output folder (default out/compare-A-B)")
    ap.add_argument("--labels", help="comma-separated names of the sources (default: folder names)")
    ap.add_argument("--max-lag", type=float, metavar="M",
                    help="largest position lag of the measurement searched (m; default half a span)")
    a = ap.parse_args()
    sources = load_sources(a)
    folder = output_folder(a)
    ref = pcsim_post.reference()
    rows = figure_rows(sources, ref)
    header, body = table_cells(rows, sources)
    inputs = input_rows(sources)
    diff = input_diff(inputs, sources)
    names = pantograph_names(sources)
    figures = {"force_uplift.png": force_uplift_figure(sources, names),
               "spectra.png": spectra_figure(sources, names)}
    extremes_csv, extremes_rows, extremes_table = span_extremes_of(sources, names)
    csv_lines = [",".join(header)] + [",".join(c.replace(",", ";") for c in r) for r in body]
    record = {"sources": [{"label": s.label, "path": s.folder,
                           "kind": "measurement" if hasattr(s, "alignment") else "run"} for s in sources],
              "figures": rows, "inputs": [{k: r[k] for k in ("role", "differs", "cells")} for r in inputs],
              "measurement": getattr(sources[-1], "alignment", None), "span_extremes": extremes_rows}
    files = {"compare.csv": "\n".join(csv_lines) + "\n", "compare.md": markdown_page(sources, header, body, inputs, extremes_table),
             "compare.json": json.dumps(record, indent=1) + "\n", "inputs.diff": diff}
    if extremes_csv:
        files["span_extremes.csv"] = "\n".join(extremes_csv) + "\n"
    write_all(folder, files, figures)
    images = [report.image(fig, name[:-4].replace("_", " and ")) for name, fig in figures.items()]
    write_all(folder, {"report.html": report_page(sources, header, body, inputs, diff, images,
                                                  extremes_table)}, {})
    print(files["compare.md"])
    print("compare: wrote %s" % folder)


if __name__ == "__main__":
    pcsim_post.main(main, error_status=2)
