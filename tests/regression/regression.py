#!/usr/bin/python3
"""Regression figures of pcsim, compared in the SLEPc manner.

Each case runs pcsim, extracts the figures it publishes (the eight EN 50318
figures of a run, the first 20 frequencies of the catenary's modes, a
pantograph's frequencies and damping ratios), prints them with 4
significant digits and diffs them against the committed file
tests/regression/expected/<case>.out. The cases of DOC_CASES pin the
figures quoted in docs/ by running the command the page names: each figure
is printed as the page prints it (its format spec), so the expected file
holds the page's text.

A figure matches when the full-precision value rounds to the committed one:
|value - expected| <= half a unit of the last digit of the committed text
(+1e-9 relative, so that a value sitting on a rounding boundary is not
flagged for a round-off change). For the 4-digit figures that is half a unit
of the 4th significant digit: runs on different rank counts differ by ~1e-10
relative (tests/contact/test_run_ranks.sh), the cheap and full paths by up to
1.4e-4 (one expected file per path), so half a unit of the 4th digit (5e-4
relative at worst, 5e-5 at best) separates a genuine change from round-off.
For a docs figure it is half a unit of the digit the page prints: the test
fails when the page's figure no longer rounds from what the command gives.

usage: regression.py CASE|GROUP [...] --bin PCSIM [--ranks N] [--regenerate]
       regression.py --list
  Several cases (a GROUP names some) run in one temporary folder: one cache,
  and a pcsim command two cases give runs once; each is diffed against its
  own expected file.
  PCSIM_REGENERATE=1 in the environment also regenerates; then the .out file
  is rewritten and the test passes.
"""
import argparse
import json
import math
import os
import re
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
    # The reduced-order catenary at its default cut-off (docs/fidelity.md: also
    # the cut-off, the basis and the dropper checks); its modes are computed
    # afresh into a temporary cache (~1 min on 1 rank). Its records one at a
    # time, as by default where a core's level-2 cache holds the dropper rows
    # (ModalCatenary::records_batch_pays): the dropper checks' counts do not
    # then depend on the machine's cache.
    "en50318-300-modal": ("run", "runs/en50318-300-modal.yaml",
                          ["-pcsim_record_batches", "false"]),
    "en50318-static-modes": ("modes", "runs/en50318-static.yaml", []),
    # docs/pantograph.md's modes of the three pantograph models (seconds each).
    "pantograph-en50318-modes": ("pantograph", "runs/pantograph/en50318_modes.yaml", []),
    "pantograph-dsa380-modes": ("pantograph", "runs/pantograph/dsa380_modes.yaml", []),
    "pantograph-flexible-modes": ("pantograph", "runs/pantograph/flexible_modes.yaml", []),
}


def fmt(v):
    return f"{v:#.4g}" if v != 0 else "0"


def damping_ratio_text(v):
    """4 significant digits, none below 1e-10: a damping ratio's round-off is
    absolute (that of the eigenvalue's real part). The flexible DSA-380's mode
    6 (zeta 7e-8) reads 6.981e-08 with the reference BLAS, 6.980e-08 with BLIS
    and 6.979e-08 with OpenBLAS (2e-11 apart); half a unit of 1e-10 holds them."""
    return fmt(v) if abs(v) >= 1e-6 else f"{v:.10f}"


def doc(label, value, spec):
    """A figure of docs/ printed as the page prints it (format spec, e.g. ".1f")."""
    return (label, value, format(value, spec))


