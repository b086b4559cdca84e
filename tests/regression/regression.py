#!/usr/bin/python3
"""Regression figures of pcsim, compared in the SLEPc manner.

Each case runs pcsim, extracts the figures it publishes (the eight EN 50318
figures of a run, the first 20 frequencies of the catenary's modes, a
pantograph's frequencies and damping ratios), prints them with 4
significant digits and diffs them against the committed file
tests/regression/expected/<case>.out.

A figure matches when the full-precision value rounds to the committed one:
|value - expected| <= half a unit of the 4th significant digit of the
expected value (+1e-9 relative, so that a value sitting on a rounding
boundary is not flagged for a round-off change). Runs on different rank
counts differ by ~1e-10 relative (tests/contact/test_run_ranks.sh), the
cheap and full paths by up to 1.4e-4 (one expected file per path), so half a
unit of the 4th digit (5e-4 relative at worst, 5e-5 at best) separates a
genuine change from round-off.

usage: regression.py CASE --bin PCSIM [--ranks N] [--regenerate]
  PCSIM_REGENERATE=1 in the environment also regenerates; then the .out file
  is rewritten and the test passes.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

RUN_FIGURES = [  # (label, unit, summary key, scale)
    ("mean contact force Fm", "N", "mean_N", 1.0),
    ("standard deviation", "N", "std_N", 1.0),
    ("statistical maximum Fm+3s", "N", "stat_max_N", 1.0),
    ("statistical minimum Fm-3s", "N", "stat_min_N", 1.0),
    ("actual maximum", "N", "max_N", 1.0),
    ("actual minimum", "N", "min_N", 1.0),
    ("loss of contact", "%", "loss_of_contact_percent", 1.0),
]

CASES = {
    # case: (command, scene, extra options)
    "en50318-300-cheap": ("run", "runs/en50318-300.yaml", ["-pcsim_path", "cheap"]),
    "en50318-300-full": ("run", "runs/en50318-300.yaml", ["-pcsim_path", "full"]),
    # README's 250 km/h figures (two outside their ranges), one rank.
    "en50318-250-cheap": ("run", "runs/interaction/en50318-250.yaml", []),
    # The reduced-order catenary at its default cut-off (docs/fidelity.md); its
    # modes are computed afresh into a temporary cache (~1 min on 1 rank).
    "en50318-300-modal": ("run", "runs/en50318-300-modal.yaml", []),
    "en50318-static-modes": ("modes", "runs/en50318-static.yaml", []),
    # docs/pantograph.md's modes of the three pantograph models (seconds each).
    "pantograph-en50318-modes": ("pantograph", "runs/pantograph/en50318_modes.yaml", []),
    "pantograph-dsa380-modes": ("pantograph", "runs/pantograph/dsa380_modes.yaml", []),
    "pantograph-flexible-modes": ("pantograph", "runs/pantograph/flexible_modes.yaml", []),
}


def fmt(v):
    return f"{v:#.4g}" if v != 0 else "0"


def figures(command, summary):
    out = []
    if command == "run":
        p = summary["pantographs"][0]
        for label, unit, key, scale in RUN_FIGURES:
            out.append((f"{label} [{unit}]", scale * p[key]))
        out.append(("maximum uplift at a support [mm]", 1e3 * summary["max_uplift_at_support_m"]))
    elif command == "pantograph":  # undamped frequencies, damped ones and their damping ratios
        for i, f in enumerate(summary["pantograph_frequencies_hz"][:20]):
            out.append((f"mode {i + 1:2d} frequency [Hz]", f))
        for i, m in enumerate(summary.get("damped_modes", [])[:20]):
            out.append((f"damped mode {i + 1:2d} frequency [Hz]", m["frequency_hz"]))
            out.append((f"damped mode {i + 1:2d} damping ratio [-]", m["damping_ratio"]))
    else:
        for i, f in enumerate(summary["catenary_frequencies_hz"][:20]):
            out.append((f"mode {i + 1:2d} frequency [Hz]", f))
    return out


def matches(value, expected_text):
    expected = float(expected_text)
    if expected == 0:
        return abs(value) < 5e-5  # prints as 0.0000 (loss of contact, percent)
    unit = 10 ** (math.floor(math.log10(abs(expected))) - 3)
    return abs(value - expected) <= 0.5 * unit + 1e-9 * abs(expected)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", choices=sorted(CASES))
    ap.add_argument("--bin", required=True, help="the pcsim executable")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--regenerate", action="store_true")
    args = ap.parse_args()
    regenerate = args.regenerate or os.environ.get("PCSIM_REGENERATE") == "1"
    command, scene, options = CASES[args.case]
    with tempfile.TemporaryDirectory() as tmp:
        outdir = os.path.join(tmp, "out")
        cmd = [os.path.join(ROOT, "scripts", "mpirun.sh"), "-n", str(args.ranks), args.bin, command,
               os.path.join(ROOT, scene), "-o", outdir, "--cache", os.path.join(tmp, "cache")] + options
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            sys.stdout.write(proc.stdout + proc.stderr)
            sys.exit(f"{args.case}: pcsim exited with {proc.returncode}")
        with open(os.path.join(outdir, "summary.json")) as f:
            summary = json.load(f)
    got = figures(command, summary)
    path = os.path.join(HERE, "expected", args.case + ".out")
    if regenerate:
        with open(path, "w") as f:
            for label, v in got:
                f.write(f"{label}: {fmt(v)}\n")
        print(f"regenerated {os.path.relpath(path, ROOT)}")
        return
    with open(path) as f:
        expected = [line.rstrip("\n").rsplit(": ", 1) for line in f if line.strip()]
    failures = 0
    if [e[0] for e in expected] != [g[0] for g in got]:
        sys.exit(f"{args.case}: the figures differ from {path}: {[e[0] for e in expected]}")
    for (label, text), (_, v) in zip(expected, got):
        ok = matches(v, text)
        failures += not ok
        print(f"{'ok  ' if ok else 'DIFF'} {label}: expected {text}, got {fmt(v)} ({v!r})")
    if failures:
        sys.exit(f"{args.case} on {args.ranks} rank(s): {failures} figure(s) differ; if the change is "
                 f"intended, regenerate with PCSIM_REGENERATE=1 and say why in the commit")
    print(f"{args.case} on {args.ranks} rank(s): all {len(got)} figures match")


if __name__ == "__main__":
    main()
