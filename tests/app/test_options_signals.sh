#!/bin/bash
# Options and signals as README ("Exit codes", "Interrupted runs") says:
#  1. a single-dash option that neither pcsim nor PETSc reads (-foo_bar) is an
#     input error (exit 2) naming it, before any work, nothing left behind;
#  2. one with a solver's prefix that no solver read (-ts_dtt, a typo of
#     -ts_dt) is a warning on stderr after the run; the inner solvers'
#     prefixes of -pc_type redundant (redundant_) are known;
#  3. -help lists the options a run reads and stops before the time loop,
#     exit 0, nothing written; -citations cites the HHT method and the thesis;
#  4. SIGTERM during the set-up ends the run with 143 and nothing left behind;
#  5. a time step that cannot converge (here: solver options that starve the
#     linear solve) is exit 3 with one line naming the likely inputs, no
#     PETSc trace, nothing left behind;
#  6. SIGTERM to `pcsim sweep` stops its running cases (each keeps its
#     checkpoint), starts no other, exits 143 and leaves no process behind.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
long=$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml
fail() { echo "FAIL: $*"; exit 1; }

run() {  # run CODE COMMAND...: the exit code must be CODE
  local want=$1; shift
  set +e; "$@" > out.log 2> err.log; local code=$?; set -e
  [ "$code" -eq "$want" ] || { cat out.log err.log; fail "exit $code, not $want: $*"; }
}

# 1. Unknown option: exit 2 naming it; no folder.
run 2 "$PCSIM_BIN" run "$scene" -o r1 -foo_bar 1
grep -qF "key '-foo_bar': unknown option" err.log || fail "message: $(cat err.log)"
[ ! -e r1 ] && [ ! -e r1.partial ] || fail "-foo_bar left a folder"
run 2 "$PCSIM_BIN" check "$scene" -foo_bar
echo "ok   -foo_bar: exit 2, named, nothing left"

# 2. A solver option nothing read: warned, and the run is the default one.
run 0 "$PCSIM_BIN" run "$scene" -o r2 --no-report -ts_max_steps 5 -ts_dtt 1e-3
grep -qF "warning: option -ts_dtt was not read" err.log || fail "no warning: $(cat err.log)"
! grep -qF "ts_max_steps" err.log || fail "-ts_max_steps was read, yet warned about"
echo "ok   -ts_dtt: warned on stderr"
# The inner solvers of PETSc's -pc_type redundant on a solver without a prefix
# (pcsim static's): known prefixes, read, no warning.
run 0 "$PCSIM_BIN" static "$scene" -o r2s -pc_type redundant -redundant_pc_type lu \
  -redundant_pc_factor_mat_solver_type klu
! grep -q "warning: option" err.log || fail "redundant_: warned: $(cat err.log)"
echo "ok   -redundant_pc_type: known and read"
# A run too short for the statistics' filter (9 to 15 samples once threw an
# internal error): the run ends normally and says why there are no figures.
run 0 "$PCSIM_BIN" run "$scene" -o r2b --no-report -ts_max_steps 12
grep -qF "did not cross the analysis section" out.log || fail "12 steps: $(cat out.log err.log)"
echo "ok   -ts_max_steps 12: no statistics, said so"

# 3. -help: the options listed, no time step, nothing written.
run 0 "$PCSIM_BIN" run "$scene" -o r3 -help
grep -q -- "-ts_type <now hht" out.log || fail "-help lists no TS option: $(head -50 out.log)"
grep -qF "stopped before the time loop" out.log || fail "-help ran on"
! grep -q "step [0-9]" out.log || fail "-help stepped"
[ ! -e r3 ] && [ ! -e r3.partial ] || fail "-help wrote $(ls -d r3*)"
echo "ok   -help: options listed, stopped before stepping, nothing written"

