#!/bin/bash
# The reduced-order (modal) catenary against the linearised FE catenary, end
# to end through `pcsim run` on one rank:
# 1. Every mode and exact bars (tests/assembly/data/small-modal-all.yaml, 280
#    unknowns, a dense Newton matrix) equal the linearised FE catenary on the
#    full Newton path (small-linear.yaml) over 400 steps from a ramp start, in
#    which two droppers go slack: max |dFc| <= 1e-9 max Fc. Measured 7.4e-11
#    (1.2e-10 over the whole 792 steps): both solve the same equations in other
#    unknowns, each to the Newton tolerance (-snes_atol 1e-6 N, above the FE
#    residual's round-off floor of ~2e-7 N; a residual r moves the contact
#    force by ~0.025 r, dynamics.cpp), so 1e-9 leaves a margin of ~30. The ramp start is used because the static start of an FE
#    catenary places the pantograph from a nonlinear guess (~2e-4 N off the
#    linear equilibrium) while the modal one is exact.
#    With every mode, bars: slack (a slack dropper keeps its static tension's
#    geometric stiffness) and bars: slack_exact (it loses it: its force is
#    exactly zero) against the same FE run: slack_exact's error is the smaller
#    by the share of that stiffness (the rest is the taut droppers'
#    linearisation, which both keep). Over the whole run (792 steps; the
#    first 400 have little slack and measure 0.91): max |dFc| 4.9e-4 and
#    3.0e-4 of max Fc, ratio 0.60; asserted <= 0.75 (a sign error, adding
#    the stiffness instead, makes it > 1). With every dropper taken exactly
#    (catenary.modal.exact_droppers_within=1000: their exact force, zero
#    while slack, with its exact tangent as six rank-one terms; bars:
#    slack_exact for the steady arms, whose linearisation moves nothing here)
#    the modal level is linear FE again over the whole run, slack droppers
#    included: measured 1.4e-10 of max Fc, asserted 1e-9 (the margin of the
#    first check; the taut droppers linearised leave 3.0e-4).
# 2. The cache: the first run computes the modes and stores them with the
#    basis it assembled, a second run reads that basis and gives the same
#    contact force bit for bit, as does a run whose stored basis was broken
#    (a miss: assembled again from the data); a lower cut-off reuses the data. The bounded dropper check equals evaluating every
#    dropper at every state (the correction of a taut dropper is exactly 0,
#    only the order of sums differs): measured 3.3e-13 of max Fc, asserted
#    1e-11, with fewer exact evaluations (0.3 against 24.0 per step). The
#    records' dropper forces and support heights are exact products, 32
#    states at a time (modal_records.cpp), each batch's on a thread of its
#    own: bit for bit those made on the stepping thread. The two runs' dropper forces
#    agree within 6.0e-11 N (asserted 1e-9 N: the states' round-off above,
#    while a record given another step's state would be off by a step's
#    change of a dropper force, ~1 N). A run stopped at step 70 (a checkpoint
#    every 50 steps: batches completed mid-run) and restarted, and a run on
#    two ranks (the batch summed to rank 0), give the same records: measured
#    2.8e-14 N and 0 (restart), 5.1e-10 N and 1.7e-10 N (two ranks: sums in
#    another order) for the dropper and contact forces, asserted 1e-9 N and
#    5e-9 N; uplifts within 1e-12 m. Records in batches leave the check's
#    line of bounds untried (0 tries a step, 2.0 one at a time). The
#    step-time report counts the check's exact anchors in the steps that made
#    them: all 1439 where every dropper is evaluated, none in the bounded runs.
# 3. Truncated at the default cut-off (1.1 x 20 Hz / (1 - v/c) = 40.5 Hz, 232
#    of 712 vectors) on the three-span test catenary (three-span-modal.yaml)
#    against the linearised FE run of the same scene (app/data/study-tiny.yaml),
#    EN 50318 figures over span 2. Measured: mean +0.05 %, sigma -0.32 %,
#    Fm+3sigma -0.09 %, actual max +1.58 %, uplift -0.13 %; asserted within
#    0.1 / 0.5 / 0.2 / 2.0 / 0.3 % (about 1.3-2 times the measured, the margin
#    for round-off in the eigensolver's basis, which moves the actual max, a
#    single sample, most).
# 4. Two pantographs on the cheap path (rank-one terms of two contacts, the
#    second head's unknown after the first's) against the full Newton path
#    over 400 steps: the cheap path's operator is the exact Jacobian, so Newton
#    takes one iteration per step (measured 1.00; a wrong rank-one term, as a
#    head's unknown misplaced, took 4.0) and both paths give the same contact
#    forces to the Newton tolerance's floor (-snes_atol 1e-6: measured 5e-13 of
#    max Fc, asserted 1e-10).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$PCSIM_SOURCE_DIR/tests/assembly/data
run() {  # run NAME SCENE [options]: pcsim run, output in $tmp/NAME, log in $tmp/NAME.log
  local name=$1 scene=$2
  shift 2
  "$PCSIM_BIN" run "$scene" -o "$tmp/$name" --cache "$tmp/cache" "$@" > "$tmp/$name.log" 2>&1 ||
    { cat "$tmp/$name.log"; exit 1; }
}

