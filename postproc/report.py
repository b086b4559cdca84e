#!/usr/bin/python3
"""Self-contained HTML report of a `pcsim run` or `pcsim sweep` result.

    report.py run   RUN_DIR   [-o RUN_DIR/report.html]
    report.py sweep SWEEP_DIR [-o SWEEP_DIR/report.html]

run:   the EN 50318 table of every pantograph (figure, unit, value, range, verdict), the
       contact force, its spectrum and the uplift at the supports, the run's facts
       (steps, Newton iterations, times), its accuracy estimate (the pilot's estimated
       errors per figure, those it measured beyond their targets marked, or the
       calibrated criteria), its inputs (the composed scene, the overrides,
       the scene file as written) and its provenance.
sweep: the swept keys and values, the EN 50318 figures of every case with their
       verdicts, the figures plotted against the swept values, failed cases with the end
       of their logs, and the provenance.
Plots are embedded as base64 PNG images; the page references no other file.
"""
import argparse
import base64
import html
import io
import os
import sys

import pcsim_post

STYLE = """
body { font-family: sans-serif; margin: 2em auto; max-width: 1150px; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; margin: 0.5em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.pass { background: #e3f4e1; } td.fail { background: #f9dcdc; font-weight: bold; }
pre { background: #f6f6f6; padding: 0.6em; overflow-x: auto; font-size: 0.85em; }
img { max-width: 100%; }
"""


def esc(value):
    return html.escape(str(value))


def table(header, rows, classes=None):
    """rows: lists of cells; classes: per row, per cell CSS class (or None)."""
    out = ["<table>", "<tr>" + "".join("<th>%s</th>" % esc(h) for h in header) + "</tr>"]
    for i, row in enumerate(rows):
        cls = classes[i] if classes else [None] * len(row)
        out.append("<tr>" + "".join("<td%s>%s</td>" % (' class="%s"' % c if c else "", esc(v))
                                    for v, c in zip(row, cls)) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def image(fig, alt):
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=90)
    pcsim_post.pyplot().close(fig)
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    return '<p><img alt="%s" src="data:image/png;base64,%s"></p>' % (esc(alt), data)


def number(v, unit=""):
    return ("%.2f" % v if unit == "%" else "%.1f" % v) if isinstance(v, (int, float)) else str(v)


def figures_table(figures):
    ranges = any(f["range"] for f in figures)
    header = ["figure", "unit", "value"] + (["range", "verdict"] if ranges else [])
    rows, classes = [], []
    for f in figures:
        row = [f["label"], f["unit"], number(f["value"], f["unit"])]
        cls = [None, None, "num"]
        if ranges:
            row += ["%g .. %g" % tuple(f["range"]) if f["range"] else "", f["verdict"] or ""]
            cls += ["num", f["verdict"]]
        rows.append(row)
        classes.append(cls)
    return table(header, rows, classes)


def criteria_table(pantograph):
    """One pantograph's verdicts under a criteria set (summary.json 'assessment')."""
    rows, classes = [], []
    for c in pantograph["criteria"]:
        rows.append([c["label"], c["unit"], number(c["value"], c["unit"]), c["limit"], c["verdict"],
                     c["clause"]])
        classes.append([None, None, "num", "num", c["verdict"], None])
    rows.append(["overall", "", "", "", pantograph["verdict"], ""])
    classes.append([None, None, None, None, pantograph["verdict"], None])
    return table(["figure", "unit", "value", "limit", "verdict", "clause"], rows, classes)


# The pilot's figures (summary.json accuracy_estimate.pilot; docs/fidelity.md): key,
# label and unit on the page.
PILOT_FIGURES = list(zip(pcsim_post.PILOT_KEYS,
                         ["mean", "sigma", "Fm+3sigma", "actual maximum", "uplift", "Fm-3sigma",
                          "actual minimum", "loss of contact"],
                         ["%"] * 5 + ["% of Fm"] * 2 + ["points"]))


