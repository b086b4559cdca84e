#!/bin/bash
# The modal level's basis against the machine's memory
# (simulation::check_modal_memory, docs/fidelity.md "Memory of the modal
# basis"): once the modes below the cut-off are counted (the inertia), before
# they are computed, a basis that would not fit is refused.
#  1. EN 50318's modal run on a machine of 150 MB, 200 MB on 2 ranks
#     (-pcsim_debug_machine_memory_mb): the FE system's estimate (0.09 GB,
#     the mesh-size check) fits, the basis (2736 vectors over 2852 kept rows
#     and the eigensolver's vectors, about 0.29 GB, the same where the
#     pilot may raise the cut-off: its rows are held once, read back from
#     the cache at a raise; 0.35 GB until 2026-12-07, when a pilot kept a
#     copy; beside the 0.10 GB in use) does not. Exit 2, one message
#     naming the scene file, the key (catenary.model, or
#     catenary.max_frequency_hz where the scene sets the cut-off) and the
#     need, on 1 and 2 ranks, with and without the accuracy pilot (whose
#     first modal run meets it); no output folder. Control: the same run on a
#     machine of 2000 MB starts (stopped after 2 steps).
#  2. The accuracy pilot's raise that the machine cannot hold: on the
#     three-span line the pilot raises 40.5 Hz to 50.6 Hz; with the raise
#     refused (-pcsim_debug_modal_memory_above_hz 45: a cut-off above 45 Hz
#     as if its basis did not fit) it says so, raises no further and the run
#     takes 40.5 Hz (summary.json: cutoff_raise_refused_hz 50.6); the
#     pilot is not cached (its cut-off is this machine's).
#  3. The rows of the pilot's first cut-off are held once: the raise reads
#     them back from the cache file the process wrote (the control of 2.:
#     "kept from the last", its results equal to the modes at once,
#     tests/assembly/test_modal_window.sh). Where that file could not be
#     written (a folder of its name in the cache), the raise says it
#     computes every mode again, and the run's contact force is the
#     control's to 1e-9 (the bound of test_modal_window.sh's raise against
#     the modes at once; the same modes in another order of computation).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
en=$PCSIM_SOURCE_DIR/runs/en50318-300-modal.yaml

refused() {  # label, key, the need in GB, command...
  local label=$1 key=$2 need=$3
  shift 3
  local code=0
  "$@" > "$tmp/out.log" 2> "$tmp/err.log" || code=$?
  [ "$code" -eq 2 ] || { echo "$label: exit $code, not 2"; cat "$tmp/out.log" "$tmp/err.log"; exit 1; }
  [ "$(grep -c "pcsim: error" "$tmp/err.log")" -eq 1 ] ||
    { echo "$label: not one message"; cat "$tmp/err.log"; exit 1; }
  grep -q "runs/en50318-300-modal.yaml: key '$key': the modal level's basis would not fit in this machine's memory: 2736 vectors (2646 modes below 69.7 Hz and the droppers' shapes) over 2852 kept rows need about $need GB" "$tmp/err.log" ||
    { echo "$label: message"; cat "$tmp/err.log"; exit 1; }
  [ ! -e "$tmp/run" ] || { echo "$label: an output folder was left"; exit 1; }
  echo "ok   $label: exit 2, $(grep -o "more than 90% of the machine's [0-9.]* GB" "$tmp/err.log")"
}

small=(-pcsim_debug_machine_memory_mb 150)
refused "1 rank, no pilot" catenary.model 0.29 "$PCSIM_BIN" run "$en" -o "$tmp/run" \
  --cache "$tmp/cache1" --no-report "${small[@]}"
# (Two ranks hold two FE systems, 0.18 GB: a machine of 200 MB holds them, not the bases.)
refused "2 ranks, no pilot" catenary.model 0.29 mpirun -n 2 "$PCSIM_BIN" run "$en" -o "$tmp/run" \
  --cache "$tmp/cache2" --no-report -pcsim_debug_machine_memory_mb 200
refused "1 rank, the pilot's first run" catenary.model 0.29 "$PCSIM_BIN" run "$en" -o "$tmp/run" \
  --cache "$tmp/cache3" --no-report "${small[@]}" -pcsim_accuracy_pilot true
refused "cut-off set by the scene" catenary.max_frequency_hz 0.29 "$PCSIM_BIN" run "$en" \
  -o "$tmp/run" --cache "$tmp/cache4" --no-report "${small[@]}" \
  --set catenary.max_frequency_hz=69.6595
