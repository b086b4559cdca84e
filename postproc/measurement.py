#!/usr/bin/python3
"""A measured contact force (CSV) read, filtered and aligned like a `pcsim run` result.

    measurement.py FILE.csv [--run RUN] [--max-lag M]

Prints what the file holds (columns, rows, range, spacing); with --run, the measurement
filtered like the run (zero-phase 4th-order Butterworth at the run's analysis.cutoff_hz, on
the measurement's time axis), aligned by position to the run's pantographs (one lag for the
file: the largest mean over the pantographs of the correlation coefficients of the filtered
forces over the run's analysis section), the lag and each pantograph's force offset found.
"""
import argparse

import numpy as np

import interaction_plots
import measurement_csv
import pcsim_post

Measurement = measurement_csv.Measurement  # the CSV read there, aligned here
__doc__ += "\n" + measurement_csv.__doc__.split("\n", 2)[2]
FILTER_ORDER = 4  # pcsim's zero_phase_lowpass (src/output/statistics.cpp)


def zero_phase_lowpass(signal, sample_rate_hz, cutoff_hz, order=FILTER_ORDER):
    """pcsim's zero_phase_filter: Butterworth sections forward and backward, odd extension of
    3 (2 sections + 1) samples, each pass starting in steady state (scipy's sosfiltfilt)."""
    from scipy import signal as sps
    sos = sps.butter(order, cutoff_hz, fs=sample_rate_hz, output="sos")
    return sps.sosfiltfilt(sos, signal, padtype="odd", padlen=3 * (2 * len(sos) + 1))


def filter_like_run(time, signal, cutoff_hz):
    """pcsim's filter_uniformly_sampled (src/output/run_results.cpp): filtered as sampled if
    the steps are uniform, else on a grid of the smallest step and read back at the samples."""
    n = len(time)
    if n < 8:
        return np.array(signal, dtype=float)
    dt = (time[-1] - time[0]) / (n - 1)
    steps = np.diff(time)
    if np.all(np.abs(steps - dt) < 1e-6 * dt):
        return zero_phase_lowpass(signal, 1.0 / dt, cutoff_hz)
    dt_min = min(dt, steps.min())
    m = int((time[-1] - time[0]) / dt_min) + 1
    grid = time[0] + dt_min * np.arange(m)
    filtered = zero_phase_lowpass(np.interp(grid, time, signal), 1.0 / dt_min, cutoff_hz)
    return filtered[np.minimum(m - 1, np.floor((time - time[0]) / dt_min + 0.5).astype(int))]


def correlation(run_on_grid, grid, x, force, lag):
    """The correlation coefficient of force(grid + lag) with run_on_grid where the measurement
    covers grid + lag, or None if it covers less than half of the grid (too little to judge)."""
    inside = (grid + lag >= x[0]) & (grid + lag <= x[-1])
    if inside.sum() < 0.5 * len(grid):
        return None
    return float(np.corrcoef(run_on_grid[inside], np.interp(grid[inside] + lag, x, force))[0, 1])


def find_lag(pairs, section, max_lag, step, path):
    """The lag L (m) for which every measured force(x - L) correlates best with its run's force
    over 'section': the mean of the pantographs' correlation coefficients, candidates every
    'step' over [-max_lag, max_lag], refined by a parabola through the best three.
    pairs: [(run_x, run_force, x, force)], one per pantograph; path: the measurement's, for an
    error. Returns (lag, mean coefficient)."""
    grid = np.arange(section[0], section[1] + 1e-9, step)
    runs_on_grid = [np.interp(grid, p[0], p[1]) for p in pairs]
    lags = np.arange(-max_lag, max_lag + 1e-9, step)
    scores = np.full(len(lags), -2.0)
    for k, lag in enumerate(lags):
        each = [correlation(r, grid, p[2], p[3], lag) for r, p in zip(runs_on_grid, pairs)]
        if None not in each:
            scores[k] = float(np.mean(each))
    best = int(np.argmax(scores))
    if scores[best] < -1.5:
        pcsim_post.fail("%s: does not cover the run's analysis section %g-%g m at any lag within "
                        "%g m (x is the position of the first force column's pantograph)"
                        % (path, section[0], section[1], max_lag))
    lag = lags[best]
    if 0 < best < len(lags) - 1 and min(scores[best - 1], scores[best + 1]) > -1.5:
        a, b, c = scores[best - 1: best + 2]
        if a - 2 * b + c < 0:
            lag += 0.5 * step * (a - c) / (a - 2 * b + c)
    return float(lag), float(scores[best])