def pilot_tables(pilot):
    """Per pantograph: each figure's estimated discretisation (and reduction) error; a
    cell is marked where the pilot measured that error beyond the figure's target."""
    kinds = ["discretisation"] + (["reduction"] if pilot.get("reduction") else [])
    beyond = {(o["pantograph"], o["figure"], kind) for kind in kinds
              for o in pilot.get(kind + "_outside_targets", [])}
    parts = []
    for i, d in enumerate(pilot["discretisation"]):
        name = d["pantograph"]
        estimates = [pilot[kind][i] for kind in kinds]
        rows = [[label, unit] + ["%.2f" % e[key] for e in estimates]
                for key, label, unit in PILOT_FIGURES]
        classes = [[None, None] + ["fail" if (name, key, kind) in beyond else "num"
                                   for kind in kinds] for key, _, _ in PILOT_FIGURES]
        parts += ["<h3>%s</h3>" % esc(name),
                  table(["figure", "unit"] + ["%s estimate" % k for k in kinds], rows, classes)]
    return parts


def accuracy_section(estimate):
    """The run's accuracy estimate: its pilot's table, or the calibrated criteria."""
    parts = ["<h2 id=\"accuracy\">Accuracy estimate</h2>"]
    if not estimate:
        return parts[0] + "<p>none recorded</p>"
    pilot = estimate.get("pilot")
    if pilot:
        cutoff = (", the modal level's reduction against linear FE at the same dt and h "
                  "(cut-off %.1f Hz)" % pilot["cutoff_hz"]) if pilot.get("reduction") else ""
        parts.append("<p>%s</p>" % esc(
            "From the pilot's runs over x %.0f-%.0f m%s: the discretisation against converged "
            "linear FE%s. An estimate is %g times the pilot's difference, at least %g (%g points "
            "for the loss of contact). Marked: a figure the pilot measured beyond its target "
            "(docs/fidelity.md)." % (pilot["from_x"], pilot["to_x"],
                                      " (cached)" if pilot.get("cached") else "", cutoff,
                                      pilot["safety_factor"], pilot["floor"],
                                      pilot["loss_of_contact_floor"])))
        parts += pilot_tables(pilot)
        outside = estimate.get("extremes_outside_pilot") or []
        if outside:
            parts.append("<p>%s</p>" % esc("Outside the pilot's stretch (estimated from its "
                                           "spans): " + ", ".join(
                "%s of '%s' at x = %.1f m" % (e["figure"], e["pantograph"], e["at_x_m"])
                for e in outside) + "."))
        return "\n".join(parts)
    rows, classes = [], []
    for c in estimate.get("criteria", []):
        rows.append([c["name"], "%.2f" % c["value"], c["measure"], "%.2f" % c["converged_min"],
                     "%.1f" % c["estimated_sigma_error_percent"],
                     "inside" if c["ok"] else "OUTSIDE", "" if c["ok"] else c["advice"]])
        classes.append([None, "num", None, "num", "num", "pass" if c["ok"] else "fail", None])
    parts.append("<p>Calibrated criteria (no pilot ran: docs/fidelity.md, \"Calibrated "
                 "criteria\").</p>")
    parts.append(table(["criterion", "value", "measure", "converged at or above",
                        "sigma error ~ %", "region", "advice"], rows, classes))
    return "\n".join(parts)


def provenance_section(p):
    if not p:
        return "<h2 id=\"provenance\">Provenance</h2><p>none recorded</p>"
    rows = [[k, p.get(k, "")] for k in ("pcsim_version", "git_commit", "command_line", "petsc_options",
                                        "ranks", "date", "host")]
    return "<h2 id=\"provenance\">Provenance</h2>" + table(["", ""], rows)


def inputs_section(p):
    if not p:
        return ""
    parts = ["<h2 id=\"inputs\">Inputs</h2>", "<p>scene file: %s</p>" % esc(p.get("scene_file", ""))]
    overrides = p.get("overrides") or []
    parts.append("<p>overrides: %s</p>" % (esc(", ".join("--set " + o for o in overrides)) or "none"))
    parts.append("<p>the scene as read (with its base files and overrides):</p>")
    parts.append("<pre>%s</pre>" % esc(p.get("resolved_scene", "")))
    parts.append("<details><summary>the scene file as written</summary><pre>%s</pre></details>"
                 % esc(p.get("scene_text", "")))
    return "\n".join(parts)


def page(title, body):
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>%s</title>"
            "<style>%s</style></head>\n<body>\n<h1>%s</h1>\n%s\n</body></html>\n"
            % (esc(title), STYLE, esc(title), body))