def modal_figures(summary):
    """docs/fidelity.md's figures of the modal catenary at its default cut-off."""
    m, a = summary["modal"], summary["accuracy_estimate"]
    # A mode at f shows at about f (1 - v/c): c from the highest frequency that matters.
    c = summary["speed_kmh"] / 3.6 / (1.0 - summary["analysis"]["cutoff_hz"]
                                      / a["highest_frequency_hz"])
    return [
        doc("default cut-off [Hz]", m["cutoff_hz"], ".1f"),  # docs print 0.1 Hz
        doc("basis vectors", m["basis_size"], "d"),  # a count: exact
        doc("wave speed c [m/s]", c, ".1f"),  # docs print 0.1 m/s
        # docs print 0.1 evaluations and 0.001 updates per step
        doc("exact dropper evaluations per step besides the exact anchors'",
            m["dropper_evaluations_per_step"]
            - m["exact_updates_per_step"] * m["tracked_bars"], ".1f"),
        doc("exact anchors per step", m["exact_updates_per_step"], ".3f"),
        doc("single-precision updates per step", m["single_precision_updates_per_step"], ".3f"),
        doc("half-precision updates per step", m["half_precision_updates_per_step"], ".3f"),
    ]


def figures(command, summary):
    out = []
    if command == "run":
        p = summary["pantographs"][0]
        for label, unit, key, scale in RUN_FIGURES:
            out.append((f"{label} [{unit}]", scale * p[key]))
        out.append(("maximum uplift at a support [mm]", 1e3 * summary["max_uplift_at_support_m"]))
        if "modal" in summary:
            out += modal_figures(summary)
    elif command == "pantograph":  # undamped frequencies, damped ones and their damping ratios
        for i, f in enumerate(summary["pantograph_frequencies_hz"][:20]):
            out.append((f"mode {i + 1:2d} frequency [Hz]", f))
        for i, m in enumerate(summary.get("damped_modes", [])[:20]):
            out.append((f"damped mode {i + 1:2d} frequency [Hz]", m["frequency_hz"]))
            out.append((f"damped mode {i + 1:2d} damping ratio [-]", m["damping_ratio"],
                        damping_ratio_text(m["damping_ratio"])))
    else:
        for i, f in enumerate(summary["catenary_frequencies_hz"][:20]):
            out.append((f"mode {i + 1:2d} frequency [Hz]", f))
    return out


# Figures of docs/catenary.md, docs/lines.md and docs/fidelity.md, each case
# running the commands the page names (one rank). A case is a function of
# `run`, which runs one pcsim command and returns (output folder, summary,
# console text); it returns the figures. The figures of docs/hard-cases.md are
# pinned by the hard tests themselves (tests/hard/hard_cases.py calls compare()).

def catenary_en50318(run):
    """docs/catenary.md: form-finding of the EN 50318 reference catenary (the
    test table's Newton iteration and control, the benchmark's 10-span row) and
    its lowest frequencies."""
    _, s, _ = run("static", "runs/en50318-static.yaml")
    r = s["snes_residual_history"]
    out = [doc("catenary unknowns", s["dofs"], "d"),  # a count: exact
           doc("Newton iterations", s["snes_iterations"], "d"),  # a count: exact
           doc("max height error at the droppers [m]", s["max_height_error_m"], ".0f")]  # docs print 0 m
    # docs print the residuals to 2 significant digits (26.8: 0.1 N); the
    # last one, at the round-off floor, differs with the rank count: not pinned
    for k, spec in enumerate((".1e", ".1e", ".1f", ".1e")):
        out.append(doc(f"Newton residual {k} [N]", r[k], spec))
    for k in range(3):  # docs print 2 significant digits (0.25: 0.01)
        out.append(doc(f"quadratic constant r{k + 1}/r{k}^2 [1/N]", r[k + 1] / r[k] ** 2, ".1e"))
        out.append(doc(f"contraction r{k + 1}/r{k}", r[k + 1] / r[k], ".2f" if k == 0 else ".1e"))
    _, s, _ = run("static", "runs/en50318-static.yaml", "--set", "catenary.form_finding=false")
    out += [doc("without form-finding: height error [mm]", 1e3 * s["max_height_error_m"],
                ".1f"),  # docs print 0.1 mm
            doc("without form-finding: tension error [%]", 100 * s["max_tension_error_rel"],
                ".2f")]  # docs print 0.01 %
    _, s, _ = run("modes", "runs/en50318-static.yaml")
    for i in (0, 1, 2, 3, 4, 19):  # docs print 1e-6 Hz
        out.append(doc(f"mode {i + 1:2d} frequency [Hz]", s["catenary_frequencies_hz"][i], ".6f"))
    return out


