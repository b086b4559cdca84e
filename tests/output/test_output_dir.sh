#!/bin/bash
# pcsim writes, replaces or deletes only output folders that it created
# (marked by .pcsim-result). Each refused case must exit 2 with one message
# naming the key (-o or the scene's 'name'), leave every file as it was, and
# leave nothing behind (no <dir>.partial, lock, old copy or out/ folder).
# Also: a second run on a folder being written is refused and the first run
# goes on; a re-run replaces an earlier result only once it has succeeded; a
# failing run leaves the earlier result intact; SIGTERM/SIGINT leave no empty
# <dir>.partial.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
tmp=$(mktemp -d)   # the files whose state is checked
logs=$(mktemp -d)  # pcsim's output
first_pid=""
cleanup() {
  if [ -n "$first_pid" ]; then kill "$first_pid" 2> /dev/null || true; fi
  rm -rf "$tmp" "$logs"
}
trap cleanup EXIT
D=$PCSIM_SOURCE_DIR/tests/catenary/data
mpirun_2() { timeout 60 mpirun -n 2 "$@"; }
failures=0
fail() {
  echo "FAIL $*" >&2
  failures=$((failures + 1))
}

# A quick static scene (two spans, 0.1 s) in a work folder with user files.
work=$tmp/work
mkdir -p "$work/data"
scene() {  # scene FILE NAME_LINE
  printf '%s\ncatenary: {design: %s/two-span.yaml, form_finding: false}\n' "$2" "$D" > "$1"
}
scene "$work/quick.yaml" "name: quick"
echo "user notes" > "$work/notes.txt"
echo "1 2 3" > "$work/data/measured.csv"

# State of a folder tree: every path with its type and content checksum. The
# inside of a <dir>.partial folder is left out: a run alive during a check
# streams its results there (the folder itself is listed).
snapshot() {
  (cd "$1" && find . -path '*.partial/*' -prune -o -printf '%p %y\n' | sort &&
    find . -path '*.partial/*' -prune -o -type f -exec md5sum {} + | sort)
}