def pantograph_columns(measurement, run):
    """[(pantograph name, force column text)] of the measurement, every name one of the run's
    ('force [N]': the run's first pantograph)."""
    out = []
    for name, text in measurement.force_columns.items():
        pantograph = name if name is not None else next(iter(run.pantographs))
        if pantograph not in run.pantographs:
            pcsim_post.fail("%s: column '%s': the run %s has no pantograph '%s' (it has: %s)"
                            % (measurement.path, text, run.folder, pantograph, ", ".join(run.pantographs)))
        out.append((pantograph, text))
    return out


def run_mean_force(run, name):
    """The run's mean filtered contact force of pantograph 'name' over the analysis section:
    its summary.json figure (pcsim's own section bounds), else from results.h5."""
    figures = next((p for p in run.summary.get("pantographs", []) if p.get("name") == name), {})
    if "mean_N" in figures:
        return float(figures["mean_N"])
    p = run.pantographs[name]
    return force_figures(p["position"], p["contact_force_filtered"], p["contact_force"],
                         run.x_from, run.x_to)["mean_N"]


def filtered_on_time_grid(measurement, run):
    """Each force low-pass filtered like the run on a uniform time grid (the median step), then
    read on a uniform grid of positions (the median spacing; the statistics weigh the line
    evenly, as a run's at its constant speed): (time, x of the first force column's pantograph,
    mean speed, {column name: (raw, filtered)}) on that grid. A position file's time is x / v
    (v: its comment's speed, else the run's)."""
    cutoff = run.summary["analysis"]["cutoff_hz"]
    time = measurement.time
    if time is None:
        speed = measurement.speed_kmh / 3.6 if measurement.speed_kmh else run.speed
        time = (measurement.x - measurement.x[0]) / speed
    dt = float(np.median(np.diff(time)))
    if dt > 1.0 / (2.5 * cutoff):
        if measurement.time is None:
            pcsim_post.fail("%s: samples every %.3g m do not resolve the %g Hz cut-off at %.0f km/h "
                            "(at most %.3g m)" % (measurement.path, dt * speed, cutoff, 3.6 * speed,
                                                  speed / (2.5 * cutoff)))
        pcsim_post.fail("%s: samples every %.3g s do not resolve the %g Hz cut-off (at most %.3g s)"
                        % (measurement.path, dt, cutoff, 1.0 / (2.5 * cutoff)))
    time_grid = np.arange(time[0], time[-1] + 1e-9 * dt, dt)
    x_on_time_grid = np.interp(time_grid, time, measurement.x)
    step = measurement.spacing()
    x = np.arange(measurement.x[0], x_on_time_grid[-1] + 1e-9 * step, step)
    at = np.interp(x, x_on_time_grid, time_grid)
    forces = {}
    for name, force in measurement.forces.items():
        filtered = zero_phase_lowpass(np.interp(time_grid, time, force), 1.0 / dt, cutoff)
        forces[name] = (np.interp(x, measurement.x, force), np.interp(at, time_grid, filtered))
    return at, x, (x[-1] - x[0]) / (at[-1] - at[0]), forces


def align(measurement, run, max_lag=None):
    """The measurement filtered like the run and aligned by position to its pantographs, one lag
    for the file (the pantographs move together): a dict with time, lag_m, correlation (mean
    over the pantographs), max_lag_m, speed (mean, m/s), covers_section and per pantograph
    (list 'pantographs') name, column, distance_m (from the first force column's pantograph in
    the run), x (aligned), force, filtered, offset_N (mean measured minus mean computed filtered
    force over the analysis section), correlation, lag_alone_m (its own best lag), covers_section."""
    columns = pantograph_columns(measurement, run)
    time, x, speed, forces = filtered_on_time_grid(measurement, run)
    reference = run.pantographs[columns[0][0]]["position"]
    step = min(measurement.spacing(), 0.1)
    section = (run.x_from, run.x_to)
    if max_lag is None:  # spans repeat: beyond half a span the lag is ambiguous
        max_lag = 0.5 * float(np.median(np.diff(run.support_x)))
    pairs, out = [], []
    for (name, text), (raw, filtered) in zip(columns, forces.values()):
        p = run.pantographs[name]
        distance = float(np.median(p["position"] - reference))
        pairs.append((p["position"], p["contact_force_filtered"], x + distance, filtered))
        alone = find_lag(pairs[-1:], section, max_lag, step, measurement.path)[0]
        out.append({"name": name, "column": text, "distance_m": distance, "force": raw,
                    "filtered": filtered, "lag_alone_m": alone})
    lag, mean_correlation = find_lag(pairs, section, max_lag, step, measurement.path)
    for o, (run_x, run_force, measured_x, filtered) in zip(out, pairs):
        o["x"] = measured_x - lag
        o["offset_N"] = (force_figures(o["x"], filtered, o["force"], *section)["mean_N"]
                         - run_mean_force(run, o["name"]))
        grid = np.arange(section[0], section[1] + 1e-9, step)
        o["correlation"] = correlation(np.interp(grid, run_x, run_force), grid, o["x"], filtered, 0.0)
        o["covers_section"] = bool(o["x"][0] <= run.x_from and o["x"][-1] >= run.x_to)
    return {"time": time, "row_x": x, "lag_m": lag, "correlation": mean_correlation, "max_lag_m": max_lag,
            "speed": speed, "covers_section": all(o["covers_section"] for o in out), "pantographs": out}


