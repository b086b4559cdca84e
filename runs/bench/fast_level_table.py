"""Table of runs/bench_fast_level.sh: the reduced (modal) level against linear FE.

usage: /usr/bin/python3 runs/bench/fast_level_table.py WORK_DIR SCENE_NAME...
WORK_DIR/<scene>/linear and WORK_DIR/<scene>/modal hold the two runs (their
summary.json). For every pantograph of every scene: the modal run's error
against linear FE at the same dt and mesh (issue 21's figures: mean, sigma,
Fm+3s and actual maximum relative; Fm-3s and actual minimum as % of Fm;
uplift relative; loss of contact in percentage points), its own accuracy
estimate, its cost (set-up, ms/step, real-time factor, step-time
percentiles, peak memory) and whether every figure meets the targets
(mean 0.5 %, sigma/Fm+3s/max 1 %, uplift 2 %, loss of contact 0.1 pp), the
modal method and basis, and how many of the pilot's eight reduction
estimates hold (at or above the actual error, at most 3 x actual + 0.3).
"""
import json
import os
import sys

TARGETS = {"mean": 0.5, "sigma": 1.0, "Fm+3s": 1.0, "max": 1.0, "uplift": 2.0, "loss": 0.1}


def load(folder):
    path = os.path.join(folder, "summary.json")
    return json.load(open(path)) if os.path.exists(path) else None


def errors(fe, modal, fe_run, modal_run):
    """Issue 21's error figures of one pantograph, in % (loss: percentage points)."""
    fm = fe["mean_N"]

    def rel(key):
        return 100.0 * (modal[key] - fe[key]) / abs(fe[key])

    def of_fm(key):
        return 100.0 * (modal[key] - fe[key]) / abs(fm)

    uplift_fe = fe_run["max_uplift_at_support_m"]
    uplift = 100.0 * (modal_run["max_uplift_at_support_m"] - uplift_fe) / abs(uplift_fe)
    return {
        "mean": rel("mean_N"), "sigma": rel("std_N"), "Fm+3s": rel("stat_max_N"),
        "max": rel("max_N"), "Fm-3s": of_fm("stat_min_N"), "min": of_fm("min_N"),
        "uplift": uplift,
        "loss": modal["loss_of_contact_percent"] - fe["loss_of_contact_percent"],
    }


def passes(e):
    return all(abs(e[k]) <= t for k, t in TARGETS.items())


# errors()'s figures, in the tables' order.
FIGURES = ("mean", "sigma", "Fm+3s", "max", "Fm-3s", "min", "uplift", "loss")
# The pilot's figures (simulation/accuracy_pilot.hpp) against errors()'s.
PILOT_KEYS = {"mean_percent": "mean", "sigma_percent": "sigma", "mean_plus_3sigma_percent": "Fm+3s",
              "actual_max_percent": "max", "uplift_percent": "uplift",
              "mean_minus_3sigma_percent_of_mean": "Fm-3s", "actual_min_percent_of_mean": "min",
              "loss_of_contact_points": "loss"}


def estimates_held(pilot_row, e):
    """'k/n': the pilot's estimates at or above |actual| and at most 3 |actual| + 0.3."""
    if not pilot_row:
        return "-"
    held = [abs(e[k]) <= pilot_row[key] <= 3 * abs(e[k]) + 0.3
            for key, k in PILOT_KEYS.items() if key in pilot_row]
    return f"{sum(held)}/{len(held)}"


def method(modal_run):
    m = modal_run.get("modal", {})
    if not m:
        return "-"
    return f"{m.get('method', 'whole')} {m.get('cutoff_hz', float('nan')):.1f} Hz ({m.get('basis_size', 0)})"


