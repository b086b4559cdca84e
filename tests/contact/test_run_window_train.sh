#!/bin/bash
# Moving window over a train (issue 21; docs/scaling.md, "Moving window"):
# two EN 50318 pantographs 120 m apart (tests/contact/data/window-two-pantographs.yaml:
# leading static at 125 m, trailing ramped up from 5 m) on a 12-span line; the
# whole line against a window of 2 behind + 4 with the train (2 between the
# pantographs, 2 of the leading one's) + 2 ahead = 8 spans, which shifts twice
# (when the leading pantograph reaches 360 and 480 m), once in the middle of
# the analysis section (300-420 m) for each pantograph.
# Checks: the window's size and shifts; every pantograph's positions those of
# the line; its EN 50318 figures against the whole line's. Measured (one rank):
# mean, sigma, Fm+3sigma <= 0.05 %, actual max <= 0.10 %, uplift 0.01 %:
# within 0.2 %, the margin of the one-pantograph test (test_run_window.sh,
# measured <= 0.03 %), 1/5 of the issue's 1 % target. The actual minimum, one
# sample, differs by up to 0.45 % (the one-pantograph window at 40 spans:
# -0.31 %, docs/scaling.md): within 1 %. Fm-3sigma (~9 N, a difference of two
# figures: its relative error ~13 x theirs) is not checked.
# Margins (1, 2), as in test_run_window.sh, are too short behind a train: the
# trailing pantograph then runs one span from the rear end through the
# leading one's wake (measured with analysis spans 5-6: trailing mean -0.14 %,
# sigma -0.26 %, max +0.41 %; with (2, 2) there <= 0.10 %).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
S=$PCSIM_SOURCE_DIR
scene=$S/tests/contact/data/window-two-pantographs.yaml

run() {  # run NAME [options]
  local name=$1
  shift
  "$PCSIM_BIN" run "$scene" -o "$tmp/$name" --no-report "$@" > "$tmp/$name.log" 2>&1 ||
    { cat "$tmp/$name.log"; exit 1; }
}
run full
run window --set window.spans_behind=2 --set window.spans_ahead=2
grep -q "moving window: 8 of the line's 12 spans (2 behind, 4 with the train, 2 ahead)" \
  "$tmp/window.log" || { cat "$tmp/window.log"; exit 1; }

"$PCSIM_PYTHON" - "$tmp" <<'PY'
import json, sys
import h5py
import numpy as np
d = sys.argv[1]
def summary(name):
    return json.load(open(f"{d}/{name}/summary.json"))
def figures(name, pantograph):
    return {f["key"]: f["value"] for f in summary(name)["en50318"][pantograph]["figures"]}
assert summary("window")["window_shifts"] == 2, summary("window").get("window_shifts")
worst = 0.0
for p in ("leading", "trailing"):
    full, win = figures("full", p), figures("window", p)
    for key, tol in (("mean_N", 2e-3), ("std_N", 2e-3), ("stat_max_N", 2e-3), ("max_N", 2e-3),
                     ("uplift_mm", 2e-3), ("min_N", 1e-2)):
        err = abs(win[key] - full[key]) / abs(full[key])
        worst = max(worst, err)
        print(f"{p} {key}: window {win[key]:.3f}, full line {full[key]:.3f}, error {100 * err:.3f} %")
        assert err < tol, (p, key)
    with h5py.File(f"{d}/window/results.h5") as fw, h5py.File(f"{d}/full/results.h5") as ff:
        xw, xf = fw[f"/pantographs/{p}/position"][:], ff[f"/pantographs/{p}/position"][:]
        assert np.array_equal(xw, xf), f"{p}: the window's positions are not the line's"
print(f"largest difference {100 * worst:.3f} %")
PY
