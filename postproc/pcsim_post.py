"""Helpers shared by the postproc scripts (not a script itself).

- clear errors instead of tracebacks: `fail`, `need_file`, `need_run_folder`, and `main`, which
  runs a script's main function and turns a missing file or a missing Python package into one
  line on stderr (exit status 2);
- the EN 50318 figures and acceptance ranges of meshes/en50318-ranges.json (the file pcsim
  embeds too): `reference`, `assess`;
- `pyplot`: matplotlib with the Agg backend, or a clear message if it is missing;
- `PILOT_KEYS`: the accuracy pilot's figures as summary.json names them, in the order of
  simulation/accuracy_pilot.hpp (kPilotFigureKeys).
"""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
RANGES_FILE = os.path.join(HERE, os.pardir, "meshes", "en50318-ranges.json")

PILOT_KEYS = ["mean_percent", "sigma_percent", "mean_plus_3sigma_percent", "actual_max_percent",
              "uplift_percent", "mean_minus_3sigma_percent_of_mean", "actual_min_percent_of_mean",
              "loss_of_contact_points"]


class ScriptError(Exception):
    """An error to report in one line (no traceback)."""


def fail(message):
    raise ScriptError(message)


def need_file(path, what="file"):
    if not os.path.isfile(path):
        fail("%s %s not found" % (what, path))
    return path


def need_run_folder(folder, files=("summary.json",), command="pcsim run"):
    """A result folder of `command` holding `files`."""
    if not os.path.isdir(folder):
        fail("%s is not a folder (give a %s result folder)" % (folder, command))
    for name in files:
        if not os.path.isfile(os.path.join(folder, name)):
            fail("%s has no %s (is it a %s result folder?)" % (folder, name, command))
    return folder


def load_json(path):
    need_file(path)
    with open(path) as f:
        try:
            return json.load(f)
        except ValueError as e:
            fail("%s is not valid JSON: %s" % (path, e))


def pyplot():
    try:
        import matplotlib
    except ImportError:
        fail("matplotlib is not installed for %s (Debian: apt-get install python3-matplotlib)"
             % sys.executable)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def reference():
    """{'edition', 'figures': [{key, label, unit, from?, scale?}], 'ranges': {speed: {key: (lo, hi)}}}"""
    data = load_json(os.path.normpath(RANGES_FILE))
    ranges = {float(v): {k: tuple(r) for k, r in figs.items()}
              for v, figs in data["ranges_by_speed_kmh"].items()}
    return {"edition": data["edition"], "figures": data["figures"], "ranges": ranges}


def ranges_at(ref, speed_kmh):
    for speed, figs in ref["ranges"].items():
        if abs(speed - speed_kmh) < 0.5:
            return figs
    return None


def assess(run_summary, pantograph, ref=None):
    """The EN 50318 figures of one pantograph of a run: [{key, label, unit, value, range, verdict}];
    range and verdict are None where the standard gives no range at the run's speed."""
    ref = ref or reference()
    ranges = ranges_at(ref, run_summary.get("speed_kmh", 0.0))
    out = []
    for f in ref["figures"]:
        source = run_summary if f.get("from") else pantograph
        key = f.get("from") or f["key"]
        if key not in source:
            continue
        value = f.get("scale", 1.0) * source[key]
        rng = ranges.get(f["key"]) if ranges else None
        verdict = None
        if rng:
            verdict = "pass" if rng[0] - 1e-9 <= value <= rng[1] + 1e-9 else "fail"
        out.append({"key": f["key"], "label": f["label"], "unit": f["unit"], "value": value,
                    "range": rng, "verdict": verdict})
    return out


def main(function, error_status=1):
    """Runs function(); a ScriptError, a missing file or package ends the script with one line
    and exit status error_status."""
    name = os.path.basename(sys.argv[0])

    def stop(message):
        print("%s: error: %s" % (name, message), file=sys.stderr)
        sys.exit(error_status)
    try:
        function()
    except ScriptError as e:
        stop(e)
    except (FileNotFoundError, IsADirectoryError, NotADirectoryError) as e:
        stop("%s: %s" % (e.strerror, e.filename))
    except ImportError as e:
        stop("%s (a Python package is missing for %s)" % (e, sys.executable))
    except subprocess.CalledProcessError as e:
        stop("%s failed with exit status %d" % (" ".join(map(str, e.cmd)), e.returncode))
    except KeyError as e:
        stop("missing entry %s in the results (written by another pcsim version?)" % e)