# 1. Every mode = FE.
run fe "$data/small-linear.yaml" -pcsim_path full -snes_atol 1e-6 -ts_max_steps 400
run all "$data/small-modal-all.yaml" -snes_atol 1e-6 -ts_max_steps 400
run fe-whole "$data/small-linear.yaml" -pcsim_path full -snes_atol 1e-6
for bars in slack slack_exact; do
  run "all-$bars" "$data/small-modal-all.yaml" -snes_atol 1e-6 --set catenary.modal.bars=$bars
done
run all-near "$data/small-modal-all.yaml" -snes_atol 1e-6 --set catenary.modal.bars=slack_exact \
  --set catenary.modal.exact_droppers_within=1000
grep -q "catenary model: modal, 280 basis vectors (280 modes" "$tmp/all.log" ||
  { cat "$tmp/all.log"; exit 1; }

# 2. The cache and the bounded dropper check (design paths made absolute).
sed -e "s#design: \.\./\.\./contact#design: $PCSIM_SOURCE_DIR/tests/contact#" \
  -e "s#model: \.\./\.\./\.\./meshes#model: $PCSIM_SOURCE_DIR/meshes#" \
  "$data/three-span-modal.yaml" > "$tmp/base.yaml"
sed 's#^  model: modal#  model: modal\n  modal: {droppers: all}#' "$tmp/base.yaml" > "$tmp/all-droppers.yaml"
sed 's#^  model: modal#  model: modal\n  max_frequency_hz: 30#' "$tmp/base.yaml" > "$tmp/lower.yaml"
# Records in batches (-pcsim_record_batches true: this small line's records
# would come one at a time), each batch's product on a thread of its own
# (-pcsim_record_thread true: forced, whatever cores the machine spares); the
# same batches without the thread.
batches=(-pcsim_record_batches true -pcsim_record_thread true)
run modal "$tmp/base.yaml" "${batches[@]}"
run unthreaded "$tmp/base.yaml" -pcsim_record_batches true -pcsim_record_thread false
run auto "$tmp/base.yaml" -pcsim_record_batches true -ts_max_steps 40
run again "$tmp/base.yaml"
run every "$tmp/all-droppers.yaml" "${batches[@]}"
run lower "$tmp/lower.yaml"
# Records in batches: stopped at step 70 (a checkpoint every 50 steps),
# restarted, and on two ranks.
run stop "$tmp/base.yaml" --set output.checkpoint_every=50 -ts_max_steps 70 "${batches[@]}"
run restarted "$tmp/base.yaml" --set output.checkpoint_every=50 --restart "$tmp/stop" \
  "${batches[@]}"
"$PCSIM_SOURCE_DIR/scripts/mpirun.sh" -n 2 "$PCSIM_BIN" run "$tmp/base.yaml" -o "$tmp/ranks2" \
  --cache "$tmp/cache" "${batches[@]}" > "$tmp/ranks2.log" 2>&1 || { cat "$tmp/ranks2.log"; exit 1; }
grep -q "computing the catenary's modes below 40.5 Hz" "$tmp/modal.log" || { cat "$tmp/modal.log"; exit 1; }
for name in again every lower; do
  grep -q "read from the cache" "$tmp/$name.log" || { cat "$tmp/$name.log"; exit 1; }
done
ls "$tmp/cache"/modal-*.h5 > /dev/null
# The first run stored its assembled basis; the second read it (not the data).
grep -q "read from the cache (assembled)" "$tmp/again.log" || { cat "$tmp/again.log"; exit 1; }
# A broken assembled basis is a miss: assembled again from the data, stored anew.
for f in "$tmp/cache"/basis-*.h5; do head -c 1000 "$f" > "$f.cut" && mv "$f.cut" "$f"; done
run broken "$tmp/base.yaml"
grep -q "read from the cache in" "$tmp/broken.log" || { cat "$tmp/broken.log"; exit 1; }

# 3. Truncated against the linearised FE run.
run linear "$PCSIM_SOURCE_DIR/tests/app/data/study-tiny.yaml"

