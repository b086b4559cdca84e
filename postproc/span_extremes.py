"""Where the extremes fall (not a script itself): every run's largest and smallest filtered
contact force per span of the analysis section (compare.py writes them as span_extremes.csv
and a table in compare.md).

A run's actual maximum or minimum is one sample: two runs can take theirs in different spans,
and the difference of their extremes is then not their difference at either span (on a line of
tension sections the modal level's minimum differs from linear FE's by 1.3 % of Fm in the span
of linear FE's minimum, by 0.1 % in the span of its own; docs/fidelity.md, "Where the extremes
fall").
"""
import numpy as np


def analysis_spans(run):
    """[(span number, from_x, to_x)] of the supports' spans inside the run's analysis section."""
    x = run.support_x
    return [(i + 1, x[i], x[i + 1]) for i in range(len(x) - 1)
            if x[i] >= run.x_from - 1e-6 and x[i + 1] <= run.x_to + 1e-6]


def local_extremes(pantograph, spans):
    """[(max, min)] of the filtered force per span ((nan, nan) where no sample lies in it)."""
    x, f = pantograph["position"], pantograph["contact_force_filtered"]
    out = []
    for k, (_, a, b) in enumerate(spans):
        last = k == len(spans) - 1  # the section's end belongs to its last span
        inside = f[(x >= a) & ((x < b) | (last & (x <= b)))]
        out.append((inside.max(), inside.min()) if inside.size else (np.nan, np.nan))
    return out


def comparable(runs):
    """True if every run has the same supports and at least one span in the first's section."""
    first = runs[0].support_x
    return bool(analysis_spans(runs[0])) and all(
        len(r.support_x) == len(first) and np.allclose(r.support_x, first, atol=1e-6) for r in runs)


def span_table(runs, names, pantograph_of):
    """Per pantograph name: {"spans": [...], "extremes": [per run [(max, min) per span]],
    "mean": the first run's mean force over those spans}. pantograph_of(run, name) gives
    the run's record of that pantograph (None: it has none). A pantograph that a run has not
    at all, or that reached no span of the section in one run, is left out."""
    spans = analysis_spans(runs[0])
    table = {}
    for name in names:
        records = [pantograph_of(r, name) for r in runs]
        if any(p is None for p in records):
            continue
        extremes = [local_extremes(p, spans) for p in records]
        if any(all(np.isnan(e[0]) for e in run) for run in extremes):
            continue  # a run whose pantograph reached no span of the section (cut short)
        x, f = records[0]["position"], records[0]["contact_force_filtered"]
        inside = (x >= spans[0][1]) & (x <= spans[-1][2])
        table[name] = {"spans": spans, "extremes": extremes, "mean": float(f[inside].mean())}
    return table


def csv_lines(table, labels):
    """span_extremes.csv: per pantograph and span, every run's local max and min [N], then per
    other run its differences from the first's (max in %, min in % of the first's Fm)."""
    header = ["pantograph", "span", "from_x [m]", "to_x [m]"]
    for l in labels:
        header += ["%s max [N]" % l, "%s min [N]" % l]
    for l in labels[1:]:
        header += ["%s - %s max [%%]" % (l, labels[0]), "%s - %s min [%%Fm]" % (l, labels[0])]
    lines = [",".join(header)]
    for name, t in table.items():
        for i, (number, a, b) in enumerate(t["spans"]):
            ref = t["extremes"][0][i]
            cells = [name.replace(",", ";"), str(number), "%.3f" % a, "%.3f" % b]
            for e in t["extremes"]:
                cells += ["%.3f" % e[i][0], "%.3f" % e[i][1]]
            for e in t["extremes"][1:]:
                cells += ["%+.3f" % (100 * (e[i][0] - ref[0]) / abs(ref[0])),
                          "%+.3f" % (100 * (e[i][1] - ref[1]) / abs(t["mean"]))]
            lines.append(",".join(cells))
    return lines


def summary_rows(table, labels):
    """Per pantograph and run: the span of its actual max and min and, for every run after the
    first, its local difference from the first in its own extreme's span and in the first's
    (max in %, min in % of the first's Fm)."""
    rows = []
    for name, t in table.items():
        ref = np.array(t["extremes"][0])
        ref_max, ref_min = int(np.nanargmax(ref[:, 0])), int(np.nanargmin(ref[:, 1]))
        for k, label in enumerate(labels):
            e = np.array(t["extremes"][k])
            i_max, i_min = int(np.nanargmax(e[:, 0])), int(np.nanargmin(e[:, 1]))
            d_max = lambda i: 100 * (e[i, 0] - ref[i, 0]) / abs(ref[i, 0])
            d_min = lambda i: 100 * (e[i, 1] - ref[i, 1]) / abs(t["mean"])
            rows.append({"pantograph": name, "source": label,
                         "max_span": t["spans"][i_max][0], "max_N": float(e[i_max, 0]),
                         "min_span": t["spans"][i_min][0], "min_N": float(e[i_min, 1]),
                         "max_there_percent": None if k == 0 else float(d_max(i_max)),
                         "max_in_first_span_percent": None if k == 0 else float(d_max(ref_max)),
                         "min_there_percent_of_fm": None if k == 0 else float(d_min(i_min)),
                         "min_in_first_span_percent_of_fm": None if k == 0 else float(d_min(ref_min))})
    return rows


def table_cells(rows, first):
    """The text, header and cells of the table of summary_rows (compare.md, report.html)."""
    signed = lambda v: "" if v is None else "%+.2f" % v
    text = ("Each run's actual maximum and minimum, the span it falls in, and the run's local "
            "extreme minus %s's in that span and in the span of %s's (maximum in %%, minimum in %% "
            "of %s's Fm; every span: span_extremes.csv)." % (first, first, first))
    header = ["pantograph", "source", "max span", "max N", "there [%]", "in the first's span [%]",
              "min span", "min N", "there [%Fm]", "in the first's span [%Fm]"]
    body = [[r["pantograph"], r["source"], "%d" % r["max_span"], "%.2f" % r["max_N"],
             signed(r["max_there_percent"]), signed(r["max_in_first_span_percent"]),
             "%d" % r["min_span"], "%.2f" % r["min_N"], signed(r["min_there_percent_of_fm"]),
             signed(r["min_in_first_span_percent_of_fm"])] for r in rows]
    return text, header, body