def catenary_100_spans(run):
    """docs/catenary.md, benchmark: the 100-span row (runs/bench_catenary.sh)."""
    _, s, _ = run("modes", "runs/en50318-static.yaml", "--set", "catenary.design.spans.count=100")
    return [doc("catenary unknowns", s["dofs"], "d"),  # a count: exact
            doc("Newton iterations", s["snes_iterations"], "d"),  # a count: exact
            doc("f1 [Hz]", s["catenary_frequencies_hz"][0], ".4f")]  # docs print 1e-4 Hz


def catenary_memory(run):
    """docs/catenary.md, memory estimate: `pcsim check` on 1000 and 100 000 spans."""
    def check(scene, use, spans):
        _, _, text = run("check", scene, "--as", use, "--set", f"catenary.design.spans.count={spans}",
                         may_fail=True)  # 100 000 spans are refused on machines below 212 GB
        found = [re.search(p, text) for p in (r"(\d+) nodes", r"(\d+) (?:catenary )?unknowns",
                                              r"estimated(?: memory)? ([\d.]+) GB")]
        if not all(found):
            sys.exit(f"pcsim check: no memory estimate in\n{text}")
        return [float(m.group(1)) for m in found]

    out = []
    for use, scene in (("static", "runs/en50318-static.yaml"), ("modes", "runs/en50318-static.yaml"),
                       ("run", "runs/en50318-300.yaml")):
        _, dofs, gb = check(scene, use, 1000)
        out.append(doc(f"1000 spans, {use}: estimate [GB]", gb, ".1f"))  # docs print 0.1 GB
    out.append(doc("1000 spans: catenary unknowns", int(dofs), "d"))  # a count: exact
    nodes, _, gb = check("runs/en50318-static.yaml", "static", 100000)
    out.append(doc("100000 spans: nodes", nodes, ".1e"))  # docs print 2.4e7
    out.append(doc("100000 spans: estimate [GB]", gb, ".0f"))  # docs print 1 GB
    return out


def lines_elasticity(variant):
    def case(run):
        """docs/lines.md, stitched and unstitched elasticity (runs/lines/elasticity.sh)."""
        out_dir, _, _ = run("static", f"runs/lines/elasticity-{variant}.yaml")
        with open(os.path.join(out_dir, "elasticity.csv")) as f:
            rows = [r.split(",") for r in f if r.strip() and not r.startswith("#")]
        e = {round(float(r[0]), 3): float(r[1]) for r in rows}
        out = [doc(f"uplift at {x} m [mm/100 N]", e[float(x)], ".1f")  # docs print 0.1 mm
               for x in range(240, 301, 5)]
        hi, lo = max(e.values()), min(e.values())
        x_lo = min(x for x in e if e[x] == lo)
        out += [doc("max [mm/100 N]", hi, ".1f"), doc("min [mm/100 N]", lo, ".1f"),  # 0.1 mm
                doc("max / min", hi / lo, ".2f"),  # docs print 0.01
                doc("non-uniformity [%]", 100 * (hi - lo) / (hi + lo), ".1f"),  # docs print 0.1 %
                # on the 0.5 m grid: exact
                doc("stiffest point from its support [m]", min(x_lo % 60, 60 - x_lo % 60), ".1f")]
        return out
    return case