# 4. SIGTERM during the set-up (the set-up of the line at 100 spans takes ~3 s,
#    its static solution 1.5 s: 0.3 s is well inside it; the 10-span line's
#    static solution takes 0.16 s since KLU, runs/bench_catenary.sh, and its
#    set-up ended before the signal in 2 of 3 runs): 143, nothing left.
set +e
"$PCSIM_BIN" run "$long" --set catenary.design.spans.count=100 -o r4 --no-report > out.log 2>&1 &
pid=$!
sleep 0.3
kill -TERM $pid
wait $pid
code=$?
set -e
[ $code -eq 143 ] || { cat out.log; fail "SIGTERM in the set-up: exit $code"; }
! grep -q "step [0-9]" out.log || fail "the signal came after the set-up; test needs a shorter sleep"
[ ! -e r4 ] && [ ! -e r4.partial ] || fail "SIGTERM in the set-up left $(ls -d r4*)"
echo "ok   SIGTERM in the set-up: 143, nothing left"

# 3b. -citations: the HHT method and the thesis are cited (PetscCitationsRegister).
run 0 "$PCSIM_BIN" run "$scene" -o r3b --no-report -ts_max_steps 2 -citations cite.bib
grep -q "HilberHughesTaylor1977" cite.bib && grep -q "pcsimThesis2014" cite.bib ||
  fail "-citations lacks HHT or the thesis: $(grep -o '@[a-z]*{[A-Za-z0-9]*' cite.bib)"
echo "ok   -citations: HHT and the thesis"

# 5. A step that fails: exit 3, one message, no trace.
run 3 "$PCSIM_BIN" run "$scene" -o r5 --no-report -ksp_type cg -pc_type none -ksp_max_it 2
grep -qF "solver failure: the time step did not converge" err.log || fail "$(cat err.log)"
[ "$(wc -l < err.log)" -eq 1 ] || fail "more than one line on stderr: $(cat err.log)"
! grep -q "Configure options\|PETSc ERROR" out.log err.log || fail "a PETSc trace was printed"
[ ! -e r5 ] && [ ! -e r5.partial ] || fail "a failed run left $(ls -d r5*)"
echo "ok   failed step: exit 3, one line, no PETSc trace, nothing left"

# 6. SIGTERM to a sweep of three cases, two at a time, while they step.
set +e
# The full EN 50318 scene (7080 steps, several seconds per case): both cases
# are still stepping when the signal comes.
"$PCSIM_BIN" sweep "$PCSIM_SOURCE_DIR/runs/en50318-300.yaml" -o s \
  --set simulation.speed_kmh=250,300,320 -j 2 --no-report > out.log 2>&1 &
pid=$!
for _ in $(seq 1 600); do  # until both running cases are in their time loop (at most 60 s)
  n=$(grep -l "pantograph at" s.partial/cases/*.log 2> /dev/null | wc -l)
  [ "$n" -ge 2 ] && break
  sleep 0.1
done
cases=$(pgrep -P $pid -f " run " || true)  # not the MPI singleton's orted
kill -TERM $pid
wait $pid
code=$?
set -e
[ $code -eq 143 ] || { cat out.log; fail "sweep after SIGTERM: exit $code"; }
[ -n "$cases" ] || fail "no running case seen"
for c in $cases; do ! kill -0 "$c" 2> /dev/null || { ps -o pid,ppid,stat,args -p "$c"; fail "case process $c left running"; }; done
grep -qF "stopping 2 running case(s)" out.log || fail "sweep: $(cat out.log)"
for c in 01_speed_kmh-250 02_speed_kmh-300; do
  [ -f "s.partial/cases/$c.partial/checkpoint.h5" ] || fail "case $c kept no checkpoint"
done
[ ! -e s.partial/cases/03_speed_kmh-320.log ] || fail "a case started after the signal"
[ ! -e s ] || fail "an interrupted sweep made its final folder"
echo "ok   sweep: SIGTERM stopped both running cases (checkpoints kept), 143, none left"
