#!/bin/bash
# The moving window on a stitched catenary (docs/scaling.md, "Moving window"):
# runs/lines/stitched-300.yaml (a stitch wire at every support but the line's
# ends) on 10 spans at 300 km/h, statistics over spans 3-4, end at 250 m; a
# window of 5 spans (1 behind, 2 with the pantograph, 2 ahead) that moves
# once, inside the analysis section. Checks:
#  - the FE window's EN 50318 figures within 0.2 % of the full line's
#    (measured 2026-12-01: mean 0.00 %, sigma 0.07 %, Fm+3sigma 0.03 %,
#    actual max 0.08 %, uplift 0.13 %; the unstitched line's test,
#    test_run_window.sh, holds 0.2 % too: 1/5 of issue 21's 1 % target);
#  - the FE window on 2 ranks equal to 1 rank to round-off (bound 1e-8 of the
#    largest force as in test_run_window.sh);
#  - the modal level in the window (catenary.model=modal, its default cut-off,
#    no pilot) against the full line's linear FE within issue 21's targets:
#    mean 0.5 %, sigma, Fm+3sigma and actual max 1 %, uplift 2 % (measured:
#    0.06, 0.33, 0.10, 0.48 and 0.80 %), and the 'auto' method choosing the
#    window on a long stitched line.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
S=$PCSIM_SOURCE_DIR
scene=$S/runs/lines/stitched-300.yaml
# shellcheck source=tests/contact/window_runs.sh
source "$S/tests/contact/window_runs.sh"
run full 1
run window1 1 "${window[@]}"
run window2 2 "${window[@]}"
run modal 1 "${window[@]}" --set catenary.model=modal
grep -q "moving window: 5 of the line's 10 spans" "$tmp/window1.log"
grep -q "modal method: window" "$tmp/modal.log"

"$PCSIM_BIN" check "$scene" --set catenary.design.spans.count=1000 --set catenary.model=modal \
  > "$tmp/check.log" 2>&1 || { cat "$tmp/check.log"; exit 1; }
grep -q "modal method window (auto: a line of 1000 identical spans" "$tmp/check.log" ||
  { cat "$tmp/check.log"; exit 1; }

PYTHONPATH="$S/tests/contact" "$PCSIM_PYTHON" - "$tmp" <<'PY'
import sys
import run_figures
runs = run_figures.Runs(sys.argv[1])
full = runs.figures("full")
limits = {  # FE window; modal window (issue 21's targets)
    "mean_N": (2e-3, 5e-3), "std_N": (2e-3, 1e-2), "stat_max_N": (2e-3, 1e-2),
    "max_N": (2e-3, 1e-2), "uplift_mm": (2e-3, 2e-2)}
for name, column in (("window1", 0), ("modal", 1)):
    assert runs.summary(name)["window_shifts"] == 1, runs.summary(name).get("window_shifts")
    got = runs.figures(name)
    for key, bounds in limits.items():
        err = abs(got[key] - full[key]) / abs(full[key])
        print(f"{name} {key}: {got[key]:.3f}, full line {full[key]:.3f}, error {100 * err:.3f} %")
        assert err < bounds[column], (name, key)
run_figures.check_window_ranks(runs)
PY