def force_figures(x, filtered, raw, x_from, x_to):
    """pcsim's force_statistics (src/output/statistics.cpp) over [x_from, x_to]: the summary.json
    entries of a pantograph."""
    inside = (x >= x_from) & (x <= x_to)
    if not inside.any():
        pcsim_post.fail("no sample in the analysis section %g-%g m" % (x_from, x_to))
    f = filtered[inside]
    mean, std = float(f.mean()), float(f.std())
    return {"mean_N": mean, "std_N": std, "stat_max_N": mean + 3 * std, "stat_min_N": mean - 3 * std,
            "max_N": float(f.max()), "min_N": float(f.min()),
            "min_unfiltered_N": float(raw[inside].min()),
            "loss_of_contact_percent": 100.0 * float(np.mean(raw[inside] <= 0)),
            "samples": int(inside.sum())}


class MeasuredRun(interaction_plots.Run):
    """A measurement aligned to a run, with what the plots read of a run (interaction_plots.Run)."""

    def __init__(self, measurement, run, label, max_lag=None):
        a = align(measurement, run, max_lag)
        self.alignment = {k: a[k] for k in ("lag_m", "correlation", "max_lag_m", "covers_section")}
        self.alignment["pantographs"] = [{k: p[k] for k in ("name", "column", "distance_m", "offset_N",
                                                            "correlation", "lag_alone_m", "covers_section")}
                                         for p in a["pantographs"]]
        self.folder, self.label, self.time, self.speed = measurement.path, label, a["time"], a["speed"]
        self.x_from, self.x_to = run.x_from, run.x_to
        self.support_x = measurement.support_x
        self.uplift = np.array([np.interp(a["row_x"], measurement.x, u) for u in measurement.uplift.T]).T
        self.pantographs, figures = {}, []
        for p in a["pantographs"]:
            self.pantographs[p["name"]] = {"position": p["x"], "contact_force": p["force"],
                                           "contact_force_filtered": p["filtered"]}
            figures.append(force_figures(p["x"], p["filtered"], p["force"], run.x_from, run.x_to))
            figures[-1].update(name=p["name"], complete=p["covers_section"])
        self.summary = {"speed_kmh": run.summary["speed_kmh"], "analysis": run.summary["analysis"],
                        "pantographs": figures}
        section = [i for i, x in enumerate(self.support_x) if self.in_section(x)]
        if section:
            self.summary["max_uplift_at_support_m"] = float(max(0.0, self.uplift[:, section].max()))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n\n", 1)[1],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file", metavar="FILE.csv", help="measurement CSV (format below)")
    ap.add_argument("--run", metavar="RUN", help="pcsim run result folder to align it to")
    ap.add_argument("--max-lag", type=float, metavar="M",
                    help="largest position lag searched (m; default half a span)")
    a = ap.parse_args()
    m = measurement_csv.Measurement(a.file)
    print("%s: %d rows, x %.2f-%.2f m every %.3g m%s, uplift at %s"
          % (a.file, len(m.x), m.x[0], m.x[-1], m.spacing(),
             "".join(", %s %.1f-%.1f N" % (text, m.forces[name].min(), m.forces[name].max())
                     for name, text in m.force_columns.items()),
             ", ".join("%g m" % x for x in m.support_x) or "no support"))
    if a.run:
        r = align(m, interaction_plots.Run(a.run), a.max_lag)
        print("against %s: lag %.3f m (mean correlation %.4f)" % (a.run, r["lag_m"], r["correlation"]))
        for p in r["pantographs"]:
            print("  pantograph '%s' (column '%s', %+.2f m from the first): force offset %+.2f N, "
                  "correlation %.4f, its own best lag %.3f m"
                  % (p["name"], p["column"], p["distance_m"], p["offset_N"], p["correlation"],
                     p["lag_alone_m"]))

if __name__ == "__main__":
    pcsim_post.main(main, error_status=2)