def run_report(folder):
    import interaction_plots
    run = interaction_plots.Run(folder)
    s, ref = run.summary, pcsim_post.reference()
    ranges = pcsim_post.ranges_at(ref, s["speed_kmh"])
    body = ["<p>%s at %.0f km/h; analysis section %.0f-%.0f m, contact force low-pass %g Hz.</p>"
            % (esc(", ".join(p["name"] for p in s["pantographs"])), s["speed_kmh"],
               s["analysis"]["from_x"], s["analysis"]["to_x"], s["analysis"]["cutoff_hz"]),
            "<p>Contents: <a href=\"#en50318\">EN 50318 figures</a>, <a href=\"#plots\">plots</a>, "
            "<a href=\"#facts\">run</a>, <a href=\"#accuracy\">accuracy estimate</a>, "
            "<a href=\"#inputs\">inputs</a>, "
            "<a href=\"#provenance\">provenance</a>.</p>",
            "<h2 id=\"en50318\">EN 50318 figures</h2>",
            "<p>%s</p>" % esc("Acceptance ranges of %s at %.0f km/h." % (ref["edition"], s["speed_kmh"])
                              if ranges else "%s gives acceptance ranges at %s km/h only: values "
                              "without verdict." % (ref["edition"], " and ".join(
                                  "%g" % v for v in sorted(ref["ranges"]))))]
    a = s.get("assessment")
    if a:  # the criteria set the run was judged against (docs/assessment.md)
        body.append("<p>%s</p>" % esc("Criteria set %s: %s (%s; %s)." % (
            a["criteria"], a["title"], a["choice"], a["file"])))
    judged = a and a["criteria"] != "en50318-2002"
    if judged:
        body[body.index("<h2 id=\"en50318\">EN 50318 figures</h2>") + 1] = (
            "<p>%s</p>" % esc("%s, %s line at %.0f km/h. \"unverified\": a value not checked "
                              "against its source, never pass or fail." % (
                                  a["scope"], a["electrification"], a["line_speed_kmh"])))
    for p in s["pantographs"]:
        body.append("<h3>%s</h3>" % esc(p["name"]))
        if p.get("complete") is False:
            body.append("<p>did not cross the analysis section: no statistics</p>")
            continue
        if judged:
            body.append(criteria_table(a["pantographs"][p["name"]]))
        else:
            body.append(figures_table(pcsim_post.assess(s, p, ref)))
    body.append("<h2 id=\"plots\">Plots</h2>")
    # One force and one spectrum panel per pantograph (several overlaid over
    # the whole line cannot be read), then the uplift at the supports.
    names = [p["name"] for p in s["pantographs"]]
    plots = []
    for name in names:
        tag = " of '%s'" % name if len(names) > 1 else ""
        plots += [(lambda n=name, t=tag: interaction_plots.force_figure(
                      [run], n, title="Contact force%s" % t), "contact force" + tag),
                  (lambda n=name, t=tag: interaction_plots.spectrum_figure(
                      [run], n, title="Contact force spectrum%s over the analysis section" % t),
                   "contact force spectrum" + tag)]
    plots.append((lambda: interaction_plots.uplift_figure([run]), "uplift at the supports"))
    for make, alt in plots:
        try:
            body.append(image(make(), alt))
        except pcsim_post.ScriptError as e:  # e.g. a run cut short: no spectrum
            body.append("<p>no %s plot: %s</p>" % (esc(alt), esc(e)))
    facts = [[k, "%.4g" % s[k] if isinstance(s[k], float) else s[k]] for k in
             ("steps", "newton_iterations_per_step", "wall_time_s", "time_per_step_ms",
              "simulated_time_s", "real_time_factor", "peak_memory_mb", "ranks", "dofs", "path")
             if k in s]
    body += ["<h2 id=\"facts\">Run</h2>", table(["", ""], facts)]
    body.append(accuracy_section(s.get("accuracy_estimate")))
    body += [inputs_section(s.get("provenance")), provenance_section(s.get("provenance"))]
    return page("pcsim run: %s" % s.get("scene", os.path.basename(folder.rstrip("/"))), "\n".join(body))


def log_tail(folder, case, lines=8):
    path = os.path.join(folder, "cases", case + ".log")
    if not os.path.isfile(path):
        return ""
    with open(path, errors="replace") as f:
        return "".join(f.readlines()[-lines:])


