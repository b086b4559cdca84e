#!/bin/bash
# Restarts of runs with a moving window (README "Interrupted runs and
# restarts"; docs/scaling.md, "Moving window"). The checkpoint keeps the
# window's shift count (attribute window_shifts): the restart shifts its
# window as many times before it takes the state (the pantographs' contact
# points two spans back a shift, the pins at the line's ends, the line's
# turbulence over the window). Until 2026-12-06 such a run could not be
# restarted, nor write checkpoints, and the modal level's automatic window
# on a long line gave way to the whole line when checkpoints were asked for.
#  1. The linearised FE window of small-window-linear.yaml (12 spans, a
#     window of 4, shifts at steps 828 and 1405 of 1764), one rank: stopped
#     at step 828 (-ts_max_steps), the step of the first shift, restarted:
#     every time series equal to the uninterrupted run's (tolerance 0: one
#     rank, the same arithmetic, measured bit for bit equal). Until the fix
#     of hht_get_acceleration the checkpoint paired the shifted state with
#     the acceleration from before the shift: 1 % in the contact force.
#  2. The same scene's modal window, SIGTERM at step 1500 (two shifts; the
#     checkpoint of the interrupted run's last step), restarted from the
#     partial folder: equal, bit for bit.
#  3. Two pantographs 120 m apart in a window over the train on two ranks
#     (window-two-pantographs.yaml, shifts at steps 2820 and 4260 of 5220),
#     SIGTERM at step 3500: equal to the uninterrupted two-rank run bit for
#     bit with deterministic linear solvers (every LU sequential and
#     redundant on each rank, as test_run_restart_np2.sh). With MUMPS's
#     parallel schedule two identical runs differ by up to 1.9e-10 of the
#     contact force (measured under load): a first version of this case
#     allowed 1e-12 with the default solvers and passed only by chance.
#  4. Refused (exit 2, one message naming --restart, nothing written): a
#     checkpoint whose window shifted more often than the run can (edited).
#  5. The turbulent cross-wind of runs/conditions/en50318-300-wind.yaml on a
#     line of 30 spans in a window of 7 (first shift at step 2820), stopped
#     at step 2000, before any shift, restarted to step 3600: equal bit for
#     bit, the lateral wire position too (the turbulence follows the window
#     after the restart's shift). Until 2026-12-06 a restart of any windy run
#     stopped at its end (exit 3, 'cannot create HDF5 dataset
#     /pantographs/pantograph/cross_wind_force': the copied results.h5 kept
#     the earlier run's end datasets).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
small=$PCSIM_SOURCE_DIR/tests/assembly/data/small-window-linear.yaml
train=$PCSIM_SOURCE_DIR/tests/contact/data/window-two-pantographs.yaml
equal="$PCSIM_PYTHON $PCSIM_SOURCE_DIR/tests/contact/compare_runs.py"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
problem() { echo "FAIL: $*" >&2; exit 1; }
pcsim_run() {  # pcsim_run LOG ARGS...: exits 0 or the test fails with the log
  local log=$1 code=0
  shift
  timeout 600 "$@" > "$log" 2>&1 || code=$?
  [ $code -eq 0 ] || { cat "$log"; problem "$log: exit $code"; }
}
attribute() {  # attribute FILE NAME
  "$PCSIM_PYTHON" -c "import h5py; print(int(h5py.File('$1', 'r').attrs['$2']))"
}
shifts_of() {  # shifts_of DIR: summary.json's window_shifts
  "$PCSIM_PYTHON" -c "import json; print(json.load(open('$1/summary.json'))['window_shifts'])"
}

# 1. FE window, stopped by -ts_max_steps at its first shift.
pcsim_run fe.log "$PCSIM_BIN" run "$small" --no-report -o fe
pcsim_run fe-stop.log "$PCSIM_BIN" run "$small" --no-report -o fe-stop -ts_max_steps 828
[ "$(attribute fe-stop/checkpoint.h5 window_shifts)" = 1 ] || problem "fe-stop: not 1 shift"
pcsim_run fe-restart.log "$PCSIM_BIN" run "$small" --no-report --restart fe-stop -o fe-restart
$equal fe fe-restart 0 || problem "the FE window's restart differs"
[ "$(shifts_of fe-restart)" = 2 ] || problem "the restart's summary.json: not 2 shifts"
echo "ok   FE window: stopped at step 828, its first shift, restarted: equal bit for bit"

