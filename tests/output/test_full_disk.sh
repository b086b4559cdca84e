#!/bin/bash
# A full file system (README "Exit codes", 5): `pcsim run` into small tmpfs
# mounts. Each run must end with exit 5 (or 0 where the results fit), one
# 'pcsim: error' line naming the file and the OS error, no HDF5 error stack,
# no signal (a crash gave 139), no final folder, and a readable .partial
# folder (its manifest says incomplete). The same on 2 ranks, with and
# without checkpoints: exit 5, no hang. Then a modal cache on a full file
# system: a warning, and the run goes on (exit 0).
# Needs root for mount (CI runs as root); fails (does not skip) without it.
# pcsim-test-processors: 2
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
tmp=$(mktemp -d)
mounts=()
cleanup() {
  for m in "${mounts[@]}"; do umount "$m" 2> /dev/null || true; done
  rm -rf "$tmp"
}
trap cleanup EXIT
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

mount_tmpfs() {  # SIZE -> prints the mount point
  local dir=$tmp/fs-$1
  mkdir -p "$dir"
  if ! mount -t tmpfs -o "size=$1" tmpfs "$dir" 2> "$tmp/mount.err"; then
    echo "cannot mount a tmpfs (not root?): $(cat "$tmp/mount.err")" >&2
    exit 1
  fi
  echo "$dir"
}

for size in 20k 60k 150k 400k 4m; do
  fs=$(mount_tmpfs $size)
  mounts+=("$fs")
  status=0
  (cd "$tmp" && timeout 300 "$PCSIM_BIN" run "$scene" -o "$fs/r" --no-report \
    > "$tmp/$size.out" 2> "$tmp/$size.err") || status=$?
  errors=$(grep -c '^pcsim: error' "$tmp/$size.err" || true)
  if grep -q 'HDF5-DIAG\|PETSc ERROR' "$tmp/$size.err"; then fail "$size: error stack printed"; fi
  if [ "$status" -eq 0 ]; then
    [ -f "$fs/r/results.h5" ] || fail "$size: exit 0 without results"
    [ "$errors" -eq 0 ] || fail "$size: exit 0 with an error message"
    echo "$size: fits (exit 0)"
    continue
  fi
  [ "$status" -eq 5 ] || fail "$size: exit $status, expected 5 (or 0)"
  [ "$errors" -eq 1 ] || fail "$size: $errors 'pcsim: error' lines, expected 1"
  grep -q "^pcsim: error: cannot write $fs/r.partial/[a-z0-9._-]*: No space left on device" \
    "$tmp/$size.err" || fail "$size: the message does not name the file and the OS error"
  [ ! -e "$fs/r" ] || fail "$size: a final folder appeared"
  [ -d "$fs/r.partial" ] || fail "$size: no partial folder kept"
  grep -q '"complete": false' "$fs/r.partial/.pcsim-result" ||
    fail "$size: the partial folder's manifest is missing or says complete"
  [ ! -e "$fs/r.pcsim-lock" ] || fail "$size: lock left"
  echo "$size: exit $status: $(grep '^pcsim: error' "$tmp/$size.err")"
done
[ "$failures" -gt 0 ] && cat "$tmp"/*.err | head -40

# On 2 ranks (only rank 0 writes; every rank must stop at the same step and
# take the same collectives after it, with and without checkpoints): exit 5,
# one error line, within the time limit (a hang is a failure).
launch=$(command -v mpiexec || command -v mpirun)
for size in 150k 400k; do
  for every in 0 20; do
    fs=$(mount_tmpfs "$size")
    mounts+=("$fs")
    status=0
    (cd "$tmp" && timeout 120 "$launch" -n 2 "$PCSIM_BIN" run "$scene" -o "$fs/r" --no-report \
      --set output.checkpoint_every=$every < /dev/null > "$tmp/np2-$size-$every.out" \
      2> "$tmp/np2-$size-$every.err") || status=$?
    errors=$(grep -c '^pcsim: error' "$tmp/np2-$size-$every.err" || true)
    if [ "$status" -ne 5 ] || [ "$errors" -ne 1 ]; then
      fail "2 ranks, $size, checkpoint_every $every: exit $status, $errors error line(s)"
    fi
    [ ! -e "$fs/r" ] || fail "2 ranks, $size: a final folder appeared"
    echo "2 ranks, $size, checkpoint_every $every: exit $status"
    umount "$fs"
  done
done

# Results that fit, a report that does not (results ~0.6 MB, report ~0.25 MB
# on 0.7 MB): exit 5 naming report.html, the results kept in the partial
# folder, no half-written report.
fs=$(mount_tmpfs 700k)
mounts+=("$fs")
status=0
(cd "$tmp" && timeout 300 "$PCSIM_BIN" run "$scene" -o "$fs/r" > "$tmp/report.out" \
  2> "$tmp/report.err") || status=$?
[ "$status" -eq 5 ] || fail "report on a full disk: exit $status (expected 5)"
grep -q "^pcsim: error: cannot write $fs/r.partial/report.html: No space left on device" \
  "$tmp/report.err" || fail "report on a full disk: $(cat "$tmp/report.err")"
[ -f "$fs/r.partial/results.h5" ] && [ ! -e "$fs/r" ] || fail "report: results not kept as partial"
[ ! -e "$fs/r.partial/report.html" ] && [ ! -e "$fs/r.partial/report.html.tmp" ] ||
  fail "report: a half-written report was left"
echo "report on a full disk: exit $status: $(grep '^pcsim: error' "$tmp/report.err")"

# The modal cache on a full file system: a warning, the run completes.
fs=$(mount_tmpfs 8k)
mounts+=("$fs")
head -c 4096 /dev/zero > "$fs/filler" 2> /dev/null || true
status=0
(cd "$tmp" && timeout 300 "$PCSIM_BIN" run "$PCSIM_SOURCE_DIR/tests/assembly/data/three-span-modal.yaml" \
  -o "$tmp/modal" --cache "$fs/cache" --no-report -ts_max_steps 5 \
  > "$tmp/modal.out" 2> "$tmp/modal.err") || status=$?
[ "$status" -eq 0 ] || fail "modal cache on a full disk: exit $status (expected 0)"
grep -q '^pcsim: warning: the modal data are not cached' "$tmp/modal.err" ||
  fail "modal cache on a full disk: no warning"
if grep -q 'HDF5-DIAG' "$tmp/modal.err"; then fail "modal cache: HDF5 error stack"; fi
if compgen -G "$fs/cache/*tmp*" > /dev/null; then fail "modal cache: temporary file left"; fi
[ "$failures" -gt 0 ] && cat "$tmp/modal.err"
echo "$failures failure(s)"
[ "$failures" -eq 0 ]
