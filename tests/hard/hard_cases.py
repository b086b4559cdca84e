#!/usr/bin/python3
"""Hard cases of runs/hard/ as CI tests (ctest -L hard) and as a table.

  hard_cases.py CASE --bin build/pcsim [--ranks N] [--full] [--keep DIR]
  hard_cases.py --list

Each case runs its scene shortened (the full scene with --full), with
output.energy on, and asserts on the outputs what docs/hard-cases.md states:
the run completes, nothing in results.h5, energy.h5 or summary.json is NaN
or Inf, Newton iterations per step stay below the case's bound, the energy
balance E - E0 = W_ext + W_diss holds within the case's tolerance, contact
force and uplift stay below the bounds derived in BOUNDS below, and the
effect the case is about shows in the shortened run. The rank case compares
1, 2 and 3 ranks to 1e-9. The shortened run's figures of docs/hard-cases.md's
table (all but ms/step) are then diffed against
tests/regression/expected/hard-<case>.out at the digits the table prints
(tests/regression/regression.py; PCSIM_REGENERATE=1 rewrites the file).
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(SOURCE, "tests", "regression"))
import regression  # noqa: E402  (compare() and the expected files)

# Shortened single-pantograph runs on the EN 50318 line: 5 -> 185 m, three
# spans, the statistics over spans 2-3 (60-180 m).
SHORT = ["simulation.end_x=185", "analysis.from_span=2", "analysis.to_span=3"]

# Bounds on the contact force and the uplift at the supports (derivation).
# The contact wire is a tensioned string on an elastic foundation (droppers
# and messenger); a constant force F moving at v deflects it by
# F / (2 sqrt(k T (1 - b^2))), b = v / c (Fryba, moving loads): the dynamic
# amplification over the static deflection is 1 / sqrt(1 - b^2). The
# pantograph's force oscillates about F0; EN 50318 at 300 km/h allows an
# actual maximum of 1.9 F0 (225 N for 120 N), i.e. F0 + 0.9 F0 at b = 0.685
# (amplification 1.37). We bound the force by F0 (1 + 2 / sqrt(1 - b^2)): the
# oscillation twice the standard's, scaled by the amplification. The uplift
# is bounded by the static uplift under that force at the softest point of a
# span: 42.0 mm per 100 N (24.6 at the supports), measured with
#   build/pcsim static runs/en50318-elasticity.yaml
# A run that injects energy (a wrong sign in a power, an unstable step) breaks
# both within a few spans; the test prints the ratio to the bound.
WAVE_SPEED_KMH = 438.0  # contact wire of meshes/en50318-reference.yaml
UPLIFT_PER_NEWTON = 0.42e-3  # m/N, largest static uplift under a point load


def force_bound(static_force, speed_kmh):
    b = speed_kmh / WAVE_SPEED_KMH
    return static_force * (1.0 + 2.0 / math.sqrt(1.0 - b * b))


# name: scene, --set overrides, PETSc options, Newton bound (iterations per
# step), energy tolerance (largest |E - E0 - W_ext - W_diss| as a fraction of
# the energy turnover), speed, static force, effect and its threshold.
# Measured on the shortened runs (runs/hard/run_hard.sh --short, 2026-11-27;
# docs/hard-cases.md), Newton iterations per step / energy residual over
# turnover: reference 1.03/7.1e-3, wave-090 1.25/6.6e-3, wave-095 1.39/6.9e-3,
# stiff-contact 1.16/1.3e-2, dt-5ms 1.99/0.32, dt-10ms 2.47/0.47,
# loss-of-contact 1.01/9.9e-3, gap-landing 1.04/7.1e-3, slack-droppers
# 1.50/4.2e-3, five-pantographs 1.49/1.0e-2, dsa380-damper-friction
# 1.07/6.3e-3, nonlinear-380 2.00/5.7e-3, undamped 1.72/1.3e-2, rejection
# 1.91/0.29. The bounds are 1.25-1.4 times the iterations and 1.4-1.9 times the
# residuals (2.8 for the gap landing, whose residual was 1.2e-2 on 2026-11-22):
# a Newton that stalls or a term whose power is missing (the moving contact's
# alone is 30-60 % of W_ext) breaks them. The residual is numerical
# dissipation (its positive part is checked separately): HHT-alpha's, larger
# at 5 and 10 ms where it removes most of the energy above 20 Hz, and that of
# the switching laws.
CASES = {
    "reference": dict(scene="../en50318-300", set=SHORT, newton=1.3, energy=0.01, speed=300,
                      f0=120, effect="none"),
    "wave-090": dict(scene="wave-090", set=SHORT, newton=1.6, energy=0.01, speed=394, f0=120,
                     effect=("slack", 70)),
    "wave-095": dict(scene="wave-095", set=SHORT, newton=1.8, energy=0.01, speed=416, f0=120,
                     effect=("loss", 5.0)),
    "stiff-contact": dict(scene="stiff-contact", set=SHORT, newton=1.5, energy=0.02, speed=300,
                          f0=120, effect=("loss", 0.5)),
    "dt-5ms": dict(scene="dt-5ms", set=SHORT, newton=2.6, energy=0.45, speed=300, f0=120,
                   effect="warn", injection=5e-4),
    "dt-10ms": dict(scene="dt-10ms", set=SHORT, newton=3.2, energy=0.65, speed=300, f0=120,
                    effect="warn", injection=2e-3),
    "loss-of-contact": dict(scene="loss-of-contact", set=SHORT, newton=1.3, energy=0.015,
                            speed=350, f0=40, effect=("loss", 5.0)),
    "gap-landing": dict(scene="gap-landing", set=SHORT, newton=1.3, energy=0.02, speed=300,
                        f0=120, effect="landing", injection=6e-3),
    "slack-droppers": dict(scene="slack-droppers", set=SHORT, newton=1.9, energy=0.008,
                           speed=380, f0=250, effect=("slack", 70)),
    "five-pantographs": dict(scene="five-pantographs",
                             set=["simulation.end_x=505", "analysis.from_span=5",
                                  "analysis.to_span=5"],
                             newton=1.9, energy=0.015, speed=300, f0=120,
                             effect=("loss", 2.0)),
    "dsa380-damper-friction": dict(scene="dsa380-damper-friction", set=SHORT, newton=1.4,
                                   energy=0.01, speed=300, f0=120, effect="dissipation"),
    "nonlinear-380": dict(scene="nonlinear-380",
                          set=["simulation.end_x=125", "analysis.from_span=2",
                               "analysis.to_span=2"],
                          newton=2.6, energy=0.01, speed=380, f0=120, effect=("loss", 0.2)),
    "undamped": dict(scene="undamped", set=SHORT, newton=2.2, energy=0.02, speed=300, f0=120,
                     effect="undamped"),
    "rejection": dict(scene="rejection", set=SHORT, options=["-snes_max_it", "2"], newton=2.7,
                      energy=0.45, speed=300, f0=120, effect="rejection", injection=2e-3),
    "ranks": dict(scene="slack-droppers",
                  set=["pantographs.0.start_x=58", "simulation.end_x=122",
                       "analysis.from_span=2", "analysis.to_span=2"],
                  newton=1.9, energy=0.01, speed=380, f0=250, effect="ranks"),
}


def run_case(args, case, ranks, out):
    c = CASES[case]
    cmd = [os.path.join(SOURCE, "scripts", "mpirun.sh"), "-n", str(ranks), args.bin, "run",
           os.path.join(SOURCE, "runs", "hard", c["scene"] + ".yaml"), "-o", out, "--no-report",
           "--set", "output.energy=true"]
    if not args.full:
        for s in c["set"]:
            cmd += ["--set", s]
    cmd += c.get("options", [])
    p = subprocess.run(cmd, capture_output=True, text=True)
    sys.stdout.write(p.stdout)
    sys.stderr.write(p.stderr)
    if p.returncode != 0:
        fail(f"{case}: pcsim exited with {p.returncode}")
    return p.stdout + p.stderr


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def check(cond, msg):
    print(("  ok   " if cond else "  FAIL ") + msg)
    if not cond:
        sys.exit(1)


def all_finite(path):
    bad = []

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f":
            if not np.all(np.isfinite(obj[()])):
                bad.append(name)

    with h5py.File(path, "r") as f:
        f.visititems(visit)
    return bad


def all_finite_json(value):
    if isinstance(value, dict):
        return all(all_finite_json(v) for v in value.values())
    if isinstance(value, list):
        return all(all_finite_json(v) for v in value)
    if isinstance(value, float):
        return math.isfinite(value)
    return True


def slack_events(results):
    """Dropper transitions from taut to slack (force <= 0) over the run."""
    with h5py.File(results, "r") as f:
        if "droppers/force" not in f:
            return 0
        taut = f["droppers/force"][()] > 1e-9
    return int(np.sum(taut[:-1] & ~taut[1:]))


def read_outputs(out):
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return summary


def assert_case(case, out, text):
    c = CASES[case]
    summary = read_outputs(out)
    for name in ("results.h5", "energy.h5"):
        bad = all_finite(os.path.join(out, name))
        check(not bad, f"{name}: every float dataset finite ({bad or 'all'})")
    check(all_finite_json(summary), "summary.json: every number finite")
    its = summary["newton_iterations_per_step"]
    check(its < c["newton"], f"Newton iterations per step {its:.2f} < {c['newton']}")
    e = summary["energy"]
    ratio = e["max_balance_residual_J"] / e["turnover_J"]
    injected = e["max_energy_injection_J"] / e["turnover_J"]
    check(ratio < c["energy"],
          f"energy balance: max |E - E0 - W_ext - W_diss| = {e['max_balance_residual_J']:.3g} J "
          f"= {ratio:.2e} of the turnover {e['turnover_J']:.4g} J < {c['energy']}")
    # HHT-alpha and the switching laws may only remove energy: the positive
    # part of the residual (energy created by the integration) stays at the
    # quadrature's level, measured <= 2.2e-5 of the turnover (stiff contact),
    # hence 1e-4. The gap landing is the exception: the contact switches on
    # inside a step at the impact, and the penalty spring's energy at the first
    # step in contact counts as created (measured 4.4e-3 of the turnover on
    # 2026-11-22, 9.9e-8 on 2026-11-27: the bound is kept for a landing inside
    # a step); and the large steps, where the trapezoidal work integrals lose
    # accuracy (second order in dt: measured 1.7e-4 at 5 ms).
    check(injected < c.get("injection", 1e-4),
          f"no energy created: max (E - E0 - W_ext - W_diss) = {injected:.2e} of the turnover "
          f"< {c.get('injection', 1e-4)}")
    bound = force_bound(c["f0"], c["speed"])
    with h5py.File(os.path.join(out, "results.h5"), "r") as f:
        forces = [g["contact_force"][()] for g in f["pantographs"].values()]
        uplift = f["supports/uplift"][()]
    fmax = max(float(np.max(fc)) for fc in forces)
    fmin = min(float(np.min(fc)) for fc in forces)
    check(fmin >= 0.0, f"contact force never pulls: min {fmin:.3g} N >= 0")
    check(fmax < bound, f"contact force max {fmax:.1f} N < bound {bound:.1f} N "
          f"(ratio {fmax / bound:.2f})")
    umax = float(np.max(uplift))
    ubound = UPLIFT_PER_NEWTON * bound
    check(umax < ubound, f"uplift at the supports max {1e3 * umax:.1f} mm < bound "
          f"{1e3 * ubound:.1f} mm (ratio {umax / ubound:.2f})")
    effect(case, c["effect"], out, text, summary, e, forces)
    return summary


def effect(case, kind, out, text, summary, e, forces):
    events = slack_events(os.path.join(out, "results.h5"))
    loss = max(100.0 * float(np.mean(fc <= 0.0)) for fc in forces)
    print(f"  slack events {events}, loss of contact {loss:.2f} % of the steps")
    kind, threshold = kind if isinstance(kind, tuple) else (kind, None)
    if kind == "slack":
        # The reference run has 45 slack events over these spans (measured,
        # case 'reference'): the threshold is 1.5 times that.
        check(events > threshold, f"droppers slacken: {events} events > {threshold}")
    elif kind == "loss":
        # The reference run never leaves the wire over these spans.
        check(loss > threshold, f"the head leaves the wire: {loss:.2f} % of the steps > {threshold} %")
    elif kind == "warn":
        check(re.search(r"warning: the time step", text) is not None,
              "the run warns that its time step is outside the converged region")
    elif kind == "landing":
        fc = forces[0]
        first = int(np.argmax(fc > 0.0))
        check(fc[0] == 0.0 and first > 0,
              f"the head starts off the wire and lands after {first} steps")
    elif kind == "dissipation":
        check(e["work_dissipated_J"] < 0.0,
              f"damper and friction dissipate: W_diss = {e['work_dissipated_J']:.3g} J < 0")
    elif kind == "undamped":
        # Only the pantograph's own damper dissipates: 2.2 J of W_ext 38.5 J
        # (the damped reference: 27.3 of 48.1 J over the same spans).
        check(abs(e["work_dissipated_J"]) < 0.1 * e["work_external_J"],
              f"little dissipates: |W_diss| = {abs(e['work_dissipated_J']):.3g} J < 0.1 W_ext")
        check(e["energy_change_J"] > 0.5 * e["work_external_J"],
              f"the energy the contact puts in stays: E - E0 = {e['energy_change_J']:.3g} J "
              f"> half of W_ext = {e['work_external_J']:.3g} J")
    elif kind == "rejection":
        check(summary["rejected_steps"] > 0,
              f"steps rejected and retried: {summary['rejected_steps']}")


def table_figures(out, summary):
    """The figures of a row of docs/hard-cases.md's table (postproc/hard_cases.py), as it prints
    them: the tolerance is half a unit of the printed digit."""
    doc = regression.doc
    e = summary["energy"]
    with h5py.File(os.path.join(out, "results.h5"), "r") as f:
        fmax = max(float(np.max(g["contact_force"][()])) for g in f["pantographs"].values())
        uplift = 1e3 * float(np.max(f["supports/uplift"][()]))
    got = [doc("Newton iterations per step", summary["newton_iterations_per_step"], ".2f")]  # 0.01
    for name, p in summary["en50318"].items():
        fig = {x["key"]: x["value"] for x in p["figures"]}
        got += [doc(f"{name}: sigma [N]", fig["std_N"], ".1f"),  # the table prints 0.1 N
                # the table prints 0.01 %
                doc(f"{name}: loss of contact [%]", fig["loss_of_contact_percent"], ".2f")]
    return got + [
        doc("slack events", slack_events(os.path.join(out, "results.h5")), "d"),  # a count: exact
        doc("max force [N]", fmax, ".0f"), doc("max uplift [mm]", uplift, ".0f"),  # 1 N, 1 mm
        doc("W_ext [J]", e["work_external_J"], ".1f"),  # the table prints 0.1 J
        doc("W_diss [J]", e["work_dissipated_J"], ".1f"),
        # the table prints 2 significant digits
        doc("balance residual / turnover", e["max_balance_residual_J"] / e["turnover_J"], ".1e"),
        doc("rejected steps", summary.get("rejected_steps", 0), "d")]  # a count: exact


def pin_figures(args, case, out, ranks):
    if not args.full:  # the expected figures are those of the shortened run
        regression.compare(f"hard-{case}", table_figures(out, read_outputs(out)), ranks,
                           os.environ.get("PCSIM_REGENERATE") == "1")


def compare_ranks(outs):
    """Contact force, pantograph coordinates and dropper forces on 1, 2, 3 ranks."""
    ref = h5py.File(os.path.join(outs[0], "results.h5"), "r")
    for out in outs[1:]:
        with h5py.File(os.path.join(out, "results.h5"), "r") as f:
            for name in ("pantographs/pantograph/contact_force", "pantographs/pantograph/q",
                         "droppers/force", "supports/uplift"):
                a, b = ref[name][()], f[name][()]
                scale = max(float(np.max(np.abs(a))), 1e-30)
                diff = float(np.max(np.abs(a - b))) / scale
                check(diff < 1e-9, f"{out}: {name} equals 1 rank to {diff:.1e} < 1e-9 (relative)")


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", nargs="?", help="one of --list")
    ap.add_argument("--bin", default=os.path.join(SOURCE, "build", "pcsim"))
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--full", action="store_true", help="the whole scene, not shortened")
    ap.add_argument("--keep", help="write the results under this folder and keep them")
    args = ap.parse_args()
    if not args.case or args.case not in CASES:
        print("cases: " + " ".join(CASES))
        return 0 if not args.case else 2
    root = args.keep or tempfile.mkdtemp(prefix="pcsim-hard-")
    os.makedirs(root, exist_ok=True)
    if CASES[args.case]["effect"] == "ranks":
        outs = []
        for ranks in (1, 2, 3):
            out = os.path.join(root, f"{args.case}-np{ranks}")
            text = run_case(args, args.case, ranks, out)
            assert_case(args.case, out, text)
            pin_figures(args, args.case, out, ranks)
            outs.append(out)
        compare_ranks(outs)
    else:
        out = os.path.join(root, args.case)
        text = run_case(args, args.case, args.ranks, out)
        assert_case(args.case, out, text)
        pin_figures(args, args.case, out, args.ranks)
    print(f"PASS {args.case}")
    if not args.keep:
        shutil.rmtree(root)  # kept on failure, for inspection
    return 0


if __name__ == "__main__":
    sys.exit(main())