# 4. Two pantographs, cheap against full path.
model=$PCSIM_SOURCE_DIR/meshes/pantographs/en50318_two_mass.yaml
cat > "$tmp/two.yaml" <<EOF
base: $tmp/base.yaml
pantographs:
  - {name: leading, model: $model, start_x: 25.0, static_force: 120, start: static}
  - {name: trailing, model: $model, start_x: 5.0, static_force: 120, start: static}
EOF
run two-cheap "$tmp/two.yaml" -ts_max_steps 400 -snes_atol 1e-6
run two-full "$tmp/two.yaml" -ts_max_steps 400 -snes_atol 1e-6 -pcsim_path full

"$PCSIM_PYTHON" - "$tmp" <<'PY'
import json, sys
import h5py
import numpy as np
d = sys.argv[1]
def force(name):
    with h5py.File(f"{d}/{name}/results.h5") as f:
        return f["/pantographs/pantograph/contact_force"][:]
def summary(name):
    return json.load(open(f"{d}/{name}/summary.json"))

fe, modal = force("fe"), force("all")
assert len(fe) == len(modal) == 401, (len(fe), len(modal))
rel = np.max(np.abs(fe - modal)) / np.max(np.abs(fe))
with h5py.File(f"{d}/fe/results.h5") as f:
    slack = (f["/droppers/force"][:] <= 0).any(axis=0).sum()
print(f"1. every mode vs FE: max |dFc| / max Fc = {rel:.2e} over 400 steps, {slack} droppers slack")
assert slack >= 2, slack  # the slack correction is exercised
assert rel <= 1e-9, rel
whole = force("fe-whole")
assert len(whole) == 793, len(whole)
err = {b: np.max(np.abs(whole - force(f"all-{b}"))) / np.max(np.abs(whole))
       for b in ("slack", "slack_exact")}
ratio = err["slack_exact"] / err["slack"]
print(f"1. every mode vs FE, linear bars: slack {err['slack']:.2e}, slack_exact "
      f"{err['slack_exact']:.2e}, ratio {ratio:.2f}")
assert ratio <= 0.75, ratio
near = np.max(np.abs(whole - force("all-near"))) / np.max(np.abs(whole))
print(f"1. every mode vs FE, every dropper exact: {near:.2e}")
assert near <= 1e-9, near

a, b, every = force("modal"), force("again"), force("every")
assert np.array_equal(a, b), "a cached basis gives another result"
assert np.array_equal(a, force("broken")), "a basis assembled again gives another result"
assert summary("modal")["modal"]["basis_assembled"] and not summary("again")["modal"]["basis_assembled"]
assert summary("again")["modal"]["basis_file"] == summary("modal")["modal"]["basis_file"] != ""
rel = np.max(np.abs(a - every)) / np.max(np.abs(a))
bounded = summary("modal")["modal"]["dropper_evaluations_per_step"]
checked = summary("every")["modal"]["dropper_evaluations_per_step"]
print(f"2. cache reused; bounded vs every dropper: {rel:.2e}, {bounded:.1f} vs {checked:.1f} "
      "exact evaluations per step")
assert rel <= 1e-11, rel
assert bounded < checked, (bounded, checked)
with h5py.File(f"{d}/modal/results.h5") as f, h5py.File(f"{d}/every/results.h5") as g:
    dn = np.max(np.abs(f["/droppers/force"][:] - g["/droppers/force"][:]))
print(f"2. recorded dropper forces, bounded check vs every dropper: max |dN| = {dn:.1e} N")
assert dn <= 1e-9, dn
def records(name):
    with h5py.File(f"{d}/{name}/results.h5") as f:
        return [f[k][:] for k in ("/droppers/force", "/supports/uplift",
                                  "/pantographs/pantograph/contact_force")]
whole = records("modal")
assert summary("modal")["records_in_batches"] and not summary("again")["records_in_batches"]
# Records one at a time anchor the check at every step, and its candidates
# are sought on the line through the last two anchors; records in batches
# anchor nothing, and the line is not tried (before 80c2e9a a record made
# one at a time before the steps left it on: 2.0 tries a step here for the
# same products; the same bits either way, asserted above).
tries = {n: summary(n)["modal"]["line_tries_per_step"] for n in ("modal", "again")}
print(f"2. line tries per step: batched {tries['modal']:.2f}, one at a time {tries['again']:.2f}")
assert tries["modal"] == 0 and tries["again"] > 0, tries
# The step-time report counts each step under its causes (step_timing.hpp):
# every step after the first at least once, an exact anchor of the dropper
# check in the step that made it: in every step where every dropper is
# evaluated ("every"), in none where the bounded check kept its first anchor
# (made before the steps: this short run needs no other).
for n in ("modal", "again", "every"):
    j = summary(n)
    causes, steps = j["step_time"]["by_cause"], j["step_time"]["steps"]
    assert sum(c["steps"] for c in causes.values()) >= steps - 1, (n, causes)
    anchors = round(j["modal"]["exact_updates_per_step"] * j["steps"])
    in_steps = causes.get("dropper_exact_anchor", {"steps": 0})["steps"]
    print(f"2. {n}: exact anchors {anchors}, steps with one {in_steps} of {steps - 1}")
    expected = steps - 1 if n == "every" else 0
    assert in_steps == expected and anchors > in_steps, (n, in_steps, anchors)