def row(scene, fe_run, modal_run):
    cells = []
    st = modal_run.get("step_time", {})
    cost = (f"{modal_run.get('setup_s', float('nan')):.1f} | {modal_run['time_per_step_ms']:.3f} | "
            f"{modal_run['real_time_factor']:.1f} | {st.get('median_ms', float('nan')):.3f} / "
            f"{st.get('p99_99_ms', float('nan')):.3f} / "
            f"{st.get('max_without_context_switch_ms', float('nan')):.3f} | "
            f"{modal_run['peak_memory_mb']:.0f} | {fe_run['time_per_step_ms']:.3f}")
    estimate = modal_run.get("accuracy_estimate", {})
    calibrated = "-"
    for c in estimate.get("criteria", []):
        if c.get("name") == "modal cut-off":
            calibrated = f"{c.get('estimated_sigma_error_percent', float('nan')):.2f}"
    # The pilot's reduction estimate of σ per pantograph (docs/fidelity.md),
    # else the calibrated one.
    pilot_rows = {p["pantograph"]: p for p in estimate.get("pilot", {}).get("reduction", [])}
    pilot = {name: p["sigma_percent"] for name, p in pilot_rows.items()}
    for fe, modal in zip(fe_run["pantographs"], modal_run["pantographs"]):
        sigma_estimate = f"{pilot[fe['name']]:.2f}" if fe["name"] in pilot else calibrated
        if "std_N" not in fe or "std_N" not in modal:
            cells.append(f"| {scene} | {fe['name']} | (no statistics) |")
            continue
        e = errors(fe, modal, fe_run, modal_run)
        figures = " | ".join(f"{e[k]:+.2f}" for k in FIGURES)
        held = estimates_held(pilot_rows.get(fe["name"]), e)
        cells.append(f"| {scene} | {fe['name']} | {method(modal_run)} | {figures} | "
                     f"{sigma_estimate} | {held} | {'yes' if passes(e) else '**no**'} | {cost} |")
    return cells


def estimate_rows(scene, fe_run, modal_run):
    """Every figure's actual error and, in brackets, the pilot's reduction estimate."""
    pilot = {p["pantograph"]: p for p in
             modal_run.get("accuracy_estimate", {}).get("pilot", {}).get("reduction", [])}
    by_figure = {k: key for key, k in PILOT_KEYS.items()}
    cells = []
    for fe, modal in zip(fe_run["pantographs"], modal_run["pantographs"]):
        if "std_N" not in fe or "std_N" not in modal:
            continue
        e = errors(fe, modal, fe_run, modal_run)
        p = pilot.get(fe["name"], {})
        figures = " | ".join(
            f"{e[k]:+.2f} ({p[by_figure[k]]:.2f})" if by_figure[k] in p else f"{e[k]:+.2f} (-)"
            for k in FIGURES)
        cells.append(f"| {scene} | {fe['name']} | {figures} |")
    return cells


def main():
    work, scenes = sys.argv[1], sys.argv[2:]
    print("| scene | pantograph | method, cut-off (vectors) | mean % | σ % | Fm+3σ % | max % | "
          "Fm−3σ %Fm | min %Fm | uplift % | loss pp | estimated σ % | estimates held | "
          "targets met | set-up s | ms/step | RTF | step median / p99.99 / max* ms | memory MB | "
          "linear FE ms/step |")
    print("|" + "---|" * 20)
    runs = {scene: (load(os.path.join(work, scene, "linear")),
                    load(os.path.join(work, scene, "modal"))) for scene in scenes}
    for scene, (fe_run, modal_run) in runs.items():
        if not fe_run or not modal_run:
            print(f"| {scene} | (a run failed: see {work}/{scene}/*.log) |")
            continue
        for line in row(scene, fe_run, modal_run):
            print(line)
    print("\n*max: over the steps without an involuntary context switch, the first step apart. "
          "set-up: the run's own, its modes read from the cache its pilot filled; the pilot's "
          "runs (the rest of a first run's set-up) are timed in OUT/SCENE/modal.log (\"pilot runs in\")")
    print("\nEvery figure's actual error against linear FE and, in brackets, the run's own "
          "estimate of it (the pilot's reduction estimate); units as above:\n")
    print("| scene | pantograph | mean % | σ % | Fm+3σ % | max % | Fm−3σ %Fm | min %Fm | "
          "uplift % | loss pp |")
    print("|" + "---|" * 10)
    for scene, (fe_run, modal_run) in runs.items():
        if fe_run and modal_run:
            for line in estimate_rows(scene, fe_run, modal_run):
                print(line)


if __name__ == "__main__":
    main()
