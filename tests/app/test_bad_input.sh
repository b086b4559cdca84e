#!/bin/bash
# Table-driven bad-input test (issue 8): every case runs the real command and
# `pcsim check` with the same arguments and asserts
#  - the exit code (2 for bad input; 0 for the accepted cases at the end),
#  - that the message names the file and the key (and the reason's gist),
#  - that no user file was touched (checksums of everything in the work folder),
#  - that nothing was left behind (no out/, -o folder, .partial or lock),
# in well under a second per case: every error is found before any solve (the
# few cases found by the static solve use designs of a few dozen DOFs).
# Then one case of each error class on 2 ranks under `timeout 60`.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
S=$PCSIM_SOURCE_DIR
w=$tmp/work # the user's folder: cases run here; nothing in it may change
mkdir -p "$w/foreign" "$w/adir"
echo "not pcsim's" > "$w/foreign/notes.txt"
echo "keep me" > "$w/keep.txt"
two_mass=$S/meshes/pantographs/en50318_two_mass.yaml
dsa=$S/meshes/pantographs/dsa380_rigid.yaml
three=$S/tests/contact/data/three-span.yaml
failures=0
cases=0

# shellcheck source=tests/app/bad_input_files.sh
source "$(dirname "$0")/bad_input_files.sh"

