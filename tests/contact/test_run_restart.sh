#!/bin/bash
# Checkpoint/restart of `pcsim run` on one rank (README "Interrupted runs and
# restarts"), on the short EN 50318 case (200 steps of 1 ms):
#  - a run stopped at step 60 (-ts_max_steps; a dropper has switched by then,
#    so the cheap path's frozen rank-one terms are in the checkpoint) and
#    restarted equals the uninterrupted run: every time series within 1e-12
#    relative (one rank: the arithmetic is the same, the result bitwise equal);
#  - SIGTERM, raised at step 120 by the run itself (-pcsim_debug_signal_step)
#    and sent from outside: exit 143, "<dir>.partial" with results.h5 up to the
#    step (complete = 0), a checkpoint and a summary saying "complete": false,
#    no final folder, no lock; restarting it gives the uninterrupted run;
#  - refused restarts (exit 2, one message naming --restart, nothing written):
#    a changed scene file, a --set the first run did not have (the message
#    names both runs' overrides), another rank
#    count, the restart folder as the new result's folder, a folder without
#    checkpoint.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:?}"
tmp=$(mktemp -d)
background=""
cleanup() {
  if [ -n "$background" ]; then kill -9 "$background" 2> /dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
compare="$PCSIM_PYTHON $PCSIM_SOURCE_DIR/tests/contact/compare_runs.py"
sed -e "s|\.\./\.\./\.\./meshes/|$PCSIM_SOURCE_DIR/meshes/|" \
  "$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml" > "$tmp/short.yaml"
cd "$tmp"
failures=0
fail() {
  echo "FAIL $*" >&2
  failures=$((failures + 1))
}
run() {  # run LOG ARGS...: pcsim run short.yaml ARGS, its status in $status
  local log=$1
  shift
  status=0
  timeout 300 "$PCSIM_BIN" run short.yaml "$@" > "$log" 2>&1 || status=$?
}
h5() {  # h5 FILE EXPRESSIONS: prints EXPRESSIONS of the open file f
  "$PCSIM_PYTHON" -c "import h5py, json; f = h5py.File('$1', 'r'); print($2)"
}

# The uninterrupted run.
run ref.log -o ref -ts_max_steps 200
[ "$status" -eq 0 ] || fail "reference run: exit $status: $(tail -3 ref.log)"

# Stopped at step 60, restarted to step 200.
run stop60.log -o stop60 -ts_max_steps 60
switched=$(h5 stop60/checkpoint.h5 \
  "int(max(f['/terms'][k][0] if f['/terms'][k].shape[0] else 0 for k in f['/terms']))")
[ "$switched" -ge 1 ] || fail "no switched dropper in the checkpoint at step 60 ($switched)"
run restart60.log -o restart60 --restart stop60 -ts_max_steps 200
if [ "$status" -ne 0 ] || ! $compare ref restart60 1e-12; then
  fail "restart from step 60: exit $status"
else
  echo "ok   stopped at step 60 ($switched switched dropper(s) frozen), restarted: equal"
fi

# SIGTERM at step 120, raised by the run.
run term.log -o term -ts_max_steps 200 -pcsim_debug_signal_step 120
check_partial() {  # check_partial NAME STEP: the partial folder of an interrupted run
  local name=$1 step=$2 problems=()
  [ "$status" -eq 143 ] || problems+=("exit $status instead of 143")
  [ ! -e "$name" ] || problems+=("a final folder appeared")
  [ ! -e "$name.pcsim-lock" ] || problems+=("lock left")
  [ "$(h5 "$name.partial/results.h5" "int(f.attrs['complete']), f['/time'].shape[0]")" = \
    "0 $((step + 1))" ] || problems+=("results.h5 not incomplete with $((step + 1)) steps")
  [ "$(h5 "$name.partial/checkpoint.h5" "int(f.attrs['step'])")" = "$step" ] ||
    problems+=("checkpoint not at step $step")
  "$PCSIM_PYTHON" -c "import json, sys; s = json.load(open('$name.partial/summary.json'))
sys.exit(0 if s['complete'] is False and s['interrupted_by'] == 'SIGTERM' else 1)" ||
    problems+=("summary.json does not say incomplete")
  if [ ${#problems[@]} -gt 0 ]; then
    fail "$name: $(IFS=';'; echo "${problems[*]}")"
    return 1
  fi
}
if check_partial term 120; then
  run term-restart.log -o term-restart --restart term.partial -ts_max_steps 200
  if [ "$status" -ne 0 ] || ! $compare ref term-restart 1e-12; then
    fail "restart after SIGTERM: exit $status"
  else
    echo "ok   SIGTERM at step 120: partial folder marked incomplete, restart equal"
  fi
fi

# SIGTERM from outside, once the first checkpoint (step 50) is on disk.
cp short.yaml every50.yaml
printf 'output:\n  checkpoint_every: 50\n' >> every50.yaml
timeout 300 "$PCSIM_BIN" run every50.yaml -o kill > kill.log 2>&1 &
background=$!
for _ in $(seq 600); do
  [ -e kill.partial/checkpoint.h5 ] && break
  sleep 0.1
done
kill -TERM "$background"
status=0
wait "$background" || status=$?
background=""
step=$(h5 kill.partial/checkpoint.h5 "int(f.attrs['step'])")
if check_partial kill "$step" && [ "$step" -lt 1440 ]; then
  echo "ok   SIGTERM from outside: stopped at step $step, partial folder marked incomplete"
fi

# Refused restarts: exit 2, one message naming --restart, no new folder.
refused() {  # refused NAME NEEDLE -- COMMAND...
  local name=$1 needle=$2
  shift 3
  status=0
  "$@" -o "new-$name" > "$name.out" 2> "$name.err" || status=$?
  if [ "$status" -ne 2 ] || [ "$(grep -c "^pcsim" "$name.err")" -ne 1 ] ||
    ! grep -q "key '--restart'.*$needle" "$name.err" || [ -n "$(ls -d new-"$name"* 2> /dev/null)" ]; then
    fail "$name: exit $status: $(cat "$name.err")"
  else
    echo "ok   $name refused: $(cat "$name.err")"
  fi
}
sed -e 's/static_force: 120/static_force: 121/' short.yaml > changed.yaml
refused changed-scene "scene file 'changed.yaml' (with its base files and overrides) differs.*(both runs have no --set: the scene file or a base file it names is not what the checkpointed run read)$" -- \
  timeout 300 "$PCSIM_BIN" run changed.yaml --restart stop60
# The message names both runs' overrides (the checkpointed one's from its summary.json).
refused changed-override "scene file 'short.yaml' (with its base files and overrides) differs.*(the checkpointed run had no --set, this command has --set pantographs.0..static_force=121: give the same --set overrides)$" -- \
  timeout 300 "$PCSIM_BIN" run short.yaml --set 'pantographs[0].static_force=121' --restart stop60
refused two-ranks "written on 1 rank(s) and this run has 2" -- \
  timeout 300 mpirun -n 2 "$PCSIM_BIN" run short.yaml --restart stop60
status=0
timeout 300 "$PCSIM_BIN" run short.yaml --restart term.partial -o term > same.out 2> same.err ||
  status=$?
if [ "$status" -ne 2 ] || ! grep -q "would become the new result's folder" same.err; then
  fail "restart into its own folder: exit $status: $(cat same.err)"
else
  echo "ok   restart into its own folder refused: $(cat same.err)"
fi
refused no-checkpoint "holds no checkpoint" -- \
  timeout 300 "$PCSIM_BIN" run short.yaml --restart ref/..

if [ "$failures" -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all restart cases passed on 1 rank"