# expect_refused NAME DIR_FROM_WHICH_TO_RUN NEEDLES... -- PCSIM ARGS...
# Runs pcsim in the folder, on 1 rank; checks exit 2, one message containing
# every needle, and that the whole $tmp tree is unchanged.
expect_refused() {
  local name=$1 where=$2
  shift 2
  local needles=()
  while [ "$1" != "--" ]; do
    needles+=("$1")
    shift
  done
  shift
  local before after status=0
  before=$(snapshot "$tmp")
  (cd "$where" && timeout 60 "$PCSIM_BIN" "$@" > "$logs/stdout" 2> "$logs/stderr") || status=$?
  local err
  err=$(cat "$logs/stderr")
  after=$(snapshot "$tmp")
  local problems=()
  [ "$status" -eq 2 ] || problems+=("exit $status instead of 2")
  [ "$(printf '%s\n' "$err" | grep -c .)" -eq 1 ] || problems+=("not one message")
  local needle
  for needle in "${needles[@]}"; do
    [[ "$err" == *"$needle"* ]] || problems+=("message lacks '$needle'")
  done
  if [ "$before" != "$after" ]; then
    problems+=("files changed: $(diff <(echo "$before") <(echo "$after") | grep '^[<>]' | head -5 |
      tr '\n' ' ')")
  fi
  if [ ${#problems[@]} -gt 0 ]; then
    fail "$name: $(IFS=';'; echo "${problems[*]}"); stderr: $err"
  else
    echo "ok   $name: $err"
  fi
}

# -o at the working directory, a folder containing it, or a foreign folder.
expect_refused dot "$work" "key '-o'" "'.' is the working directory" -- \
  static quick.yaml -o .
expect_refused dot-slash "$work" "key '-o'" "is the working directory" -- \
  static quick.yaml -o ./
expect_refused parent "$work/data" "key '-o'" "contains the working directory" -- \
  static ../quick.yaml -o ..
expect_refused grandparent "$work/data" "key '-o'" "contains the working directory" -- \
  static ../quick.yaml -o "$tmp"
expect_refused foreign "$tmp" "key '-o'" "not empty and was not written by pcsim" -- \
  static work/quick.yaml -o work/data
expect_refused holds-scene "$tmp" "key '-o'" "holds the scene file" -- \
  static work/quick.yaml -o work
echo "not a folder" > "$tmp/plain-file"
expect_refused file "$tmp" "key '-o'" "exists and is not a folder" -- \
  static work/quick.yaml -o plain-file
rm "$tmp/plain-file"
# On 2 ranks: the same message once, exit 2 from mpirun, no hang.
status=0
(cd "$work" && mpirun_2 "$PCSIM_BIN" static quick.yaml -o . > /dev/null 2> "$logs/np2.err") ||
  status=$?
n=$(grep -c "^pcsim" "$logs/np2.err" || true)
if [ "$status" -ne 2 ] || [ "$n" -ne 1 ] || ! grep -q "key '-o'" "$logs/np2.err"; then
  fail "dot on 2 ranks: exit $status, $n messages: $(cat "$logs/np2.err")"
else
  echo "ok   dot on 2 ranks: exit 2, one message"
fi

# Scene names that are not one folder name (no -o: the folder would be out/<name>).
for bad in '".."' '""' '"../../x"' '"a/b"' '"."'; do
  scene "$work/bad-name.yaml" "name: $bad"
  expect_refused "name $bad" "$work" "bad-name.yaml" "key 'name'" -- static bad-name.yaml
  rm "$work/bad-name.yaml"
done
[ ! -e "$work/out" ] || fail "an out/ folder was created"

# A result, then a re-run that fails after the output folder was opened
# (Newton limited to 1 iteration: exit 3): the earlier result stays intact.
(cd "$work" && "$PCSIM_BIN" static quick.yaml -o result > /dev/null)
grep -q '"complete": true' "$work/result/.pcsim-result" || fail "result: manifest not complete"
before=$(snapshot "$work/result")
status=0
(cd "$work" && "$PCSIM_BIN" static quick.yaml -o result -snes_max_it 1 > /dev/null 2>&1) ||
  status=$?
leftovers=$(cd "$work" && ls -d result.* 2> /dev/null || true)
if [ "$status" -ne 3 ] || [ "$before" != "$(snapshot "$work/result")" ] || [ -n "$leftovers" ]; then
  fail "failing re-run: exit $status, result changed or left: $leftovers"
else
  echo "ok   failing re-run (exit 3) left the earlier result intact"
fi

# A second run while a first one writes the folder: refused, the first goes on.
# The lock held by flock(1) around the second run stands for the first run.
touch "$work/result.pcsim-lock"
before=$(snapshot "$tmp")
status=0
(cd "$work" && flock result.pcsim-lock timeout 60 "$PCSIM_BIN" static quick.yaml -o result \
  > /dev/null 2> "$logs/lock.err") || status=$?
after=$(snapshot "$tmp")
rm "$work/result.pcsim-lock"
if [ "$status" -ne 2 ] || ! grep -q "another pcsim run is writing" "$logs/lock.err" ||
  [ "$before" != "$after" ]; then
  fail "held lock: exit $status: $(cat "$logs/lock.err")"
else
  echo "ok   held lock: $(cat "$logs/lock.err")"
fi

# A real first run (the full EN 50318 run, minutes long) on the folder of the
# earlier result: a second run is refused while it runs; SIGTERM then ends it,
# and it leaves neither its lock nor an empty partial folder, and the earlier
# result intact. A signal that arrives once the time stepping has begun stops
# the run at a step and keeps its data: then the partial folder holds
# results.h5, a checkpoint and a summary marked incomplete (the restart tests:
# tests/contact/test_run_restart.sh); it is removed here before the next case.
for signal in TERM INT; do
  before=$(snapshot "$work/result")
  # SIGINT is ignored by background jobs of a script: start with the default.
  /usr/bin/python3 -c 'import os, signal, sys
signal.signal(signal.SIGINT, signal.SIG_DFL)
os.execv(sys.argv[1], sys.argv[1:])' "$PCSIM_BIN" run "$PCSIM_SOURCE_DIR/runs/en50318-300.yaml" \
    -o "$work/result" --overwrite > "$logs/first.log" 2>&1 &
  first_pid=$!
  for _ in $(seq 300); do
    [ -e "$work/result.partial/.pcsim-result" ] && break
    sleep 0.1
  done
  expect_refused "second run (first run alive)" "$work" "another pcsim run is writing" -- \
    static quick.yaml -o result
  kill -0 "$first_pid" || fail "the first run ended early: $(cat "$logs/first.log")"
  kill -"$signal" "$first_pid"
  status=0
  wait "$first_pid" || status=$?
  first_pid=""
  if [ -d "$work/result.partial" ] && [ -f "$work/result.partial/checkpoint.h5" ] &&
    grep -q '"complete": false' "$work/result.partial/summary.json"; then
    echo "     (SIG$signal arrived while stepping: partial folder kept with its data)"
    rm -rf "$work/result.partial"
  fi
  leftovers=$(cd "$work" && ls -d result.* 2> /dev/null || true)
  if [ -n "$leftovers" ] || [ "$before" != "$(snapshot "$work/result")" ]; then
    fail "SIG$signal: left '$leftovers' or changed the earlier result"
  else
    echo "ok   SIG$signal ended the first run (status $status), no lock or empty partial left"
  fi
done

# A successful re-run replaces the earlier result, with nothing left beside it.
old_pid=$(sed -n 's/.*"pid": \([0-9]*\).*/\1/p' "$work/result/.pcsim-result")
(cd "$work" && "$PCSIM_BIN" static quick.yaml -o result > /dev/null)
new_pid=$(sed -n 's/.*"pid": \([0-9]*\).*/\1/p' "$work/result/.pcsim-result")
leftovers=$(cd "$work" && ls -d result.* 2> /dev/null || true)
if [ "$old_pid" = "$new_pid" ] || [ -n "$leftovers" ] || [ ! -f "$work/result/static.h5" ]; then
  fail "re-run: manifest pid $old_pid -> $new_pid, leftovers '$leftovers'"
else
  echo "ok   re-run replaced the earlier result (manifest pid $old_pid -> $new_pid)"
fi

# A file the user put into a result (a post-processing plot) is never deleted:
# the re-run is refused and names it, even with --overwrite.
echo "plot" > "$work/result/plot.png"
before=$(snapshot "$work/result")
expect_refused "re-run over a user's file" "$work" "plot.png" -- static quick.yaml -o result \
  --overwrite
[ "$before" = "$(snapshot "$work/result")" ] || fail "the result with the user's file changed"
rm "$work/result/plot.png"

# The default folder out/<name>, twice (the second run replaces the first).
(cd "$work" && "$PCSIM_BIN" static quick.yaml > /dev/null && "$PCSIM_BIN" static quick.yaml > /dev/null)
[ "$(cd "$work/out" && ls -A)" = "quick" ] || fail "out/ holds $(ls -A "$work/out")"
# The user's files were never touched.
[ "$(cat "$work/notes.txt")" = "user notes" ] && [ "$(cat "$work/data/measured.csv")" = "1 2 3" ] ||
  fail "user files changed"

if [ "$failures" -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all output-folder cases passed"