def lines_irregular(rms_mm):
    def case(run):
        """docs/lines.md, contact-wire irregularities (runs/lines/irregularity-study.sh)."""
        import h5py
        out_dir, s, _ = run("run", "runs/lines/irregular-random-300.yaml", "--set",
                            f"catenary.design.irregularities.random.rms={rms_mm / 1000}", "--no-report")
        p, a = s["pantographs"][0], s["analysis"]
        out = [doc(f"{label} [N]", p[key], ".1f")  # docs print 0.1 N
               for label, key in (("mean", "mean_N"), ("sigma", "std_N"), ("max", "max_N"),
                                  ("min", "min_N"), ("mean + 3 sigma", "stat_max_N"),
                                  ("mean - 3 sigma", "stat_min_N"))]
        out.append(doc("loss of contact [%]", p["loss_of_contact_percent"], ".2f"))  # docs print 0.01 %
        with h5py.File(os.path.join(out_dir, "results.h5"), "r") as f:
            x = f[f"/pantographs/{p['name']}/position"][()]
            force = f[f"/pantographs/{p['name']}/contact_force"][()]
        force = force[(x >= a["from_x"]) & (x <= a["to_x"])]
        for label, v in (("mean", force.mean()), ("sigma", force.std()), ("max", force.max()),
                         ("min", force.min())):
            out.append(doc(f"unfiltered {label} [N]", float(v), ".1f"))  # docs print 0.1 N
        return out
    return case


def fidelity_time_step(run):
    """docs/fidelity.md: the accuracy estimate's warning for runs/en50318-300.yaml at dt 2 ms."""
    _, s, text = run("run", "runs/en50318-300.yaml", "-ts_dt", "2e-3", "-ts_max_steps", "5",
                     "--no-report")
    m = re.search(r"warning: the time step is outside the converged region \(sigma error ~([\d.]+) %\): "
                  r"use -ts_dt ([\d.]+) \(or smaller\)", text)
    if not m:
        sys.exit(f"no time-step warning in\n{text}")
    if "an accuracy pilot's discretisation estimate is then an indication, not a bound" not in text:
        sys.exit(f"no word on the pilot's discretisation estimate under the warning in\n{text}")
    a = s["accuracy_estimate"]
    return [doc("highest frequency that matters [Hz]", a["highest_frequency_hz"], ".1f"),  # 0.1 Hz
            doc("steps per period", a["criteria"][0]["value"], ".1f"),  # docs print 0.1
            doc("estimated sigma error [%]", a["criteria"][0]["estimated_sigma_error_percent"],
                ".1f"),  # docs print 0.1 % (the table; the warning rounds it)
            doc("warning: sigma error [%]", float(m.group(1)), ".0f"),  # the warning prints 1 %
            doc("warning: advised dt [s]", float(m.group(2)), ".4f")]  # the warning prints 0.1 ms


def fidelity_cheap_path(run):
    """docs/fidelity.md, nonlinear pantographs on the cheap path: Newton iterations per step."""
    _, s, _ = run("run", "runs/interaction/dsa380-300-base.yaml", "-ts_max_steps", "2000", "--no-report")
    out = [doc("DSA-380, linear FE: unknowns", s["dofs"], "d"),  # a count: exact
           doc("DSA-380, linear FE: Newton iterations per step", s["newton_iterations_per_step"],
               ".3f")]  # docs print 0.001
    _, s, _ = run("run", "runs/en50318-300.yaml", "-ts_max_steps", "2000", "--no-report")
    out.append(doc("lumped pantograph, linear FE: Newton iterations per step",
                   s["newton_iterations_per_step"], ".3f"))  # docs print 0.001
    return out


def bench_table():
    """runs/bench/fast_level_table.py (errors() of one run against another)."""
    sys.path.insert(0, os.path.join(ROOT, "runs", "bench"))
    import fast_level_table
    return fast_level_table


def readme_fast_level(run):
    """README, "The fast level on other scenes": en50318-300's row of the
    table of every figure's error against linear FE and the run's own
    (pilot's) estimate of it, and the cut-off and basis the pilot keeps
    (runs/bench_fast_level.sh's two runs; about 2 minutes)."""
    table = bench_table()
    scene = "runs/interaction/en50318-300.yaml"
    _, fe, _ = run("run", scene, "--set", "catenary.model=linear", "-pcsim_accuracy_pilot", "false",
                   "--no-report")
    _, modal, _ = run("run", scene, "--set", "catenary.model=modal", "-pcsim_accuracy_pilot", "true",
                      "--no-report")
    e = table.errors(fe["pantographs"][0], modal["pantographs"][0], fe, modal)
    estimate = modal["accuracy_estimate"]["pilot"]["reduction"][0]
    out = [doc("cut-off [Hz]", modal["modal"]["cutoff_hz"], ".1f"),  # README prints 0.1 Hz
           doc("basis vectors", modal["modal"]["basis_size"], "d")]  # a count: exact
    for key, figure in table.PILOT_KEYS.items():  # README prints 0.01 (% or points)
        out += [doc(f"{figure} error", e[figure], "+.2f"),
                doc(f"{figure} estimate", estimate[key], ".2f")]
    return out