"$PCSIM_BIN" run "$en" -o "$tmp/fits" --cache "$tmp/cache5" --no-report \
  -pcsim_debug_machine_memory_mb 2000 -ts_max_steps 2 > "$tmp/fits.log" 2>&1 ||
  { echo "a machine of 2000 MB refused"; cat "$tmp/fits.log"; exit 1; }
echo "ok   a machine of 2000 MB: the run starts"

# 2. The pilot's raise refused.
lumped=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
cutoffs() {  # the run's cut-off and the refused raise's (summary.json)
  /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1]))
p=j['accuracy_estimate']['pilot']
print('%.1f %.1f %d' % (j['modal']['cutoff_hz'], p['cutoff_raise_refused_hz'], p['cutoff_raises']))" \
    "$1/summary.json"
}
for case in raised refused; do
  extra=()
  [ "$case" = refused ] && extra=(-pcsim_debug_modal_memory_above_hz 45)
  "$PCSIM_BIN" run "$lumped" --set catenary.model=modal -pcsim_accuracy_pilot true \
    -o "$tmp/$case" --cache "$tmp/cache-$case" --no-report "${extra[@]}" > "$tmp/$case.log" 2>&1 ||
    { cat "$tmp/$case.log"; exit 1; }
done
[ "$(cutoffs "$tmp/raised")" = "50.6 0.0 1" ] || { echo "control: $(cutoffs "$tmp/raised")"; exit 1; }
[ "$(cutoffs "$tmp/refused")" = "40.5 50.6 0" ] || { echo "refused: $(cutoffs "$tmp/refused")"; exit 1; }
grep -q "modal at 50.6 Hz (its modes computed unless cached) ... not raised: 294 vectors" \
  "$tmp/refused.log" || { echo "no refusal line"; cat "$tmp/refused.log"; exit 1; }
grep -q "modal cut-off raised 0 time(s), to 40.5 Hz: its raise to 50.6 Hz would not fit in this machine's memory" \
  "$tmp/refused.log" || { echo "no estimate line"; cat "$tmp/refused.log"; exit 1; }
# The cut-off the machine's memory chose is not cached for another machine.
ls "$tmp/cache-raised"/accuracy-pilot-*.json > /dev/null || { echo "control: no pilot cached"; exit 1; }
! ls "$tmp/cache-refused"/accuracy-pilot-*.json > /dev/null 2>&1 ||
  { echo "a pilot whose raise was refused was cached"; exit 1; }
echo "ok   the pilot's raise to 50.6 Hz refused: the run takes 40.5 Hz (50.6 Hz without the refusal), not cached"

# 3. The raise without the first cut-off's rows in the cache.
grep -q "^      [0-9]* modes computed, the [0-9]* below 40.5 Hz kept from the last$" \
  "$tmp/raised.log" || { echo "control: the raise did not keep the modes below"; exit 1; }
# (The control's pilot took 50.6 Hz and removed its 40.5 Hz data, which
# those at 50.6 Hz serve: the same name but for the cut-off.)
taken=$(cd "$tmp/cache-raised" && ls modal-*-50.5625Hz.h5)
first=${taken%-50.5625Hz.h5}-40.45Hz.h5
[ ! -e "$tmp/cache-raised/$first" ] || { echo "control: the 40.5 Hz data left"; exit 1; }
mkdir -p "$tmp/cache-unwritable/$first"
"$PCSIM_BIN" run "$lumped" --set catenary.model=modal -pcsim_accuracy_pilot true \
  -o "$tmp/again" --cache "$tmp/cache-unwritable" --no-report > "$tmp/again.log" 2>&1 ||
  { cat "$tmp/again.log"; exit 1; }
grep -q "^      [0-9]* modes computed, those below 40.5 Hz again: their rows are not in the cache file this process wrote" \
  "$tmp/again.log" || { echo "no line on the modes computed again"; cat "$tmp/again.log"; exit 1; }
[ "$(cutoffs "$tmp/again")" = "50.6 0.0 1" ] || { echo "again: $(cutoffs "$tmp/again")"; exit 1; }
/usr/bin/python3 - "$tmp/raised" "$tmp/again" <<'PY'
import sys
import h5py
import numpy as np
a, b = (h5py.File(d + "/results.h5", "r")["pantographs/lumped/contact_force"][:]
        for d in sys.argv[1:3])
rel = np.max(np.abs(a - b)) / np.max(np.abs(a))
print(f"ok   the raise without the first rows in the cache: every mode computed again, {rel:.1e} from the control")
assert rel <= 1e-9, rel
PY
echo "modal memory: ok"
