#!/bin/bash
# Checkpoint/restart of `pcsim run` on two ranks, on the short EN 50318 case
# (200 steps; the one-rank cases and the refusals: test_run_restart.sh).
#  - With deterministic linear solvers (every LU factorisation sequential and
#    redundant on each rank), SIGTERM on rank 1 only at step 60 stops both
#    ranks at that step (the stop is agreed collectively), and the restart
#    equals the uninterrupted run: every time series within 1e-12 relative
#    (measured: bitwise). This checks that the checkpoint holds the whole
#    distributed state.
#  - With the default solvers (MUMPS for the static solves, the domain
#    decomposition of solvers/schur_dd.hpp for the steps), the restart is
#    checked to 1e-9 relative: MUMPS schedules its parallel factorisation
#    dynamically, and the order of its floating-point sums changes from run to
#    run (measured with MUMPS also for the steps: up to 2e-11 relative in the
#    contact force between two uninterrupted runs, 1.3e-11 between a restart
#    and an uninterrupted run).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
compare="$PCSIM_PYTHON $PCSIM_SOURCE_DIR/tests/contact/compare_runs.py"
sed -e "s|\.\./\.\./\.\./meshes/|$PCSIM_SOURCE_DIR/meshes/|" \
  "$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml" > "$tmp/short.yaml"
cd "$tmp"
failures=0
fail() {
  echo "FAIL $*" >&2
  failures=$((failures + 1))
}
run() {  # run LOG ARGS...: pcsim run short.yaml ARGS on 2 ranks, its status in $status
  local log=$1
  shift
  status=0
  timeout 600 mpirun -n 2 "$PCSIM_BIN" run short.yaml "$@" > "$log" 2>&1 || status=$?
}
# Sequential LU on every rank (PETSc's for the step matrix, MUMPS's
# sequential one for the static solves, whose matrices PETSc's LU refuses).
deterministic=(-cheap_pc_type redundant -cheap_redundant_pc_factor_mat_ordering_type qmd)
for prefix in static_ start_ start_load_; do
  deterministic+=("-${prefix}pc_type" redundant "-${prefix}redundant_pc_factor_mat_solver_type" mumps)
done

run ref-det.log -o ref-det -ts_max_steps 200 "${deterministic[@]}"
[ "$status" -eq 0 ] || fail "deterministic reference: exit $status: $(tail -3 ref-det.log)"
run term.log -o term -ts_max_steps 200 -pcsim_debug_signal_step 60 -pcsim_debug_signal_rank 1 \
  "${deterministic[@]}"
step=$("$PCSIM_PYTHON" -c "import h5py; print(int(h5py.File('term.partial/checkpoint.h5', 'r').attrs['step']))")
if [ "$status" -ne 143 ] || [ "$step" -ne 60 ] || [ -e term ]; then
  fail "SIGTERM on rank 1 at step 60: exit $status, checkpoint at step $step"
fi
run restart-det.log -o restart-det --restart term.partial -ts_max_steps 200 "${deterministic[@]}"
if [ "$status" -ne 0 ] || ! $compare ref-det restart-det 1e-12; then
  fail "deterministic solvers: restart after SIGTERM: exit $status"
else
  echo "ok   deterministic solvers: SIGTERM on rank 1 stopped both at step 60, restart equal"
fi

run ref.log -o ref -ts_max_steps 200
run stop60.log -o stop60 -ts_max_steps 60
run restart.log -o restart --restart stop60 -ts_max_steps 200
if [ "$status" -ne 0 ] || ! $compare ref restart 1e-9; then
  fail "default solvers: restart from step 60: exit $status"
else
  echo "ok   default solvers: stopped at step 60, restarted: equal within 1e-9"
fi

# A stop at or before the checkpoint (-ts_max_steps counts from the run's
# start): refused before any work on both ranks, nothing written.
run nothing.log -o nothing --restart stop60 -ts_max_steps 60
if [ "$status" -ne 2 ] || [ "$(grep -c '^pcsim: error' nothing.log)" -ne 1 ] ||
  ! grep -qF "key '-ts_max_steps': 60 steps: the checkpoint in 'stop60' is at step 60" nothing.log ||
  [ -e nothing ] || [ -e nothing.partial ]; then
  fail "restart with nothing left to step: exit $status: $(tail -2 nothing.log)"
else
  echo "ok   restart with -ts_max_steps 60 from step 60: refused (exit 2), nothing written"
fi

if [ "$failures" -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all restart cases passed on 2 ranks"