def fidelity_slack_exact(run):
    """docs/fidelity.md, "A slack dropper's geometric stiffness": the rows of
    en50318-300 and en50318-250 (linear FE and the modal level at 69.7 and
    64.0 Hz with bars slack, then slack_exact; pilot off; about 45 s, the
    modes of 69.7 Hz computed once for both)."""
    table = bench_table()
    out = []
    for speed, cutoff in ((300, "69.7"), (250, "64.0")):
        scene = f"runs/interaction/en50318-{speed}.yaml"
        _, fe, _ = run("run", scene, "--set", "catenary.model=linear", "-pcsim_accuracy_pilot", "false",
                       "--no-report")
        for bars in ("slack", "slack_exact"):
            _, modal, _ = run("run", scene, "--set", "catenary.model=modal", "--set",
                              f"catenary.max_frequency_hz={cutoff}", "--set",
                              f"catenary.modal.bars={bars}", "-pcsim_accuracy_pilot", "false",
                              "--no-report")
            e = table.errors(fe["pantographs"][0], modal["pantographs"][0], fe, modal)
            for figure in ("sigma", "Fm+3s", "max", "Fm-3s", "uplift", "loss"):  # the page prints 0.01
                out.append(doc(f"{speed} km/h, {bars}: {figure} error", e[figure], "+.2f"))
    return out


DOC_CASES = {
    "catenary-en50318": catenary_en50318,
    "catenary-100-spans": catenary_100_spans,  # ~15 s (modes of 100 spans)
    "catenary-memory": catenary_memory,
    "lines-elasticity-stitched": lines_elasticity("stitched"),  # ~15 s each
    "lines-elasticity-unstitched": lines_elasticity("unstitched"),
    "lines-irregular-0mm": lines_irregular(0),  # ~15 s each (7080 steps)
    "lines-irregular-0.5mm": lines_irregular(0.5),
    "lines-irregular-1mm": lines_irregular(1),
    "lines-irregular-2mm": lines_irregular(2),
    "fidelity-time-step": fidelity_time_step,
    "fidelity-cheap-path": fidelity_cheap_path,
    "readme-fast-level": readme_fast_level,  # ~2 min (a pilot of 3 runs, modes included)
    "fidelity-slack-exact": fidelity_slack_exact,  # ~45 s (6 runs, the modes of 69.7 Hz once)
}

# Cases run together, by one name: they share the EN 50318 line's basis at
# 69.7 Hz and a linear FE run (89 s for the three, against 18 + 50 + 39 s one
# by one, idle machine, 2026-12-07).
GROUPS = {
    "en50318-modal-cases": ["en50318-300-modal", "readme-fast-level", "fidelity-slack-exact"],
}


def matches(value, expected_text):
    expected = float(expected_text)
    if expected_text == "0":
        return abs(value) < 5e-5  # prints as 0.0000 (loss of contact, percent)
    mantissa, _, exponent = expected_text.lower().partition("e")
    unit = 10.0 ** (int(exponent or 0) - len(mantissa.partition(".")[2]))  # of the last digit
    return abs(value - expected) <= 0.5 * unit + 1e-9 * abs(expected)


