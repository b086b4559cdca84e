#!/bin/bash
# Where a run's extremes fall against its accuracy pilot's stretch
# (simulation/pilot_extremes.hpp, docs/fidelity.md "Where the extremes fall"),
# end to end: the two-pantograph scene of the 55 m line
# (tests/simulation/data/span55-two-pantographs-short.yaml) on 10 spans with
# the analysis section spans 4-6, of which the pilot runs spans 4-5.
#  - summary.json's max_at_x_m and min_at_x_m are where the filtered contact
#    force of results.h5 (h5py, not pcsim's code) is largest and smallest in
#    the section;
#  - max_uplift_at_support_x_m is the support of the largest uplift in
#    /supports/uplift over the section's supports;
#  - accuracy_estimate.extremes_outside_pilot lists exactly those of them
#    outside the pilot's stretch (the uplift's for every pantograph) (accuracy_estimate.pilot from_x, to_x),
#    and each pantograph's loss of contact where a sample of the unfiltered
#    force at zero in the section is outside it, and
#    the console says so for each; on this scene the trailing pantograph's
#    maximum and minimum (at 328 and 283 m, 2026-12-06) and not the leading
#    one's, so both outcomes are checked;
#  - postproc/pilot_check.py against linear FE of the same scene marks the
#    estimates of those figures, and only those.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
# The scene on 10 spans, its section on spans 4-6: the modal run and its reference.
scene=("$PCSIM_SOURCE_DIR/tests/simulation/data/span55-two-pantographs-short.yaml"
  --set catenary.design.spans.count=10 --set simulation.end_x=460 --set analysis.to_span=6)
"$PCSIM_BIN" run "${scene[@]}" --set catenary.model=modal -pcsim_accuracy_pilot true \
  --cache "$tmp/cache" -o run --no-report > run.log 2>&1 || { cat run.log; exit 1; }
grep -q "accuracy pilot: spans 4-5" run.log || { cat run.log; exit 1; }
"$PCSIM_PYTHON" - <<'PY' || { cat run.log; exit 1; }
import json
import h5py
import numpy as np
summary = json.load(open("run/summary.json"))
section = summary["analysis"]
pilot = summary["accuracy_estimate"]["pilot"]
listed = {(e["pantograph"], e["figure"]): e["at_x_m"]
          for e in summary["accuracy_estimate"]["extremes_outside_pilot"]}
outside = lambda at: (at < pilot["from_x"]) | (at > pilot["to_x"])  # a position or an array
log = open("run.log").read()
expected = {}
with h5py.File("run/results.h5", "r") as f:
    for p in summary["pantographs"]:
        g = f["pantographs"][p["name"]]
        x, force = g["position"][:], g["contact_force_filtered"][:]
        inside = (x >= section["from_x"]) & (x <= section["to_x"])
        for key, pick, figure, word in (("max_at_x_m", np.argmax, "actual_max_percent", "maximum"),
                                        ("min_at_x_m", np.argmin, "actual_min_percent_of_mean",
                                         "minimum")):
            at = x[inside][pick(force[inside])]
            assert p[key] == at, (p["name"], key, p[key], at)
            if outside(at):
                expected[(p["name"], figure)] = at
                line = f"the actual {word} of '{p['name']}' falls at x = {at:.1f} m, outside"
                assert line in log, line
        # The loss of contact: the section's samples of the unfiltered force at zero.
        lost = x[inside & (g["contact_force"][:] <= 0)]
        if outside(lost).any():
            expected[(p["name"], "loss_of_contact_points")] = lost[outside(lost)][0]
            line = (f"the loss of contact of '{p['name']}' has {outside(lost).sum()} of its "
                    f"{lost.size} samples at zero outside the pilot's stretch")
            assert line in log, line
    # The largest uplift at a support of the section, the first in results.h5's order.
    xs, uplift = f["supports/x"][:], f["supports/uplift"][:]
    at_support = (xs >= section["from_x"] - 1e-9) & (xs <= section["to_x"] + 1e-9)
    rows = np.where(at_support[None, :], uplift, -np.inf)
    support = xs[np.unravel_index(np.argmax(rows), rows.shape)[1]]
    assert rows.max() > 0 and summary["max_uplift_at_support_x_m"] == support, (
        summary["max_uplift_at_support_x_m"], support)
    if outside(support):
        for p in summary["pantographs"]:
            expected[(p["name"], "uplift_percent")] = support
        assert f"the largest uplift at a support falls at x = {support:.1f} m" in log
assert listed == expected, (listed, expected)
names = {name for name, figure in listed if figure != "uplift_percent"}
assert names == {"trailing"}, names  # one pantograph outside, one inside: both outcomes
print("extremes outside the pilot's stretch:", sorted(listed.items()))
PY
# postproc/pilot_check.py marks those estimates, and only those.
"$PCSIM_BIN" run "${scene[@]}" -pcsim_accuracy_pilot false -o linear --no-report > linear.log 2>&1 ||
  { cat linear.log; exit 1; }
"$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/postproc/pilot_check.py" run --reference linear > check.log
"$PCSIM_PYTHON" - <<'PY' || { cat check.log; exit 1; }
import json
summary = json.load(open("run/summary.json"))
listed = summary["accuracy_estimate"]["extremes_outside_pilot"]
words = {"actual_max_percent": "actual max", "actual_min_percent_of_mean": "actual min",
         "uplift_percent": "uplift", "loss_of_contact_points": "loss of contact"}
# Its columns: kind (15), pantograph (12), figure (16), one space apart.
marked = [(line[16:28].strip(), line[29:45].strip()) for line in open("check.log")
          if "(falls outside the pilot's stretch)" in line]
assert sorted(marked) == sorted(
    (e["pantograph"], words[e["figure"]]) for e in listed), (marked, listed)
assert f"{len(listed)} estimates of figures that fall outside the pilot's stretch" in open(
    "check.log").read()
print(f"pilot_check.py: {len(marked)} estimates marked")
PY
echo "pilot extremes: ok"
