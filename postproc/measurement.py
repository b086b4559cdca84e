#!/usr/bin/python3
"""A measured contact force (CSV) read, filtered and aligned like a `pcsim run` result.

    measurement.py FILE.csv [--run RUN] [--max-lag M]

Prints what the file holds (columns, rows, range, spacing); with --run, the measurement
filtered like the run (zero-phase 4th-order Butterworth at the run's analysis.cutoff_hz),
aligned by position to the run's first pantograph (the lag of largest cross-correlation of
the filtered forces over the run's analysis section), the lag and the force offset found.

Format (docs/assessment.md "Measurements"): comma-separated, '#' lines are comments; the
first other line is the header, every column with its unit in brackets:
  x [m] (or [km])       contact point position along the track, increasing; or
  t [s]                 time, increasing, with a comment line '# speed [km/h]: V' (x = V t)
  force [N] (or [kN])   measured contact force
  uplift X [mm] (or [m]) optional, any number: contact-wire uplift at the support at X m
"""
import argparse
import re

import numpy as np

import interaction_plots
import pcsim_post

UNITS = {"x": {"m": 1.0, "km": 1000.0}, "t": {"s": 1.0}, "force": {"N": 1.0, "kN": 1000.0},
         "uplift": {"mm": 1e-3, "m": 1.0}}
MIN_ROWS = 64
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


def parse_header(path, header):
    """{'axis': 'x'|'t', 'scale': {column: factor}, 'uplift_x': [support x per uplift column]}"""
    columns = []
    for i, cell in enumerate(c.strip() for c in header.split(",")):
        m = re.fullmatch(r"(x|t|force|uplift\s+(-?[0-9.]+))\s*(\[([^\]]*)\])?", cell)
        if not m:
            pcsim_post.fail("%s: header column %d '%s' is none of x [m], t [s], force [N], "
                            "uplift X [mm]" % (path, i + 1, cell))
        kind = "uplift" if m.group(1).startswith("uplift") else m.group(1)
        if m.group(3) is None:
            pcsim_post.fail("%s: header column '%s' has no unit (write e.g. '%s [%s]')"
                            % (path, cell, cell, next(iter(UNITS[kind]))))
        if m.group(4).strip() not in UNITS[kind]:
            pcsim_post.fail("%s: header column '%s': unit '%s' is not one of %s"
                            % (path, cell, m.group(4), ", ".join(UNITS[kind])))
        columns.append((kind, UNITS[kind][m.group(4).strip()],
                        float(m.group(2)) if kind == "uplift" else None))
    kinds = [c[0] for c in columns]
    if kinds.count("force") != 1 or kinds.count("x") + kinds.count("t") != 1:
        pcsim_post.fail("%s: the header needs one position column 'x [m]' or time column "
                        "'t [s]' and one 'force [N]' (it has: %s)" % (path, header.strip()))
    return columns


class Measurement:
    """A measurement CSV: position (m), force (N), uplift histories at supports (m)."""

    def __init__(self, path):
        self.path = pcsim_post.need_file(path, "measurement")
        with open(path, errors="replace") as f:
            lines = [(n + 1, l) for n, l in enumerate(f) if l.strip()]
        comments = [l for _, l in lines if l.lstrip().startswith("#")]
        data = [(n, l) for n, l in lines if not l.lstrip().startswith("#")]
        if not data:
            pcsim_post.fail("%s: no header line" % path)
        columns = parse_header(path, data[0][1])
        rows = [self.row(n, l, len(columns)) for n, l in data[1:]]
        if len(rows) < MIN_ROWS:
            pcsim_post.fail("%s: %d rows, at least %d needed" % (path, len(rows), MIN_ROWS))
        table = np.array(rows) * np.array([c[1] for c in columns])
        kinds = [c[0] for c in columns]
        axis = "x" if "x" in kinds else "t"
        self.speed_kmh = self.speed_comment(comments)
        along = table[:, kinds.index(axis)]
        if np.any(np.diff(along) <= 0):
            pcsim_post.fail("%s: column %s does not increase strictly" % (path, axis))
        if axis == "t" and self.speed_kmh is None:
            pcsim_post.fail("%s: a time column needs the speed in a comment line "
                            "'# speed [km/h]: V'" % path)
        self.x = along * self.speed_kmh / 3.6 if axis == "t" else along
        self.force = table[:, kinds.index("force")]
        self.support_x = np.array([c[2] for c in columns if c[0] == "uplift"])
        self.uplift = table[:, [i for i, c in enumerate(columns) if c[0] == "uplift"]]
        self.comments = [c.lstrip("# ").rstrip() for c in comments]

    def row(self, number, line, width):
        cells = line.split(",")
        try:
            values = [float(c) for c in cells]
        except ValueError:
            values = []
        if len(values) != width or not np.all(np.isfinite(values)):
            pcsim_post.fail("%s: line %d: %d numbers expected: %s"
                            % (self.path, number, width, line.strip()[:60]))
        return values

    def speed_comment(self, comments):
        for c in comments:
            m = re.match(r"#\s*speed\s*\[km/h\]\s*[:=]\s*([0-9.eE+-]+)\s*$", c.strip())
            if m:
                return float(m.group(1))
        return None

    def spacing(self):
        return float(np.median(np.diff(self.x)))