def runner(binary, ranks, tmp):
    """run(command, scene, *options): pcsim into a new folder of tmp, one cache
    for all; a command given again returns its first run's results."""
    count = [0]
    done = {}

    def run(command, scene, *options, may_fail=False):
        key = (command, scene, options, may_fail)
        if key in done:
            return done[key]
        count[0] += 1
        out_dir = os.path.join(tmp, f"out{count[0]}")
        cmd = [os.path.join(ROOT, "scripts", "mpirun.sh"), "-n", str(ranks), binary, command,
               os.path.join(ROOT, scene), "-o", out_dir, "--cache", os.path.join(tmp, "cache")]
        proc = subprocess.run(cmd + list(options), capture_output=True, text=True)
        if proc.returncode != 0 and not may_fail:
            sys.stdout.write(proc.stdout + proc.stderr)
            sys.exit(f"{' '.join(cmd + list(options))}: pcsim exited with {proc.returncode}")
        summary = None
        if os.path.exists(os.path.join(out_dir, "summary.json")):
            with open(os.path.join(out_dir, "summary.json")) as f:
                summary = json.load(f)
        done[key] = out_dir, summary, proc.stdout + proc.stderr
        return done[key]
    return run


def compare(case, got, ranks=1, regenerate=False):
    """Diffs the figures (label, value[, printed text]) against expected/<case>.out."""
    got = [g if len(g) == 3 else (g[0], g[1], fmt(g[1])) for g in got]
    path = os.path.join(HERE, "expected", case + ".out")
    if regenerate:
        with open(path, "w") as f:
            for label, _, text in got:
                f.write(f"{label}: {text}\n")
        print(f"regenerated {os.path.relpath(path, ROOT)}")
        return
    with open(path) as f:
        expected = [line.rstrip("\n").rsplit(": ", 1) for line in f if line.strip()]
    failures = 0
    if [e[0] for e in expected] != [g[0] for g in got]:
        sys.exit(f"{case}: the figures differ from {path}: {[e[0] for e in expected]}")
    for (label, text), (_, v, printed) in zip(expected, got):
        ok = matches(v, text)
        failures += not ok
        print(f"{'ok  ' if ok else 'DIFF'} {label}: expected {text}, got {printed} ({v!r})")
    if failures:
        sys.exit(f"{case} on {ranks} rank(s): {failures} figure(s) differ; if the change is "
                 f"intended, regenerate with PCSIM_REGENERATE=1 and say why in the commit")
    print(f"{case} on {ranks} rank(s): all {len(got)} figures match")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    # Several cases (or a group of GROUPS) run with one runner: the same cache
    # (a basis computed once), a command two cases give run once; each case
    # is compared with its own expected file.
    ap.add_argument("cases", nargs="*", metavar="case", help="one or more of --list")
    ap.add_argument("--bin", help="the pcsim executable")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--regenerate", action="store_true")
    ap.add_argument("--list", action="store_true", help="list the cases")
    args = ap.parse_args()
    if args.list or not args.cases:
        print("cases: " + " ".join(list(CASES) + list(DOC_CASES)))
        print("groups: " + " ".join(f"{g} ({' '.join(c)})" for g, c in GROUPS.items()))
        return
    args.cases = [c for name in args.cases for c in GROUPS.get(name, [name])]
    unknown = [c for c in args.cases if c not in CASES and c not in DOC_CASES]
    if unknown:
        ap.error(f"unknown case(s) {' '.join(unknown)}; --list lists them")
    if not args.bin:
        ap.error("--bin is required")
    regenerate = args.regenerate or os.environ.get("PCSIM_REGENERATE") == "1"
    with tempfile.TemporaryDirectory() as tmp:
        run = runner(args.bin, args.ranks, tmp)
        results = []
        for case in args.cases:
            if case in DOC_CASES:
                results.append((case, DOC_CASES[case](run)))
            else:
                command, scene, options = CASES[case]
                _, summary, _ = run(command, scene, *options)
                results.append((case, figures(command, summary)))
    failed = []
    for case, got in results:
        try:
            compare(case, got, args.ranks, regenerate)
        except SystemExit as e:  # every case reported before the exit
            print(e)
            failed.append(case)
    if failed:
        sys.exit(f"differ: {' '.join(failed)}")


if __name__ == "__main__":
    main()
