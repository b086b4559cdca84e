#!/usr/bin/python3
"""The accuracy pilot's estimate against the actual errors of a run.

    pilot_check.py RUN [--reference FE_RUN] [--converged FINE_RUN] [--check] [--targets]

RUN is a result folder of `pcsim run` whose summary.json holds
accuracy_estimate.pilot (docs/fidelity.md, "Accuracy estimate"). With
--reference (linear FE at the same dt and mesh), RUN's actual reduction error
per figure is compared with the pilot's reduction estimate; with --converged
(linear FE at a much finer dt and mesh), the reference's actual
discretisation error with the pilot's discretisation estimate (both runs must
be of the same scene). Prints one table per pantograph, marking the
estimates of the extremes and losses of contact that fall outside the
pilot's stretch (accuracy_estimate.extremes_outside_pilot: estimated from other spans,
docs/fidelity.md "Where the extremes fall"); with --check, exits 1
unless every estimate is at or above its actual error and at most
3 x actual + 0.3 (issue 21's bounds); with --targets, also unless RUN's
actual errors against the reference are within the fast level's targets
(docs/fidelity.md: mean 0.5 %, sigma, Fm+3sigma and actual maximum 1 %,
uplift 2 %, Fm-3sigma and actual minimum 2 % of Fm, loss of contact 0.1
percentage point).
"""
import argparse
import json
import sys

import pcsim_post

# Same order, units and names as simulation/accuracy_pilot.hpp.
KEYS = pcsim_post.PILOT_KEYS
LABELS = ["mean", "sigma", "Fm+3sigma", "actual max", "uplift", "Fm-3sigma", "actual min",
          "loss of contact"]
UNITS = ["%", "%", "%", "%", "%", "%Fm", "%Fm", "pt"]
TARGETS = [0.5, 1, 1, 1, 2, 2, 2, 0.1]  # simulation/accuracy_pilot.cpp, kPilotTargets


def figures(summary):
    """Per pantograph name: the eight figures (N, m, %)."""
    out = {}
    for p in summary["pantographs"]:
        out[p["name"]] = [p["mean_N"], p["std_N"], p["stat_max_N"], p["max_N"],
                          summary["max_uplift_at_support_m"], p["stat_min_N"], p["min_N"],
                          p["loss_of_contact_percent"]]
    return out


def actual_errors(run, reference):
    """Per pantograph: |run - reference| in the units of KEYS."""
    a, r = figures(run), figures(reference)
    out = {}
    for name, ref in r.items():
        x = a[name]
        fm = abs(ref[0])
        rel = [100 * abs(x[i] - ref[i]) / abs(ref[i]) if ref[i] else 0.0 for i in range(5)]
        out[name] = rel + [100 * abs(x[5] - ref[5]) / fm, 100 * abs(x[6] - ref[6]) / fm,
                           abs(x[7] - ref[7])]
    return out


def compare(kind, estimate, actual):
    """Rows (pantograph, figure, estimate, actual, ok) of one kind of error."""
    rows = []
    for p in estimate:
        name = p["pantograph"]
        for i, key in enumerate(KEYS):
            e, a = p[key], actual[name][i]
            ok = a <= e + 1e-12 and e <= 3 * a + 0.3 + 1e-12
            rows.append((kind, name, i, e, a, ok))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="a result folder of pcsim run with the pilot's estimate")
    parser.add_argument("--reference", help="linear FE at the run's dt and mesh")
    parser.add_argument("--converged", help="linear FE at a finer dt and mesh")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 unless every estimate is within [actual, 3 actual + 0.3]")
    parser.add_argument("--targets", action="store_true",
                        help="exit 1 unless the run's reduction errors meet the targets")
    args = parser.parse_args()

    def summary(folder):
        try:
            with open(f"{folder}/summary.json") as f:
                return json.load(f)
        except (OSError, ValueError) as e:
            sys.exit(f"pilot_check.py: error: {folder}/summary.json: {e.strerror if isinstance(e, OSError) else e}")

    run = summary(args.run)
    pilot = run["accuracy_estimate"].get("pilot")
    if pilot is None:
        sys.exit(f"{args.run}/summary.json: no accuracy_estimate.pilot (the pilot did not run)")
    rows = []
    if args.reference:
        reference = summary(args.reference)
        if "reduction" in pilot:
            rows += compare("reduction", pilot["reduction"], actual_errors(run, reference))
        if args.converged:
            converged = summary(args.converged)
            rows += compare("discretisation", pilot["discretisation"],
                            actual_errors(reference, converged))
    unseen = {(e["pantograph"], KEYS.index(e["figure"]))
              for e in run["accuracy_estimate"].get("extremes_outside_pilot", [])}
    print(f"{'error':15} {'pantograph':12} {'figure':16} {'estimate':>9} {'actual':>9}  "
          "within [actual, 3 actual + 0.3]")
    for kind, name, i, e, a, ok in rows:
        mark = "  (falls outside the pilot's stretch)" if (name, i) in unseen else ""
        print(f"{kind:15} {name:12} {LABELS[i]:16} {e:8.2f}{UNITS[i]:3} {a:6.2f}{UNITS[i]:3}  "
              f"{'yes' if ok else 'NO'}{mark}")
    failed = [r for r in rows if not r[5]]
    print(f"{len(rows) - len(failed)} of {len(rows)} estimates within their bounds")
    below = [r for r in failed if r[4] > r[3] + 1e-12]
    above = [r for r in failed if r not in below]
    if failed:
        print(f"{len(below)} below the actual error ({sum((r[1], r[2]) in unseen for r in below)} "
              f"of figures outside the pilot's stretch), {len(above)} above 3 actual + 0.3 "
              f"({sum((r[1], r[2]) in unseen for r in above)} of such figures)")
    if unseen:
        outside = [r for r in rows if (r[1], r[2]) in unseen]
        print(f"{len(outside)} estimates of figures that fall outside the pilot's stretch, "
              f"{sum(not r[5] for r in outside)} of them outside their bounds")
    missed = [r for r in rows if r[0] == "reduction" and r[4] > TARGETS[r[2]]]
    for kind, name, i, e, a, ok in missed:
        print(f"target missed: {name} {LABELS[i]} {a:.2f}{UNITS[i]} > {TARGETS[i]}{UNITS[i]}")
    if args.targets and not [r for r in rows if r[0] == "reduction"]:
        sys.exit("--targets: no reduction error to check (RUN is not modal, or no --reference)")
    if (args.check and (failed or not rows)) or (args.targets and missed):
        sys.exit(1)


if __name__ == "__main__":
    main()