def find_lag(run_x, run_force, x, force, section, max_lag, step):
    """The lag L (m) for which force(x - L) correlates best with run_force over 'section':
    candidates every 'step' over [-max_lag, max_lag], refined by a parabola through the best
    three. Returns (lag, correlation coefficient)."""
    grid = np.arange(section[0], section[1] + 1e-9, step)
    run_on_grid = np.interp(grid, run_x, run_force)
    lags = np.arange(-max_lag, max_lag + 1e-9, step)
    scores = np.full(len(lags), -2.0)
    for k, lag in enumerate(lags):
        inside = (grid + lag >= x[0]) & (grid + lag <= x[-1])
        if inside.sum() < 0.5 * len(grid):  # too little overlap to judge
            continue
        scores[k] = np.corrcoef(run_on_grid[inside], np.interp(grid[inside] + lag, x, force))[0, 1]
    best = int(np.argmax(scores))
    if scores[best] < -1.5:
        pcsim_post.fail("the measurement does not cover the analysis section %g-%g m at any "
                        "lag within %g m" % (section[0], section[1], max_lag))
    lag = lags[best]
    if 0 < best < len(lags) - 1 and min(scores[best - 1], scores[best + 1]) > -1.5:
        a, b, c = scores[best - 1: best + 2]
        if a - 2 * b + c < 0:
            lag += 0.5 * step * (a - c) / (a - 2 * b + c)
    return float(lag), float(scores[best])


def align(measurement, run, max_lag=None):
    """The measurement filtered like the run and aligned to its first pantograph: a dict with
    x (aligned positions), time, force, filtered, lag_m, correlation, offset_N (mean measured
    minus mean computed filtered force over the analysis section), speed."""
    name, p = run.pantograph()
    speed = measurement.speed_kmh / 3.6 if measurement.speed_kmh else run.speed
    step = measurement.spacing()
    cutoff = run.summary["analysis"]["cutoff_hz"]
    if step > speed / (2.5 * cutoff):
        pcsim_post.fail("%s: samples every %.3g m do not resolve the %g Hz cut-off at %.0f km/h "
                        "(at most %.3g m)" % (measurement.path, step, cutoff, 3.6 * speed,
                                              speed / (2.5 * cutoff)))
    grid = np.arange(measurement.x[0], measurement.x[-1] + 1e-9, step)
    time = (grid - grid[0]) / speed
    filtered = zero_phase_lowpass(np.interp(grid, measurement.x, measurement.force), speed / step,
                                  cutoff)
    if max_lag is None:  # spans repeat: beyond half a span the lag is ambiguous
        max_lag = 0.5 * float(np.median(np.diff(run.support_x)))
    lag, correlation = find_lag(p["position"], p["contact_force_filtered"], grid, filtered,
                                (run.x_from, run.x_to), max_lag, min(step, 0.1))
    x = grid - lag
    inside = (x >= run.x_from - 1e-9) & (x <= run.x_to + 1e-9)
    run_inside = (p["position"] >= run.x_from - 1e-9) & (p["position"] <= run.x_to + 1e-9)
    offset = filtered[inside].mean() - p["contact_force_filtered"][run_inside].mean()
    return {"pantograph": name, "x": x, "time": time, "filtered": filtered,
            "force": np.interp(grid, measurement.x, measurement.force), "lag_m": lag,
            "correlation": correlation, "offset_N": float(offset), "speed": speed,
            "max_lag_m": max_lag, "covers_section": bool(x[0] <= run.x_from and x[-1] >= run.x_to)}


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
        self.alignment = {k: a[k] for k in ("pantograph", "lag_m", "correlation", "offset_N",
                                            "max_lag_m", "covers_section")}
        self.folder, self.label, self.time, self.speed = measurement.path, label, a["time"], a["speed"]
        self.x_from, self.x_to = run.x_from, run.x_to
        self.support_x = measurement.support_x
        grid = a["x"] + a["lag_m"]  # the measurement's own positions
        self.uplift = np.array([np.interp(grid, measurement.x, u) for u in measurement.uplift.T]).T
        self.pantographs = {a["pantograph"]: {"position": a["x"], "contact_force": a["force"],
                                              "contact_force_filtered": a["filtered"]}}
        figures = force_figures(a["x"], a["filtered"], a["force"], run.x_from, run.x_to)
        figures["name"] = a["pantograph"]
        figures["complete"] = a["covers_section"]
        self.summary = {"speed_kmh": run.summary["speed_kmh"], "analysis": run.summary["analysis"],
                        "pantographs": [figures]}
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
    m = Measurement(a.file)
    print("%s: %d rows, x %.2f-%.2f m every %.3g m, force %.1f-%.1f N, uplift at %s"
          % (a.file, len(m.x), m.x[0], m.x[-1], m.spacing(), m.force.min(), m.force.max(),
             ", ".join("%g m" % x for x in m.support_x) or "no support"))
    if a.run:
        r = align(m, interaction_plots.Run(a.run), a.max_lag)
        print("against %s, pantograph '%s': lag %.3f m (correlation %.4f), force offset %+.2f N"
              % (a.run, r["pantograph"], r["lag_m"], r["correlation"], r["offset_N"]))


if __name__ == "__main__":
    pcsim_post.main(main, error_status=2)