# Every entry's path and type, and each file's size, modification time and
# inode: a file pcsim wrote, replaced or removed changes it (a folder's time
# is left out: a run's own scratch file, made and removed, changes it). One
# find and one sort a case (with a checksum of every file it took 40 ms a
# case, a tenth of the test's time); the checksums are compared once, at the
# end.
snapshot() {
  (cd "$w" && find . \( -type d -printf '%p %y\n' \) -o -printf '%p %y %s %T@ %i\n' | LC_ALL=C sort)
}
checksums() { (cd "$w" && find . -type f -print0 | LC_ALL=C sort -z | xargs -0 md5sum); }
before=$(snapshot)
before_sums=$(checksums)
# Milliseconds since the epoch, without starting a program (bash's EPOCHREALTIME, its
# decimal point the locale's).
now_ms() { local t=${EPOCHREALTIME//[!0-9]/}; echo $((t / 1000)); }

# expect NAME CODE "NEEDLE|NEEDLE..." CHECK(yes|no) COMMAND ARGS...
# CHECK=yes: `pcsim check` with the same arguments must give the same code and
# message (no: the error is found by the solve, which check does not run).
expect() {
  local name=$1 code=$2 needles=$3 also_check=$4 command=$5
  shift 5
  local runs=("$command")
  [ "$also_check" = yes ] && [ "$command" != check ] && runs+=(check)
  local cmd
  for cmd in "${runs[@]}"; do
    cases=$((cases + 1))
    local status=0 problems=() start end line
    start=$(now_ms)
    (cd "$w" && "$PCSIM_BIN" "$cmd" "$@" > "$tmp/out.txt" 2> "$tmp/err.txt") || status=$?
    end=$(now_ms)
    local err lines=0 first=""
    err=$(< "$tmp/err.txt")
    # One pass over its lines: the error messages, and the first pcsim line.
    while IFS= read -r line; do
      [[ $line == "pcsim: error"* ]] && lines=$((lines + 1))
      [[ -z $first && $line == pcsim* ]] && first=${line:0:150}
    done <<< "$err"
    [ "$status" -eq "$code" ] || problems+=("exit $status instead of $code")
    local needle
    IFS='|' read -r -a list <<< "$needles"
    for needle in "${list[@]}"; do
      [[ $err == *"$needle"* ]] || problems+=("stderr lacks '$needle'")
    done
    if [ "$code" -ne 0 ]; then
      [ "$lines" -eq 1 ] || problems+=("$lines error messages instead of 1")
    fi
    # Accepted runs of the real command write their results: remove them
    # (pcsim's own folder) before comparing the work folder.
    [ "$code" -eq 0 ] && [ "$cmd" != check ] && rm -rf "$w/out"
    [ "$(snapshot)" = "$before" ] || problems+=("the work folder changed: $(diff <(echo "$before") <(snapshot) | grep '^[<>]' | head -3 | tr '\n' ' ' || true)")
    if [ ${#problems[@]} -gt 0 ]; then
      echo "FAIL $name ($cmd): $(IFS=';'; echo "${problems[*]}")" >&2
      sed 's/^/    /' "$tmp/err.txt" >&2
      failures=$((failures + 1))
    else
      printf 'ok   %-16s %-10s %4d ms: %s\n' "$name" "$cmd" $((end - start)) "$first"
    fi
  done
}

# ---- the files of meshes/bad/ (checked as designs) ----
expect bad/bar-same-node 2 "meshes/bad/bar-same-node.yaml|key 'bars[0].nodes'|to itself" no \
  check "$S/meshes/bad/bar-same-node.yaml"
expect bad/dropper 2 "meshes/bad/dropper-outside-span.yaml|key 'droppers.positions[3]'|outside the span" no \
  check "$S/meshes/bad/dropper-outside-span.yaml"
expect bad/tension 2 "meshes/bad/negative-tension.yaml|key 'wires.contact.tension'|must be positive" no \
  check "$S/meshes/bad/negative-tension.yaml"
expect bad/node-range 2 "meshes/bad/node-out-of-range.yaml|key 'bars[0].nodes[1]'|out of range" no \
  check "$S/meshes/bad/node-out-of-range.yaml"
expect bad/unknown-key 2 "meshes/bad/unknown-key.yaml|key 'droppers.stiffnes'|unknown key" no \
  check "$S/meshes/bad/unknown-key.yaml"
[ "$(ls "$S"/meshes/bad/*.yaml | wc -l)" -eq 5 ] || { echo "FAIL: meshes/bad/ has new files: add them here" >&2; failures=$((failures + 1)); }

# ---- scenes, designs, output folders (static, modes) ----
expect missing-scene 2 "no-such-scene.yaml|cannot open|no such file" yes static no-such-scene.yaml
expect unknown-section 2 "unknown-section.yaml|key 'modez'|unknown key" yes static unknown-section.yaml
expect wrong-type 2 "wrong-type.yaml|key 'modes.count'|integer" yes modes wrong-type.yaml
expect zero-modes 2 "zero-modes.yaml|key 'modes.count'|at least 1" yes modes zero-modes.yaml
expect negative-mass 2 "negative-mass-design.yaml|key 'wires.contact.mass_per_length'|must be positive" yes \
  static negative-mass.yaml
expect design-dir 2 "design-dir.yaml|key 'catenary.design'|is a folder" yes static design-dir.yaml
expect missing-design 2 "missing-design.yaml|key 'catenary.design'|no such file" yes static missing-design.yaml
expect bad-design-key 2 "meshes/bad/unknown-key.yaml|key 'droppers.stiffnes'" yes modes bad-design-key.yaml
expect scene-name 2 "bad-name.yaml|key 'name'|must not be '..'" yes static bad-name.yaml
expect out-dot 2 "command line|key '-o'|working directory" yes static good-static.yaml -o .
expect out-foreign 2 "command line|key '-o'|not written by pcsim" yes static good-static.yaml -o foreign
expect huge 2 "huge-design.yaml|key 'spans.count'|too large for this machine|/proc/meminfo" yes static huge.yaml
expect huge-run 2 "huge-design.yaml|key 'spans.count'|too large for this machine" yes run huge-run.yaml
expect huge-set 2 "command line --set catenary.design.spans.count=100000|key 'spans.count'|too large" yes \
  static reference-static.yaml --set catenary.design.spans.count=100000
expect huge-design-set 2 "command line --set spans.count=100000|key 'spans.count'|too large" no \
  check "$S/meshes/en50318-reference.yaml" --set spans.count=100000
expect long-wire 2 "long-wire-design.yaml|key 'wires[0].nodes.elements'|too large" yes static long-wire.yaml
expect eps-nev-0 2 "command line|key '-eps_nev'|from 1" yes modes modes-scene.yaml -eps_nev 0
expect eps-nev-abc 2 "command line|key '-eps_nev'|integer" yes modes modes-scene.yaml -eps_nev abc
expect modes-fmax 2 "command line|key '-modes_fmax'|>= 0" yes modes modes-scene.yaml -modes_fmax -1
# The slices of the modes' interval computed at once: 1 to the ranks (solvers/spectrum.hpp).
expect modes-slices 2 "command line|key '-eps_krylovschur_partitions'|integer" yes \
  modes modes-scene.yaml -modes_fmax 3 -eps_krylovschur_partitions abc
expect modal-slices 2 "command line|key '-modal_eps_krylovschur_partitions'|from 1 to the number of ranks, 1 (got 2)" yes \
  run good-run.yaml --set catenary.model=modal -modal_eps_krylovschur_partitions 2
expect check-as 2 "command line|key '--as'|static, modes, run or pantograph" no check good-static.yaml --as nonsense
expect check-as-run 2 "good-static.yaml|key 'simulation'|missing" no check good-static.yaml --as run

# ---- run scenes ----
expect twins 2 "twins.yaml|key 'pantographs[1].name'|already used" yes run twins.yaml
expect past-end 2 "past-end.yaml|key 'pantographs[1].start_x'|past the end of the contact wire" yes run past-end.yaml
expect before-line 2 "before-line.yaml|key 'pantographs[0].start_x'|got -10" yes run before-line.yaml
expect end-beyond 2 "end-beyond.yaml|key 'simulation.end_x'|on the line" yes run end-beyond.yaml
expect window-size 2 "window-size.yaml|key 'window'|4 spans|not shorter than the line (3 spans)" yes run window-size.yaml
expect window-behind 2 "window-behind.yaml|key 'window.spans_behind'|at least 1" yes run window-behind.yaml
expect window-typo 2 "window-typo.yaml|key 'window.spans_ahed'|unknown key" yes run window-typo.yaml
expect window-train 2 "window-train.yaml|key 'window'|a window of 11 spans (spans_behind + 4 spans of the train|not shorter than the line (10 spans)" yes run window-train.yaml
expect window-droppers 2 "window-droppers.yaml|key 'window'|needs a line of identical spans|droppers.spans" yes run window-droppers.yaml
expect window-energy 2 "window-energy.yaml|key 'output.energy'|moving window" yes run window-energy.yaml
# A window asked for by the modal method (no 'window' section): the method's key
# is named, not a 'window' key the scene does not have.
expect method-window-reach 2 "command line --set catenary.modal.method=window|key 'catenary.modal.method'|window: the window's front reaches the line's end|default margins" \
  yes run "$S/runs/interaction/two-pantographs-300.yaml" --set catenary.model=modal --set catenary.modal.method=window
expect method-window-sections 2 "command line --set catenary.modal.method=window|key 'catenary.modal.method'|window: needs a line of identical spans" \
  yes run "$S/runs/lines/three-sections-300.yaml" --set catenary.model=modal --set catenary.modal.method=window
expect too-fast 2 "too-fast.yaml|key 'simulation.speed_kmh'|wave speed" yes run too-fast.yaml
expect panto-key 2 "panto-key.yaml|key 'pantographs[0].stiffnes'|unknown key" yes run panto-key.yaml
expect missing-model 2 "missing-model.yaml|key 'pantographs[0].model'|no such file" yes run missing-model.yaml
expect model-dir 2 "model-dir.yaml|key 'pantographs[0].model'|is a folder" yes run model-dir.yaml
expect negative-panto 2 "negative-panto-model.yaml|key 'stages[0].mass'|positive" yes run negative-panto.yaml
expect model-file 2 "negative-panto-model.yaml|key 'stages[0].mass'|positive" no check negative-panto-model.yaml
expect cutoff 2 "cutoff.yaml|key 'analysis.cutoff_hz'|Nyquist frequency 500 Hz" yes run cutoff.yaml
expect dt-one 2 "dt-one.yaml|key 'analysis.cutoff_hz'|Nyquist|simulation.dt = 1 s" yes run dt-one.yaml
expect few-samples 2 "few-samples.yaml|key 'simulation.dt'|filter needs more than 15" yes run few-samples.yaml
expect spans 2 "spans.yaml|key 'analysis'|to_span" yes run spans.yaml
expect gap 2 "gap.yaml|key 'pantographs[0].start.gap'|at most 0.5 m" yes run gap.yaml
expect hht-scene 2 "hht-scene.yaml|key 'simulation.hht_alpha'|[0, 1/3]" yes run hht-scene.yaml
expect set-dt 2 "command line --set simulation.dt=0.5|key 'simulation.dt'|filter needs more than 15" yes \
  run good-run.yaml --set simulation.dt=0.5 --set analysis.cutoff_hz=0.5
expect dsa-high 2 "dsa-high.yaml|key 'pantographs[0].working_height'|cannot be assembled at frame angle|working height 3 m" \
  yes run dsa-high.yaml
expect study-high 2 "study-high.yaml|key 'equilibrium.working_height'|working height 3.5 m" yes \
  pantograph study-high.yaml

# ---- issue 22: strict YAML, pantograph names, bounds, the keys messages name ----
expect dup-key 2 "dup-key.yaml|key 'simulation.dt'|duplicate key" yes run dup-key.yaml
expect dup-design 2 "dup-design.yaml|key 'element_length'|duplicate key" yes check dup-design.yaml
expect dup-model 2 "dup-model.yaml|key 'stages[0].mass'|duplicate key" yes run dup-panto.yaml
expect two-docs 2 "two-docs.yaml|more than one YAML document" yes run two-docs.yaml
expect empty-dt 2 "empty-dt.yaml|key 'simulation.dt'|has no value" yes run empty-dt.yaml
expect empty-model 2 "empty-model.yaml|key 'stages[0].damping'|has no value" yes run empty-panto.yaml
expect set-empty 2 "command line --set simulation.dt=~|key 'simulation.dt'|has no value" yes \
  run good-run.yaml --set simulation.dt=~
# issue 21: droppers near the pantographs exact (a distance; not with bars: exact)
expect near-negative 2 "command line --set catenary.modal.exact_droppers_within=-5|key 'catenary.modal.exact_droppers_within'|must not be negative" yes \
  run good-run.yaml --set catenary.model=modal --set catenary.modal.exact_droppers_within=-5
expect near-exact 2 "key 'catenary.modal.exact_droppers_within'|bars: exact already takes every bar's exact force" yes \
  run good-run.yaml --set catenary.model=modal --set catenary.modal.bars=exact \
  --set catenary.modal.exact_droppers_within=5
# ---- issue 25: conditions ----
expect ice-negative 2 "command line --set conditions.ice.contact=-0.5|key 'conditions.ice.contact'|must not be negative" yes \
  run good-run.yaml --set conditions.ice.contact=-0.5
expect ice-stitch 2 "command line --set conditions.ice.stitch=0.5|key 'conditions.ice.stitch'|the design has no stitch wire" yes \
  run good-run.yaml --set conditions.ice.stitch=0.5
expect ice-key 2 "command line --set conditions.ice.dropper=0.5|key 'conditions.ice.dropper'|unknown key" yes \
  run good-run.yaml --set conditions.ice.dropper=0.5
# issue 25: wind (docs/conditions.md "Wind")
expect wind-negative 2 "command line --set conditions.wind.speed=-10|key 'conditions.wind.speed'|must not be negative" yes \
  run good-run.yaml --set conditions.wind.speed=-10
expect wind-key 2 "command line --set conditions.wind.gust=30|key 'conditions.wind.gust'|unknown key" yes \
  run good-run.yaml --set conditions.wind.gust=30
expect wind-type 2 "command line --set conditions.wind.speed=strong|key 'conditions.wind.speed'|number" yes \
  run good-run.yaml --set conditions.wind.speed=strong
expect wind-width 2 "command line --set conditions.wind|key 'conditions.wind'|must be positive" yes \
  run good-run.yaml --set "conditions.wind={speed: 20, working_half_width: 0.3, vehicle_sway: 0.2, track_tolerance: 0.1}"
expect wind-terrain 2 "command line --set conditions.wind.terrain_category=V|key 'conditions.wind.terrain_category'|must be one of" yes \
  run good-run.yaml --set "conditions.wind={speed: 20, turbulence: {}}" --set conditions.wind.terrain_category=V
expect wind-both 2 "command line --set conditions.wind|key 'conditions.wind'|needs exactly one of 'speed'" yes \
  run good-run.yaml --set "conditions.wind={speed: 20, basic_speed: 25}"
cw="pantographs[0].cross_wind"
expect cross-wind-missing 2 "command line --set $cw|key '$cw.lateral_stiffness'|missing" yes \
  run good-run.yaml --set "$cw={drag_area: 0.5}"
expect cross-wind-negative 2 "command line --set $cw|key '$cw.drag_area'|must be positive" yes \
  run good-run.yaml --set "$cw={drag_area: -0.5, lateral_stiffness: 5e4}"
# issue 25: the pantograph's base motion (docs/conditions.md "Vehicle excitation")
base="pantographs[0].base_motion"
expect base-key 2 "command line --set $base|key '$base.phase'|unknown key" yes \
  run good-run.yaml --set "$base={type: harmonic, amplitude: 0.002, frequency_hz: 5, phase: 1}"
expect base-negative 2 "command line --set $base|key '$base.amplitude'|must be positive" yes \
  run good-run.yaml --set "$base={type: harmonic, amplitude: -0.002, frequency_hz: 5}"
expect base-file 2 "command line --set $base|key '$base.file'|no such file" yes \
  run good-run.yaml --set "$base={type: file, file: no-such-roof.csv}"
expect base-dsa 2 "dsa-base.yaml|key '$base.interpolation'|'linear' is not available for a moving-frame" yes \
  run dsa-base.yaml
expect base-dsa-file 2 "dsa-base-file.yaml|key '$base.interpolation'|needs the base's acceleration" yes \
  run dsa-base-file.yaml
expect base-interpolation 2 "command line --set $base|key '$base.interpolation'|spline" yes \
  run good-run.yaml --set "$base={type: file, file: $S/runs/conditions/roof.csv, interpolation: spline}"
expect name-slash 2 "name-slash.yaml|key 'pantographs[1].name'|must not contain '/'" yes run name-slash.yaml
expect name-abs 2 "name-abs.yaml|key 'pantographs[1].name'|must not contain '/'" yes run name-abs.yaml
expect name-dot 2 "name-dot.yaml|key 'pantographs[0].name'|must not be '.'" yes run name-dot.yaml
expect name-empty 2 "name-empty.yaml|key 'pantographs[0].name'|must not be empty" yes run name-empty.yaml
expect tension 2 "tension-design.yaml|key 'wires.contact.tension'|at most" yes static tension.yaml
expect ei 2 "ei-design.yaml|key 'wires.contact.EI'|at most" yes modes ei.yaml
expect tiny-element 2 "tiny-element-design.yaml|key 'element_length'|at least 0.0001 m" yes static tiny-element.yaml
expect fine 2 "fine-design.yaml|key 'element_length'|too large for this machine" yes static fine.yaml
expect alpha 2 "alpha-design.yaml|key 'damping.rayleigh_alpha'|at most" yes static alpha.yaml
expect beta 2 "beta-design.yaml|key 'damping.rayleigh_beta'|at most" yes static beta.yaml
expect big-force 2 "big-force.yaml|key 'pantographs[0].static_force'|at most" yes run big-force.yaml
expect tiny-cutoff 2 "tiny-cutoff.yaml|key 'analysis.cutoff_hz'|at least 0.001 Hz" yes run tiny-cutoff.yaml
expect tiny-dt 2 "tiny-dt.yaml|key 'simulation.dt'|at least" yes run tiny-dt.yaml
expect huge-dt 2 "huge-dt.yaml|key 'simulation.dt'|at most 1 s" yes run huge-dt.yaml
expect heavy 2 "heavy-model.yaml|key 'stages[0].mass'|at most" yes run heavy.yaml
expect damped 2 "damped-model.yaml|key 'stages[1].damping'|at most" yes run damped.yaml
expect long-l1 2 "long-l1-model.yaml|key 'geometry.L1'|cannot be assembled at any frame angle" yes run long-l1.yaml

# ---- command-line numerics of a run ----
expect ts-dt-0 2 "command line|key '-ts_dt'|positive" yes run good-run.yaml -ts_dt 0
expect ts-dt-neg 2 "command line|key '-ts_dt'|positive" yes run good-run.yaml -ts_dt -1e-3
expect ts-dt-abc 2 "command line|key '-ts_dt'|must be a number (got 'abc')" yes run good-run.yaml -ts_dt abc
expect ts-dt-inf 2 "command line|key '-ts_dt'|finite" yes run good-run.yaml -ts_dt inf
expect ts-dt-nyquist 2 "good-run.yaml|key 'analysis.cutoff_hz'|-ts_dt = 0.05 s" yes run good-run.yaml -ts_dt 0.05
expect hht-alpha 2 "command line|key '-ts_hht_alpha'|[0, 1/3]" yes run good-run.yaml -ts_hht_alpha 0.9
expect ts-max-time-abc 2 "command line|key '-ts_max_time'|must be a number (got 'abc')" yes run good-run.yaml -ts_max_time abc
expect ts-max-time-0 2 "command line|key '-ts_max_time'|positive" yes run good-run.yaml -ts_max_time 0
# Past the scene's end the pantograph would run off the line (a solver failure).
expect ts-max-time-past 2 "command line|key '-ts_max_time'|past the scene's end|simulation.end_x" yes run good-run.yaml -ts_max_time 1e6
expect ts-max-steps-abc 2 "command line|key '-ts_max_steps'|must be an integer (got '2.5')" yes run good-run.yaml -ts_max_steps 2.5
expect ts-max-steps-neg 2 "command line|key '-ts_max_steps'|1 or more" yes run good-run.yaml -ts_max_steps -1
# No step: nothing to write (it failed after the static solve, exit 3).
expect ts-max-steps-0 2 "command line|key '-ts_max_steps'|1 or more" yes run good-run.yaml -ts_max_steps 0
expect ts-euler 2 "command line|key '-ts_type'|second order" yes run good-run.yaml -ts_type euler
expect ts-unknown 2 "command line|key '-ts_type'|unknown" yes run good-run.yaml -ts_type nonsense
expect path-bad 2 "command line|key '-pcsim_path'|auto, full or cheap" yes run good-run.yaml -pcsim_path fast
expect path-cheap 2 "command line|key '-pcsim_path'|cheap path needs" yes run dsa-cheap.yaml -pcsim_path cheap
expect record-batches 2 "command line|key '-pcsim_record_batches'|not auto, true or false" yes run good-run.yaml -pcsim_record_batches sometimes
expect record-thread 2 "command line|key '-pcsim_record_thread'|not auto, true or false" yes run good-run.yaml -pcsim_record_thread sometimes
expect step-cpu-word 2 "command line|key '-pcsim_step_cpu'|'first' is not a CPU number" yes run good-run.yaml -pcsim_step_cpu first
expect step-cpu-absent 2 "command line|key '-pcsim_step_cpu'|CPU 4096 is not one this process may run on" yes run good-run.yaml -pcsim_step_cpu 4096

# ---- found by the static solve (pcsim check solves nothing) ----
expect hanging 2 "hanging-design.yaml|key 'wires'|form-finding found no tension distribution|wire 'hanger'" no \
  static hanging.yaml

# ---- accepted: warnings name the file and key, or the elements ----
expect close 0 "pcsim: warning: close.yaml|key 'pantographs[1].start_x'|5 m from 'p'" no check close.yaml
expect crawl 0 "pcsim: warning: crawl.yaml|key 'simulation'|time steps" no check crawl.yaml
expect slack-wire 0 "pcsim: warning: elements in compression|wire 'wire', cable elements: 10|negative eigenvalue" no \
  static slack-wire.yaml
expect stiff 0 "" no static stiff.yaml
grep -q "stagnated at rounding\|CONVERGED_FNORM" "$tmp/out.txt" || { echo "FAIL stiff: no convergence note" >&2; failures=$((failures + 1)); }

# spans.count 100000 is refused before the mesh is built: the process's CPU
# time (user + system) must stay well under a second (building the mesh
# allocated for 9 s before std::bad_alloc). Wall time is printed only: on a
# loaded machine MPI's start-up waits for the scheduler.
TIMEFORMAT='%R %U %S'
times=$({ time (cd "$w" && "$PCSIM_BIN" static huge.yaml > /dev/null 2>&1 || true); } 2>&1)
read -r wall user sys <<< "$times"
cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f", u + s }')
echo "     spans.count 100000 refused: CPU $cpu s, wall $wall s"
awk -v c="$cpu" 'BEGIN { exit !(c < 0.5) }' || { echo "FAIL: spans.count 100000 took $cpu s of CPU" >&2; failures=$((failures + 1)); }

# pcsim check on large inputs (issue 22): 5000 pantographs (the spacing
# warnings compare neighbours in start order, one model file parsed once) and
# a scene of thousands of keys (composition indexes keys; no linear search
# per key). Each took more than 60 s; about 1 s now on an idle machine. The
# 10 s bound is only a sanity limit for a loaded machine (MPI start-up
# included): the point is the complexity, not the speed.
{
  echo "name: many"
  echo "catenary: {design: $three}"
  echo "pantographs:"
  awk -v m="$two_mass" 'BEGIN { for (i = 0; i < 5000; ++i) printf "  - {name: p%d, model: %s, start_x: %.4f}\n", i, m, 13.1 + 0.002 * i }'
  echo "simulation: {speed_kmh: 200, end_x: 80}"
  echo "analysis: {from_span: 2, to_span: 2}"
  echo "set:"
  awk 'BEGIN { for (i = 0; i < 5000; ++i) printf "  pantographs[%d].ramp_distance: 20\n", i }'
} > "$tmp/many.yaml"
{
  echo "name: keys"
  echo "catenary: {design: $three}"
  echo "pantographs: [{name: p, model: $two_mass, start_x: 13.1}]"
  echo "simulation: {speed_kmh: 200, end_x: 80}"
  echo "set:"
  awk 'BEGIN { for (i = 0; i < 5000; ++i) printf "  simulation.k%d: %d\n", i, i }'
  awk 'BEGIN { for (i = 0; i < 5000; ++i) printf "key%d: %d\n", i, i }'
} > "$tmp/keys.yaml"
for c in "many:0:5000 pantograph(s)" "keys:2:key 'key0'|unknown key"; do
  IFS=: read -r name code needle <<< "$c"
  cases=$((cases + 1))
  status=0
  start=$(now_ms)
  (cd "$w" && timeout 60 "$PCSIM_BIN" check "$tmp/$name.yaml" > "$tmp/out.txt" 2> "$tmp/err.txt") || status=$?
  ms=$(($(now_ms) - start))
  found=yes
  IFS='|' read -r -a list <<< "$needle"
  for n in "${list[@]}"; do grep -qF -- "$n" "$tmp/out.txt" "$tmp/err.txt" || found=no; done
  if [ "$status" -ne "$code" ] || [ "$found" = no ] || [ "$ms" -gt 10000 ]; then
    echo "FAIL large $name: exit $status (expected $code), '$needle' found: $found, $ms ms" >&2
    head -3 "$tmp/err.txt" >&2
    failures=$((failures + 1))
  else
    echo "ok   large input $name: pcsim check in $ms ms"
  fi
done

# ---- each error class on 2 ranks: same code, one message, nothing left ----
# Every rank ends with the agreed code (no MPI_Abort: checked), so Open MPI's
# wait before it kills the ranks of a job with a non-zero exit
# (odls_base_sigkill_timeout, 1 s) has nothing to wait for: 0 s here (a
# refusal took 1.31 s with the default and 0.30 s with 0, mpirun -n 2 pcsim
# check no-such.yaml, 2026-12-07; the exit code is the same).
export OMPI_MCA_odls_base_sigkill_timeout=0
# expect2 NAME NEEDLE COMMAND ARGS...
expect2() {
  local name=$1 needle=$2
  shift 2
  cases=$((cases + 1))
  local status=0 problems=()
  (cd "$w" && timeout 60 mpirun -n 2 "$PCSIM_BIN" "$@" > "$tmp/out.txt" 2> "$tmp/err.txt") || status=$?
  [ "$status" -eq 2 ] || problems+=("exit $status instead of 2")
  [ "$(grep -c "^pcsim: error" "$tmp/err.txt" || true)" -eq 1 ] || problems+=("not one message")
  grep -qF -- "$needle" "$tmp/err.txt" || problems+=("stderr lacks '$needle'")
  ! grep -q "other ranks did not stop" "$tmp/err.txt" || problems+=("MPI_Abort")
  [ "$(snapshot)" = "$before" ] || problems+=("the work folder changed")
  if [ ${#problems[@]} -gt 0 ]; then
    echo "FAIL 2 ranks $name: $(IFS=';'; echo "${problems[*]}")" >&2
    sed 's/^/    /' "$tmp/err.txt" >&2
    failures=$((failures + 1))
  else
    echo "ok   2 ranks $name: $(grep "^pcsim: error" "$tmp/err.txt" | cut -c1-120)"
  fi
}
expect2 design "key 'wires.contact.tension'" check "$S/meshes/bad/negative-tension.yaml"
expect2 scene "key 'pantographs[1].name'" run twins.yaml
expect2 positions "key 'pantographs[1].start_x'" run past-end.yaml
expect2 nyquist "key 'analysis.cutoff_hz'" run cutoff.yaml
expect2 memory "key 'spans.count'" static huge.yaml
expect2 numerics "key '-ts_dt'" run good-run.yaml -ts_dt abc
expect2 modes "key '-eps_nev'" modes modes-scene.yaml -eps_nev 0
expect2 slices "key '-modal_eps_krylovschur_partitions'" run good-run.yaml --set catenary.model=modal \
  -modal_eps_krylovschur_partitions 3
expect2 geometry "key 'pantographs[0].working_height'" run dsa-high.yaml
expect2 output "key '-o'" static good-static.yaml -o foreign
expect2 design-dir "key 'catenary.design'" static design-dir.yaml
expect2 form-finding "key 'wires'" static hanging.yaml
expect2 step-cpu "pins the stepping thread of a run of one rank; on 2 ranks" run good-run.yaml -pcsim_step_cpu 0

# A refused run's message is the last thing said: PETSc's summaries at
# finalisation (-log_view, -options_left) would follow it with a page on stdout.
cases=$((cases + 1))
status=0
(cd "$w" && timeout 60 mpirun -n 2 "$PCSIM_BIN" run good-run.yaml -ts_dt abc -log_view -options_left \
  > "$tmp/out.txt" 2> "$tmp/err.txt") || status=$?
if [ "$status" -ne 2 ] || [ -s "$tmp/out.txt" ] || [ "$(grep -c "^pcsim: error" "$tmp/err.txt" || true)" -ne 1 ]; then
  echo "FAIL 2 ranks -log_view: exit $status, $(wc -l < "$tmp/out.txt") line(s) on stdout" >&2
  head -3 "$tmp/out.txt" "$tmp/err.txt" >&2
  failures=$((failures + 1))
else
  echo "ok   2 ranks -log_view -options_left: nothing on stdout after the refusal"
fi

[ "$(checksums)" = "$before_sums" ] || { echo "FAIL: a file of the work folder changed (checksums)" >&2; failures=$((failures + 1)); }
echo "$cases runs, $failures failure(s)"
[ "$failures" -eq 0 ]