# The batches' products on their own thread: the same bits as on the stepping
# thread (the same product of the same states, delivered in order).
assert summary("modal")["records_thread"] and not summary("unthreaded")["records_thread"]
assert summary("unthreaded")["records_in_batches"]
# auto: a thread where the process may run on more than one CPU and its node
# has more CPUs than processes (this one alone).
import os
spare = len(os.sched_getaffinity(0)) > 1 and os.cpu_count() > 1
assert summary("auto")["records_thread"] == spare, (summary("auto")["records_thread"], spare)
assert all(np.array_equal(a, b) for a, b in zip(whole, records("unthreaded"))), "thread"
# One at a time: single-precision anchors within their bound (1 N); measured
# 3.2e-5 N from the exact ones, asserted 1e-3 N (the rounding's spread,
# while a stale anchor would be off by a step's change of a dropper force).
dn = np.max(np.abs(records("again")[0] - whole[0]))
print(f"2. recorded dropper forces, one at a time vs batches: max |dN| = {dn:.1e} N")
assert dn <= 1e-3, dn
for name in ("restarted", "ranks2"):
    other = records(name)
    assert all(a.shape == b.shape for a, b in zip(whole, other)), name
    dn, dz, df = (np.max(np.abs(a - b)) for a, b in zip(whole, other))
    print(f"2. records in batches, {name} vs one run on one rank: |dN| {dn:.1e} N, "
          f"|d uplift| {dz:.1e} m, |dFc| {df:.1e} N")
    # Two ranks sum in another order: measured 5.1e-10 N and 1.7e-10 N.
    limit = 1e-9 if name == "restarted" else 5e-9
    assert dn <= limit and dz <= 1e-12 and df <= limit, (name, dn, dz, df)
assert summary("lower")["modal"]["cutoff_hz"] == 30.0

# The accuracy estimate of the modal run (docs/fidelity.md): its cut-off is 1.1
# times cutoff_hz / (1 - v/c), inside; 1.5 m elements are 1.85 per wavelength
# v / 20 Hz, outside (converged >= 4.4), with the advice to refine.
criteria = {c["name"]: c for c in summary("modal")["accuracy_estimate"]["criteria"]}
assert sorted(criteria) == ["element length", "modal cut-off", "time step"], criteria
assert abs(criteria["modal cut-off"]["value"] - 1.1) < 1e-9 and criteria["modal cut-off"]["ok"]
assert not criteria["element length"]["ok"] and "element_length" in criteria["element length"]["advice"]
assert "modal cut-off" not in str(summary("linear")["accuracy_estimate"])

figures = {"mean_N": 0.1, "std_N": 0.5, "stat_max_N": 0.2, "max_N": 2.0}
fe, modal = summary("linear"), summary("modal")
assert modal["modal"]["basis_size"] == 232, modal["modal"]
for key, limit in figures.items():
    err = 100 * (modal["pantographs"][0][key] / fe["pantographs"][0][key] - 1)
    print(f"3. default cut-off vs FE: {key} {err:+.2f} % (limit {limit} %)")
    assert abs(err) <= limit, (key, err)
err = 100 * (modal["max_uplift_at_support_m"] / fe["max_uplift_at_support_m"] - 1)
print(f"3. default cut-off vs FE: uplift {err:+.2f} % (limit 0.3 %)")
assert abs(err) <= 0.3, err

cheap, full = summary("two-cheap"), summary("two-full")
assert cheap["path"] == "cheap" and full["path"] == "full", (cheap["path"], full["path"])
rel = 0.0
for name in ("leading", "trailing"):
    with h5py.File(f"{d}/two-cheap/results.h5") as a, h5py.File(f"{d}/two-full/results.h5") as b:
        fa = a[f"/pantographs/{name}/contact_force"][:]
        fb = b[f"/pantographs/{name}/contact_force"][:]
    assert len(fa) == len(fb) == 401 and fa.max() > 50, (len(fa), fa.max())
    rel = max(rel, np.max(np.abs(fa - fb)) / np.max(np.abs(fb)))
its = cheap["newton_iterations_per_step"]
print(f"4. two pantographs, cheap vs full path: max |dFc| / max Fc = {rel:.2e}, "
      f"{its:.2f} Newton iterations per step on the cheap path")
assert its <= 1.05, its
assert rel <= 1e-10, rel
PY