def sweep_rows(summary, ref):
    keys = list(summary["swept"])
    rows, classes = [], []
    for case in summary["cases"]:
        s = case.get("summary")
        ok = case["status"] == 0 and s
        pants = s.get("pantographs", []) if ok else [None]
        for p in pants:
            figures = pcsim_post.assess(s, p, ref) if p and p.get("complete") is not False else []
            by_key = {f["key"]: f for f in figures}
            row = [case["name"]] + [case["values"].get(k, "") for k in keys]
            row += [p["name"] if p else "", "ok" if ok else "failed (exit %d)" % case["status"]]
            cls = [None] * (len(keys) + 2) + [None if ok else "fail"]
            for f in ref["figures"]:
                a = by_key.get(f["key"])
                row.append(number(a["value"], a["unit"]) + (" " + a["verdict"] if a["verdict"] else "")
                           if a else "")
                cls.append(a["verdict"] if a else None)
            rows.append(row)
            classes.append(cls)
    return rows, classes


def sweep_report(folder):
    import sweep_plots
    summary = pcsim_post.load_json(os.path.join(folder, "summary.json"))
    if "swept" not in summary:
        pcsim_post.fail("%s is not a pcsim sweep result (its summary.json has no 'swept')" % folder)
    ref = pcsim_post.reference()
    keys = list(summary["swept"])
    failed = [c for c in summary["cases"] if c["status"] != 0]
    body = ["<p>%d cases over %s; %d failed.</p>" % (len(summary["cases"]), esc(", ".join(keys)),
                                                   len(failed)),
            "<p>Contents: <a href=\"#cases\">EN 50318 figures of the cases</a>, "
            "<a href=\"#plots\">plots</a>, <a href=\"#inputs\">inputs</a>, "
            "<a href=\"#provenance\">provenance</a>.</p>",
            "<h2 id=\"swept\">Swept values</h2>",
            table(["key", "values"], [[k, ", ".join(v)] for k, v in summary["swept"].items()])]
    rows, classes = sweep_rows(summary, ref)
    header = ["case"] + keys + ["pantograph", "status"] + ["%s (%s)" % (f["label"], f["unit"])
                                                         for f in ref["figures"]]
    body += ["<h2 id=\"cases\">EN 50318 figures of the cases</h2>",
             "<p>Verdicts against the %s ranges where the standard gives them (%s km/h).</p>"
             % (esc(ref["edition"]), " and ".join("%g" % v for v in sorted(ref["ranges"]))),
             table(header, rows, classes), "<h2 id=\"plots\">Plots</h2>"]
    if any(c["status"] == 0 for c in summary["cases"]):
        body.append(image(sweep_plots.sweep_figure(summary, ref=ref), "EN 50318 figures against "
                          + keys[0]))
    for c in failed:
        body.append("<h3>case %s failed (exit %d)</h3><pre>%s</pre>"
                    % (esc(c["name"]), c["status"], esc(log_tail(folder, c["name"]))))
    body += [inputs_section(summary.get("provenance")), provenance_section(summary.get("provenance"))]
    return page("pcsim sweep: %s" % summary.get("provenance", {}).get("scene_file", folder), "\n".join(body))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n\n", 2)[2],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("kind", choices=("run", "sweep"), help="what the folder holds")
    ap.add_argument("folder", metavar="FOLDER", help="a pcsim run or pcsim sweep result folder")
    ap.add_argument("-o", "--output", help="HTML file (default: FOLDER/report.html)")
    a = ap.parse_args()
    if a.kind == "run":
        pcsim_post.need_run_folder(a.folder, ("summary.json", "results.h5"))
        text = run_report(a.folder)
    else:
        pcsim_post.need_run_folder(a.folder, ("summary.json",), "pcsim sweep")
        text = sweep_report(a.folder)
    output = a.output or os.path.join(a.folder, "report.html")
    temporary = output + ".tmp"
    try:  # whole or not at all
        with open(temporary, "w") as f:
            f.write(text)
        os.replace(temporary, output)
    except OSError as e:  # a full disk: pcsim run reports it as its exit 5
        if os.path.exists(temporary):
            os.remove(temporary)
        print("cannot write %s: %s" % (output, e.strerror), file=sys.stderr)
        sys.exit(5)
    print("report: wrote %s" % output)


if __name__ == "__main__":
    pcsim_post.main(main)