# 2. Modal window, SIGTERM after its second shift.
modal=(--set catenary.model=modal --cache cache --no-report)
pcsim_run modal.log "$PCSIM_BIN" run "$small" "${modal[@]}" -o modal
status=0
"$PCSIM_BIN" run "$small" "${modal[@]}" -o modal-term -pcsim_debug_signal_step 1500 \
  > modal-term.log 2>&1 || status=$?
[ $status -eq 143 ] || { cat modal-term.log; problem "modal-term: exit $status, not 143"; }
[ "$(attribute modal-term.partial/checkpoint.h5 window_shifts)" = 2 ] ||
  problem "modal-term: not 2 shifts"
pcsim_run modal-restart.log "$PCSIM_BIN" run "$small" "${modal[@]}" --restart modal-term.partial \
  -o modal-restart
$equal modal modal-restart 0 || problem "the modal window's restart differs"
echo "ok   modal window: SIGTERM at step 1500 after 2 shifts, restarted: equal bit for bit"

# 3. Two pantographs, a window over the train, two ranks.
deterministic=(-cheap_pc_type redundant -cheap_redundant_pc_factor_mat_ordering_type qmd)
for prefix in static_ start_ start_load_; do
  deterministic+=("-${prefix}pc_type" redundant "-${prefix}redundant_pc_factor_mat_solver_type" mumps)
done
two_ranks=(mpirun -n 2 "$PCSIM_BIN" run "$train" --set window.spans_behind=2
  --set window.spans_ahead=2 --no-report "${deterministic[@]}")
pcsim_run train.log "${two_ranks[@]}" -o train
status=0
"${two_ranks[@]}" -o train-term -pcsim_debug_signal_step 3500 > train-term.log 2>&1 || status=$?
[ $status -ne 0 ] || { cat train-term.log; problem "train-term: not interrupted"; }
[ "$(attribute train-term.partial/checkpoint.h5 window_shifts)" = 1 ] ||
  problem "train-term: not 1 shift"
pcsim_run train-restart.log "${two_ranks[@]}" --restart train-term.partial -o train-restart
$equal train train-restart 0 || problem "the train's restart on 2 ranks differs"
echo "ok   two pantographs, 2 ranks: SIGTERM at step 3500 after 1 shift, restarted: equal bit for bit"

# 4. A shift count the run cannot reach.
cp -r fe-stop edited
"$PCSIM_PYTHON" -c "import h5py; h5py.File('edited/checkpoint.h5', 'r+').attrs['window_shifts'] = 7.0"
status=0
"$PCSIM_BIN" run "$small" --no-report --restart edited -o refused > refused.log 2>&1 || status=$?
if [ $status -ne 2 ] || [ "$(grep -c 'pcsim: error' refused.log)" -ne 1 ] ||
  ! grep -q -- "--restart.*shifted 7 times; this run's shifts 4 times at most" refused.log ||
  [ -e refused ] || [ -e refused.partial ]; then
  cat refused.log
  problem "7 shifts: exit $status"
fi
echo "ok   refused: $(grep 'pcsim: error' refused.log)"

# 5. A windy line, restarted before its window's first shift.
windy=("$PCSIM_BIN" run "$PCSIM_SOURCE_DIR/runs/conditions/en50318-300-wind.yaml" --no-report
  --set catenary.design.spans.count=30 --set window.spans_behind=2)
pcsim_run windy.log "${windy[@]}" -o windy -ts_max_steps 3600
pcsim_run windy-stop.log "${windy[@]}" -o windy-stop -ts_max_steps 2000
[ "$(attribute windy-stop/checkpoint.h5 window_shifts)" = 0 ] || problem "windy-stop: shifted"
pcsim_run windy-restart.log "${windy[@]}" --restart windy-stop -o windy-restart -ts_max_steps 3600
$equal windy windy-restart 0 || problem "the windy window's restart differs"
"$PCSIM_PYTHON" - <<'PY' || problem "the windy window's restart: its lateral records differ"
import h5py
import numpy as np
g = "pantographs/pantograph/"
a, b = (h5py.File(f"{d}/results.h5", "r") for d in ("windy", "windy-restart"))
assert a.attrs["complete"] == b.attrs["complete"] == 1
for name in ("wire_lateral", "cross_wind_force", "head_lateral_offset"):
    assert np.array_equal(a[g + name][:], b[g + name][:]), name
PY
[ "$(shifts_of windy-restart)" = 1 ] || problem "windy-restart: not 1 shift"
echo "ok   windy line: stopped at step 2000 before any shift, restarted: equal bit for bit"
