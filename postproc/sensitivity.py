#!/usr/bin/python3
"""Sobol sensitivity indices of the EN 50318 figures of a `pcsim sweep --cases` result.

    sensitivity.py SWEEP_DIR [-o DIR] [--bootstrap R] [--seed S] [--confidence C] [--bins M]

For every pantograph, every EN 50318 figure and every sampled key:
- a Saltelli design (postproc/sample.py saltelli; the sweep's summary.json keeps the table's
  '# sample:' record): the first-order index S1 (Saltelli et al. 2010, Comput. Phys. Commun.
  181, estimator (b): mean(f(B) (f(A_B^i) - f(A))) / V) and the total index ST (Jansen 1999:
  mean((f(A) - f(A_B^i))^2) / 2V), V the variance of f over A and B;
- any other design (lhs, sobol, grid, or a table without a record): the given-data first-order
  index from binning the key (M bins of equal counts, or one bin per value when a key has at
  most M values): the variance of the bin means over V, less its sampling bias (the ANOVA
  estimate of the between-bin variance); no total index.
Confidence intervals: percentile bootstrap over the base rows (Saltelli) or the cases (binning),
R resamples (1000) from the seed S (1). A case that failed drops its row (Saltelli: the whole
base row j, i.e. A_j, B_j and every A_B^i_j). A figure constant over the cases has no indices.
Writes, in DIR (default SWEEP_DIR): sensitivity.csv, sensitivity.md (a table per pantograph),
sensitivity.png (bars of S1 and ST with their intervals, a panel per figure; one file per
pantograph when there are several: sensitivity-<name>.png) and scatter.png (every figure
against every key, scatter-<name>.png with several pantographs).
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import pcsim_post  # noqa: E402


# --- estimators --------------------------------------------------------------------------------

def saltelli_indices(ya, yb, yab):
    """First-order (Saltelli 2010) and total (Jansen) indices from f(A), f(B) (N,) and
    f(A_B^i) (k, N): (S1 (k,), ST (k,)); NaN where f is constant."""
    ya, yb, yab = np.asarray(ya, float), np.asarray(yb, float), np.asarray(yab, float)
    # Centred on the mean of f over A and B (as SALib does): the estimators' expectations do
    # not change, the variance of the S1 estimator does not grow with the mean of f.
    f0 = np.mean(np.concatenate([ya, yb]))
    ya, yb, yab = ya - f0, yb - f0, yab - f0
    v = np.var(np.concatenate([ya, yb]))
    if not v > 0:
        return np.full(len(yab), np.nan), np.full(len(yab), np.nan)
    s1 = np.mean(yb * (yab - ya), axis=1) / v
    st = 0.5 * np.mean((ya - yab) ** 2, axis=1) / v
    return s1, st


def bootstrap(estimate, n, resamples, seed, confidence):
    """Percentile intervals of estimate(index array) -> tuple of arrays, resampling n rows."""
    import warnings
    rng = np.random.default_rng(seed)
    draws = [estimate(rng.integers(0, n, n)) for _ in range(resamples)]
    alpha = 100 * (1 - confidence) / 2
    out = []
    with warnings.catch_warnings():  # a constant figure: NaN intervals, no warning
        warnings.simplefilter("ignore", RuntimeWarning)
        for j in range(len(draws[0])):
            values = np.array([d[j] for d in draws], float)
            out.append((np.nanpercentile(values, alpha, axis=0),
                        np.nanpercentile(values, 100 - alpha, axis=0)))
    return out


def saltelli_with_intervals(ya, yb, yab, resamples=1000, seed=1, confidence=0.95):
    """{'S1', 'ST', 'S1_ci', 'ST_ci'}: the indices and their bootstrap intervals ((lo, hi) arrays)."""
    ya, yb, yab = np.asarray(ya, float), np.asarray(yb, float), np.asarray(yab, float)
    s1, st = saltelli_indices(ya, yb, yab)
    (s1_lo, s1_hi), (st_lo, st_hi) = bootstrap(
        lambda i: saltelli_indices(ya[i], yb[i], yab[:, i]), len(ya), resamples, seed, confidence)
    return {"S1": s1, "ST": st, "S1_ci": (s1_lo, s1_hi), "ST_ci": (st_lo, st_hi)}


def bin_labels(x, bins):
    """The bin of every value: one per distinct value if there are at most `bins`, else
    `bins` bins of (nearly) equal counts by rank."""
    x = np.asarray(x)
    distinct, codes = np.unique(x, return_inverse=True)
    if len(distinct) <= bins:
        return codes
    order = np.argsort(np.asarray(x, float), kind="stable")
    labels = np.empty(len(x), int)
    labels[order] = np.arange(len(x)) * bins // len(x)
    return labels


def binned_first_order(labels, y):
    """Given-data S1: the between-bin variance (ANOVA estimate, sampling bias removed) over
    the variance of y; NaN where y is constant."""
    y = np.asarray(y, float)
    n = len(y)
    groups = np.unique(labels)
    m = len(groups)
    v = np.var(y)
    if not v > 0 or m < 2 or n <= m:
        return np.nan
    means = np.array([y[labels == g].mean() for g in groups])
    counts = np.array([np.sum(labels == g) for g in groups])
    ss_between = np.sum(counts * (means - y.mean()) ** 2)
    ms_within = (np.sum((y - means[np.searchsorted(groups, labels)]) ** 2)) / (n - m)
    return (ss_between - (m - 1) * ms_within) / n / v


def binned_with_intervals(x, y, bins, resamples=1000, seed=1, confidence=0.95):
    labels = bin_labels(x, bins)
    y = np.asarray(y, float)
    s1 = binned_first_order(labels, y)
    [(lo, hi)] = bootstrap(lambda i: [binned_first_order(labels[i], y[i])], len(y), resamples,
                           seed, confidence)
    return s1, (float(lo), float(hi))


# --- the sweep's figures -----------------------------------------------------------------------

def numeric(values):
    try:
        return np.array([float(v) for v in values])
    except ValueError:
        return np.array(values, dtype=object)


def sweep_data(summary):
    """(keys, {key: values per case}, {pantograph: {figure key: array per case, NaN if none}},
    {figure key: (label, unit)})."""
    ref = pcsim_post.reference()
    keys = summary.get("cases_table", {}).get("columns") or list(summary["swept"])
    cases = summary["cases"]
    x = {k: numeric([c["values"][k] for c in cases]) for k in keys}
    figures = {f["key"]: (f["label"], f["unit"]) for f in ref["figures"]}
    y = {}
    for j, case in enumerate(cases):
        s = case.get("summary")
        if case["status"] != 0 or not s:
            continue
        for p in s.get("pantographs", []):
            if p.get("complete") is False:
                continue
            table = y.setdefault(p["name"], {f: np.full(len(cases), np.nan) for f in figures})
            for f in pcsim_post.assess(s, p, ref):
                table[f["key"]][j] = f["value"]
    return keys, x, y, figures


def saltelli_layout(sample, keys, count):
    """N, checking the sweep's cases are the design's N (k + 2) rows in its order."""
    n = int(sample.get("block_rows", 0))
    if sample.get("keys") != keys or count != n * (len(keys) + 2):
        pcsim_post.fail("the sweep's %d cases of %s are not the Saltelli table of %s (N=%d: %d cases)"
                        % (count, ", ".join(keys), ", ".join(sample.get("keys", [])), n,
                           n * (len(sample.get("keys", [])) + 2)))
    return n


def indices(summary, resamples, seed, confidence, bins):
    """Rows {pantograph, figure, label, unit, key, method, n, S1, S1_low, S1_high, ST, ...}."""
    keys, x, y, figures = sweep_data(summary)
    sample = summary.get("sample") or {}
    design = sample.get("design", "table")
    rows = []
    for pantograph, table in sorted(y.items()):
        for f, values in table.items():
            label, unit = figures[f]
            base = {"pantograph": pantograph, "figure": f, "label": label, "unit": unit}
            if design == "saltelli":
                n = saltelli_layout(sample, keys, len(values))
                blocks = values.reshape(len(keys) + 2, n)
                keep = np.all(np.isfinite(blocks), axis=0)
                if keep.sum() < 2:
                    continue
                r = saltelli_with_intervals(blocks[0, keep], blocks[1, keep], blocks[2:, keep],
                                            resamples, seed, confidence)
                for i, key in enumerate(keys):
                    rows.append(dict(base, key=key, method="saltelli", n=int(keep.sum()),
                                     S1=r["S1"][i], S1_low=r["S1_ci"][0][i], S1_high=r["S1_ci"][1][i],
                                     ST=r["ST"][i], ST_low=r["ST_ci"][0][i], ST_high=r["ST_ci"][1][i]))
                continue
            keep = np.isfinite(values)
            if keep.sum() < 3:
                continue
            m = bins or max(2, int(round(math.sqrt(keep.sum()))))
            for key in keys:
                s1, (lo, hi) = binned_with_intervals(x[key][keep], values[keep], m, resamples, seed,
                                                     confidence)
                rows.append(dict(base, key=key, method="binned (%s)" % design, n=int(keep.sum()),
                                 S1=s1, S1_low=lo, S1_high=hi, ST=np.nan, ST_low=np.nan, ST_high=np.nan))
    return keys, x, y, figures, rows


# --- output ------------------------------------------------------------------------------------

FIELDS = ["pantograph", "figure", "unit", "key", "method", "n", "S1", "S1_low", "S1_high", "ST",
          "ST_low", "ST_high"]


def fmt(v):
    return "" if v is None or (isinstance(v, float) and math.isnan(v)) else (
        "%.4f" % v if isinstance(v, (float, np.floating)) else str(v))


def write_tables(folder, rows, confidence):
    with open(os.path.join(folder, "sensitivity.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(FIELDS)
        for r in rows:
            w.writerow([fmt(r[k]) for k in FIELDS])
    lines = []
    for pantograph in sorted({r["pantograph"] for r in rows}):
        lines += ["## %s" % pantograph, "",
                  "| figure | key | S1 | %d %% interval | ST | %d %% interval | method, n |"
                  % (100 * confidence, 100 * confidence), "|---|---|---|---|---|---|---|"]
        mine = [r for r in rows if r["pantograph"] == pantograph]
        constant = sorted({r["label"] for r in mine if math.isnan(r["S1"])},
                          key=[r["label"] for r in mine].index)
        for r in (r for r in mine if not math.isnan(r["S1"])):
            ci = lambda a, b: "" if math.isnan(r[a]) else "[%s, %s]" % (fmt(r[a]), fmt(r[b]))
            lines.append("| %s (%s) | %s | %s | %s | %s | %s | %s, %d |" % (
                r["label"], r["unit"], r["key"], fmt(r["S1"]), ci("S1_low", "S1_high"), fmt(r["ST"]),
                ci("ST_low", "ST_high"), r["method"], r["n"]))
        if constant:
            lines += ["", "No indices (the same value in every case): %s." % ", ".join(constant)]
        lines.append("")
    text = "\n".join(lines)
    with open(os.path.join(folder, "sensitivity.md"), "w") as f:
        f.write(text)
    return text


def bar_figure(rows, figures, keys, title):
    plt = pcsim_post.pyplot()
    shown = [f for f in figures if any(r["figure"] == f and not math.isnan(r["S1"]) for r in rows)]
    cols = min(3, max(1, len(shown)))
    fig, axes = plt.subplots(max(1, math.ceil(len(shown) / cols)), cols, squeeze=False,
                             figsize=(4.6 * cols, 3.4 * max(1, math.ceil(len(shown) / cols))))
    for ax in axes.flat[len(shown):]:
        ax.set_visible(False)
    for ax, f in zip(axes.flat, shown):
        by_key = {r["key"]: r for r in rows if r["figure"] == f}
        pos = np.arange(len(keys))
        for j, (name, color) in enumerate((("S1", "C0"), ("ST", "C3"))):
            vals = np.array([by_key[k][name] if k in by_key else np.nan for k in keys], float)
            if np.all(np.isnan(vals)):
                continue
            lo = np.array([by_key[k][name + "_low"] if k in by_key else np.nan for k in keys], float)
            hi = np.array([by_key[k][name + "_high"] if k in by_key else np.nan for k in keys], float)
            err = np.vstack([np.clip(vals - lo, 0, None), np.clip(hi - vals, 0, None)])
            ax.bar(pos + (j - 0.5) * 0.38, vals, 0.36, yerr=err, capsize=3, color=color, label=name)
        ax.set_xticks(pos, short_names(keys), fontsize=8, rotation=30, ha="right")
        ax.axhline(0, color="0.3", lw=0.6)
        ax.set_title("%s (%s)" % figures[f], fontsize=9)
        ax.grid(axis="y", alpha=0.3)
    if shown:
        axes.flat[0].legend(fontsize=8)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def short_names(keys):
    """The shortest trailing parts of the keys that tell them apart
    (pantographs[0].model.stages[1].mass -> stages[1].mass beside stages[0].mass)."""
    parts = [k.split(".") for k in keys]
    for n in range(1, max(len(p) for p in parts) + 1):
        names = [".".join(p[-n:]) for p in parts]
        if len(set(names)) == len(names):
            return names
    return list(keys)


def scatter_figure(x, table, figures, keys, title):
    plt = pcsim_post.pyplot()
    shown = [f for f in figures if np.any(np.isfinite(table[f]))]
    fig, axes = plt.subplots(max(1, len(shown)), len(keys), squeeze=False,
                             figsize=(3.2 * len(keys), 2.3 * max(1, len(shown))))
    for row, f in zip(axes, shown):
        for ax, key in zip(row, keys):
            values = x[key]
            if values.dtype == object:
                cats = sorted(set(values))
                values = np.array([cats.index(v) for v in values], float)
                ax.set_xticks(range(len(cats)), cats, fontsize=7)
            ax.plot(values, table[f], ".", ms=3, alpha=0.6)
            ax.tick_params(labelsize=7)
            if ax is row[0]:
                ax.set_ylabel("%s (%s)" % (f, figures[f][1]), fontsize=7)
            if row is axes[-1]:
                ax.set_xlabel(key, fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n\n", 2)[2],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sweep", metavar="SWEEP_DIR", help="pcsim sweep result folder")
    ap.add_argument("-o", "--output", metavar="DIR", help="folder of the tables and plots (SWEEP_DIR)")
    ap.add_argument("--bootstrap", type=int, default=1000, metavar="R", help="bootstrap resamples (1000)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the bootstrap (1)")
    ap.add_argument("--confidence", type=float, default=0.95, help="interval level (0.95)")
    ap.add_argument("--bins", type=int, default=0, metavar="M",
                    help="bins of the given-data estimate (default: sqrt of the cases)")
    ap.add_argument("--no-plots", action="store_true", help="tables only")
    a = ap.parse_args()
    if a.bootstrap < 10 or not 0 < a.confidence < 1 or a.bins < 0 or a.bins == 1:
        pcsim_post.fail("--bootstrap >= 10, 0 < --confidence < 1, --bins 0 (automatic) or >= 2")
    pcsim_post.need_run_folder(a.sweep, ("summary.json",), "pcsim sweep")
    summary = pcsim_post.load_json(os.path.join(a.sweep, "summary.json"))
    if "swept" not in summary:
        pcsim_post.fail("%s is not a pcsim sweep result (its summary.json has no 'swept')" % a.sweep)
    folder = a.output or a.sweep
    os.makedirs(folder, exist_ok=True)
    keys, x, y, figures, rows = indices(summary, a.bootstrap, a.seed, a.confidence, a.bins)
    if not rows:
        pcsim_post.fail("%s: no successful cases to estimate indices from" % a.sweep)
    print(write_tables(folder, rows, a.confidence))
    if not a.no_plots:
        for pantograph in sorted(y):
            suffix = "" if len(y) == 1 else "-" + pantograph
            mine = [r for r in rows if r["pantograph"] == pantograph]
            bar_figure(mine, figures, keys, "Sobol indices, %s (%s)" % (pantograph, mine[0]["method"])) \
                .savefig(os.path.join(folder, "sensitivity%s.png" % suffix), dpi=90)
            scatter_figure(x, y[pantograph], figures, keys, "figures against the sampled keys, %s" % pantograph) \
                .savefig(os.path.join(folder, "scatter%s.png" % suffix), dpi=80)
    print("sensitivity: wrote sensitivity.csv, sensitivity.md%s in %s"
          % ("" if a.no_plots else ", sensitivity*.png, scatter*.png", folder))


if __name__ == "__main__":
    pcsim_post.main(main)
