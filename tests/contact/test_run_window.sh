#!/bin/bash
# Moving window against the full line (docs/scaling.md, "Moving window"):
# the EN 50318 case at 300 km/h on a 10-span line, statistics over spans 3-4
# (120-240 m), end at 250 m; the window of 5 spans (1 behind, 2 with the
# pantograph, 2 ahead) moves once, at 180 m, inside the analysis section.
# Checks: one shift; the EN 50318 figures within 0.2 % of the full line's
# (measured: mean, sigma, Fm+3sigma 0.00 %, actual max 0.03 %, uplift 0.02 %;
# the 40-span table in docs/scaling.md: <= 0.04 %; 0.2 % leaves room for the
# round-off of other machines and ranks, 1/5 of the issue's 1 % target); the
# window on 2 ranks equal to 1 rank to
# round-off (measured 7e-11 of the largest force; bound 1e-8 as in
# test_run_ranks.sh).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
S=$PCSIM_SOURCE_DIR
scene=$S/runs/en50318-300.yaml
# shellcheck source=tests/contact/window_runs.sh
source "$S/tests/contact/window_runs.sh"
run full 1
run window1 1 "${window[@]}"
run window2 2 "${window[@]}"
grep -q "moving window: 5 of the line's 10 spans" "$tmp/window1.log"

PYTHONPATH="$S/tests/contact" "$PCSIM_PYTHON" - "$tmp" <<'PY'
import sys
import run_figures
d = sys.argv[1]
runs = run_figures.Runs(d)
summary, figures = runs.summary, runs.figures
assert summary("window1")["window_shifts"] == 1, summary("window1").get("window_shifts")
full, win = figures("full"), figures("window1")
for key in ("mean_N", "std_N", "stat_max_N", "max_N", "uplift_mm"):
    err = abs(win[key] - full[key]) / abs(full[key])
    print(f"{key}: window {win[key]:.3f}, full line {full[key]:.3f}, error {100 * err:.3f} %")
    assert err < 2e-3, key
run_figures.check_window_ranks(runs)
PY
