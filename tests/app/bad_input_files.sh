# The inputs of test_bad_input.sh, written into its work folder "$w" (sourced
# by it: S, w, two_mass, dsa and three set there): designs, models and scenes
# that are each wrong in one way, and the good ones the accepted cases run.
# shellcheck shell=bash disable=SC2154  # S, w, two_mass, dsa, three: the test sets them

# ---- input files (tiny designs: three spans of 30 m, 1.5 m elements) ----
sed 's/mass_per_length: 1.35,/mass_per_length: -1.35,/' "$three" > "$w/negative-mass-design.yaml"
# The EN 50318 line with 100000 spans: 2.4e7 nodes, ~190 GB by the estimate.
sed 's/^spans: {count: 10, length: 60.0}/spans: {count: 100000, length: 60.0}/' \
  "$S/meshes/en50318-reference.yaml" > "$w/huge-design.yaml"
grep -q "mass_per_length: -1.35" "$w/negative-mass-design.yaml"
grep -q "count: 100000" "$w/huge-design.yaml"
cat > "$w/long-wire-design.yaml" << 'YAML'
type: explicit
nodes: [[0, 0, 0], [1.0e6, 0, 0]]
wires:
  - {name: w, nodes: {from: 0, to: 1, elements: 2000000000}, mass_per_length: 1, EA: 1.0e7, EI: 1, tension: 1000}
supports: [{node: 0}, {node: 1}]
YAML
# A straight wire pinned at both ends whose unstressed length is 4 % too long:
# it "converges" at once to a state under 3.6e7 N of compression (EA 1e9).
cat > "$w/slack-wire-design.yaml" << 'YAML'
type: explicit
gravity: 9.81
nodes: [[0, 0, 0], [10, 0, 0]]
wires:
  - {name: wire, nodes: {from: 0, to: 1, elements: 10}, mass_per_length: 1.35, EA: 1.0e9, EI: 195, tension: 1000, unstressed: 1.04}
supports: [{node: 0}, {node: 1}]
YAML
# A heavy vertical wire pinned at both ends: form-finding to a mean tension of
# 10 N leaves its lower half in compression.
cp "$S/tests/solvers/data/hanging-design.yaml" "$w/hanging-design.yaml"
# Two spans with EA 1e9: Newton's residual stalls at rounding (~1e-4 N).
sed 's/EA: 1.0e7/EA: 1.0e9/; s/EA: 1.44e7/EA: 1.0e9/' "$S/tests/catenary/data/two-span.yaml" > "$w/stiff-design.yaml"
grep -c "EA: 1.0e9" "$w/stiff-design.yaml" | grep -q 2
sed 's/mass: 7.2,/mass: -7.2,/' "$two_mass" > "$w/negative-panto-model.yaml"

# catenary_scene NAME DESIGN [EXTRA LINES]
catenary_scene() {
  printf 'name: %s\ncatenary: {design: %s}\n%s' "$1" "$2" "${3:-}" > "$w/$1.yaml"
}
# run_scene NAME PANTOGRAPH-LINES [SIMULATION EXTRA] [ANALYSIS EXTRA] [DESIGN]
run_scene() {
  cat > "$w/$1.yaml" << YAML
name: $1
catenary: {design: ${5:-$three}}
pantographs:
$2
simulation: {speed_kmh: 200, end_x: 80${3:-}}
analysis: {from_span: 2, to_span: 2${4:-}}
YAML
}
one="  - {name: p, model: $two_mass, start_x: 13.1}"

catenary_scene good-static "$three"
catenary_scene modes-scene "$three" $'modes: {count: 4}\n'
catenary_scene bad-name "$three"
printf 'name: ".."\ncatenary: {design: %s}\n' "$three" > "$w/bad-name.yaml"
catenary_scene unknown-section "$three" $'modez: {count: 3}\n'
catenary_scene wrong-type "$three" $'modes: {count: three}\n'
catenary_scene zero-modes "$three" $'modes: {count: 0}\n'
catenary_scene negative-mass "negative-mass-design.yaml"
catenary_scene design-dir "adir"
catenary_scene missing-design "no-such-design.yaml"
catenary_scene bad-design-key "$S/meshes/bad/unknown-key.yaml"
catenary_scene huge "huge-design.yaml"
catenary_scene long-wire "long-wire-design.yaml"
catenary_scene slack-wire "slack-wire-design.yaml"
catenary_scene hanging "hanging-design.yaml"
catenary_scene stiff "stiff-design.yaml"
run_scene good-run "$one"
run_scene twins "  - {name: p, model: $two_mass, start_x: 13.1}
  - {name: p, model: $two_mass, start_x: 3.1}"
run_scene past-end "  - {name: p, model: $two_mass, start_x: 13.1}
  - {name: q, model: $two_mass, start_x: 40}"
run_scene before-line "  - {name: p, model: $two_mass, start_x: -10}"
run_scene end-beyond "$one"
sed -i 's/end_x: 80/end_x: 200/' "$w/end-beyond.yaml"
run_scene too-fast "  - {name: p, model: $two_mass, start_x: 13.1}" "" "" "$three"
sed -i 's/speed_kmh: 200/speed_kmh: 500/' "$w/too-fast.yaml"
run_scene panto-key "  - {name: p, model: $two_mass, start_x: 13.1, stiffnes: 3}"
run_scene missing-model "  - {name: p, model: no-such-model.yaml, start_x: 13.1}"
run_scene model-dir "  - {name: p, model: adir, start_x: 13.1}"
run_scene negative-panto "  - {name: p, model: negative-panto-model.yaml, start_x: 13.1}"
run_scene cutoff "$one" "" ", cutoff_hz: 600"
run_scene dt-one "$one" ", dt: 1.0"
run_scene few-samples "$one" ", dt: 0.5" ", cutoff_hz: 0.5"
run_scene spans "$one" "" ", to_span: 7"
sed -i 's/from_span: 2, to_span: 2, to_span: 7/from_span: 2, to_span: 7/' "$w/spans.yaml"
run_scene dsa-high "  - {name: p, model: $dsa, start_x: 13.1, working_height: 3.0}"
run_scene dsa-cheap "  - {name: p, model: $dsa, start_x: 13.1}"
run_scene dsa-base "  - {name: p, model: $S/meshes/pantographs/dsa380_flexible.yaml, start_x: 13.1,
     base_motion: {type: file, file: $S/runs/conditions/roof.csv, interpolation: linear}}"
run_scene dsa-base-file "  - {name: p, model: $dsa, start_x: 13.1,
     base_motion: {type: file, file: $S/runs/conditions/roof.csv, interpolation: linear}}"
echo "effects: {catenary_nonlinear: true}" >> "$w/dsa-cheap.yaml"  # no cheap path
run_scene huge-run "$one" "" "" "huge-design.yaml"
run_scene close "  - {name: p, model: $two_mass, start_x: 13.1}
  - {name: q, model: $two_mass, start_x: 8.1}"
run_scene gap "  - {name: p, model: $two_mass, start_x: 13.1, start: {gap: 0.8}}"
run_scene hht-scene "$one" ", hht_alpha: 0.5"
catenary_scene reference-static "$S/meshes/en50318-reference.yaml"
run_scene crawl "$one"
sed -i 's/speed_kmh: 200/speed_kmh: 0.001/' "$w/crawl.yaml"
# Moving windows (scene key 'window', docs/scaling.md): the three-span line is
# shorter than any window; a span count below 1; a typo; an output the window
# cannot give (on the 10-span EN 50318 line, a 4-span window).
for c in "window-size:{spans_behind: 1, spans_ahead: 1}" "window-behind:{spans_behind: 0}" \
  "window-typo:{spans_ahed: 2}"; do
  run_scene "${c%%:*}" "$one"
  echo "window: ${c#*:}" >> "$w/${c%%:*}.yaml"
done
# A window on a line whose spans 3 and 4 have droppers of their own: it
# would carry them along with every shift (once accepted without a word).
cat > "$w/window-droppers.yaml" << YAML
name: window-droppers
catenary: {design: $S/meshes/lines/presag-heights.yaml}
set: {catenary.design.spans.count: 30}
pantographs: [{name: p, model: $two_mass, start_x: 5}]
simulation: {speed_kmh: 200, end_x: 200}
analysis: {from_span: 2, to_span: 3}
window: {spans_behind: 1, spans_ahead: 1}
YAML
cat > "$w/window-energy.yaml" << YAML
name: window-energy
catenary: {design: $S/meshes/en50318-reference.yaml}
pantographs: [{name: p, model: $two_mass, start_x: 5}]
simulation: {speed_kmh: 200, end_x: 200}
analysis: {from_span: 2, to_span: 3}
window: {spans_behind: 1, spans_ahead: 1}
output: {energy: true}
YAML
# A window over a train (issue 21): two pantographs 200 m apart on the
# 10-span line need 2 + 4 (the train) + 2 + 3 spans, not shorter than the line.
cat > "$w/window-train.yaml" << YAML
name: window-train
catenary: {design: $S/meshes/en50318-reference.yaml}
pantographs:
  - {name: leading, model: $two_mass, start_x: 205}
  - {name: trailing, model: $two_mass, start_x: 5}
simulation: {speed_kmh: 200, end_x: 520}
analysis: {from_span: 5, to_span: 5}
window: {spans_behind: 2, spans_ahead: 3}
YAML
# Issue 22 (a fuzzer's inputs): duplicate keys, a second document, empty
# values; pantograph names that are not one HDF5 link name; magnitudes no
# line or pantograph has; keys a message must name.
run_scene dup-key "$one" ", dt: 0.001, dt: 0.002"
sed 's/^element_length: .*/&\nelement_length: 1.0/' "$three" > "$w/dup-design.yaml"
sed 's/mass: 7.2, stiffness: 4200/mass: 7.2, mass: 3, stiffness: 4200/' "$two_mass" > "$w/dup-model.yaml"
run_scene dup-panto "  - {name: p, model: dup-model.yaml, start_x: 13.1}"
run_scene two-docs "$one"
printf -- '---\nname: other\n' >> "$w/two-docs.yaml"
run_scene empty-dt "$one"
sed -i 's/^simulation: {speed_kmh: 200, end_x: 80}/simulation:\n  speed_kmh: 200\n  end_x: 80\n  dt:/' "$w/empty-dt.yaml"
sed 's/damping: 10}/damping: }/' "$two_mass" > "$w/empty-model.yaml"
run_scene empty-panto "  - {name: p, model: empty-model.yaml, start_x: 13.1}"
run_scene name-slash "  - {name: a, model: $two_mass, start_x: 13.1}
  - {name: a/, model: $two_mass, start_x: 3.1}"
run_scene name-abs "  - {name: abs, model: $two_mass, start_x: 13.1}
  - {name: /abs, model: $two_mass, start_x: 3.1}"
run_scene name-dot "  - {name: ., model: $two_mass, start_x: 13.1}"
run_scene name-empty "  - {name: '', model: $two_mass, start_x: 13.1}"
sed 's/tension: 20000.0/tension: 1.0e300/' "$three" > "$w/tension-design.yaml"
sed 's/EI: 195.0/EI: 1.0e300/' "$three" > "$w/ei-design.yaml"
sed 's/^element_length: .*/element_length: 5.0e-19/' "$three" > "$w/tiny-element-design.yaml"
sed 's/^element_length: .*/element_length: 1.0e-4/' "$S/meshes/en50318-reference.yaml" > "$w/fine-design.yaml"
sed 's/rayleigh_alpha: 0.0125/rayleigh_alpha: 1.0e300/' "$three" > "$w/alpha-design.yaml"
sed 's/rayleigh_beta: 1.0e-4/rayleigh_beta: 1.0e300/' "$three" > "$w/beta-design.yaml"
grep -q "rayleigh_alpha: 1.0e300" "$w/alpha-design.yaml"
grep -q "rayleigh_beta: 1.0e300" "$w/beta-design.yaml"
grep -q "tension: 1.0e300" "$w/tension-design.yaml"
grep -q "EI: 1.0e300" "$w/ei-design.yaml"
grep -q "element_length: 5.0e-19" "$w/tiny-element-design.yaml"
grep -q "element_length: 1.0e-4" "$w/fine-design.yaml"
for d in tension ei tiny-element fine alpha beta; do catenary_scene "$d" "$d-design.yaml"; done
run_scene big-force "  - {name: p, model: $two_mass, start_x: 13.1, static_force: 18446744073709551616}"
run_scene tiny-cutoff "$one" "" ", cutoff_hz: 5.0e-324"
run_scene tiny-dt "$one" ", dt: 1.0e-300"
run_scene huge-dt "$one" ", dt: 1.0e10"
sed 's/mass: 7.2,/mass: 1.0e300,/' "$two_mass" > "$w/heavy-model.yaml"
sed 's/damping: 90}/damping: 1.0e300}/' "$two_mass" > "$w/damped-model.yaml"
sed 's/^\(  *\)L1: .*/\1L1: 50.0/' "$dsa" > "$w/long-l1-model.yaml"
grep -q "L1: 50.0" "$w/long-l1-model.yaml"
run_scene heavy "  - {name: p, model: heavy-model.yaml, start_x: 13.1}"
run_scene damped "  - {name: p, model: damped-model.yaml, start_x: 13.1}"
run_scene long-l1 "  - {name: p, model: long-l1-model.yaml, start_x: 13.1}"
cat > "$w/study-high.yaml" << YAML
name: study-high
pantograph: {model: $dsa}
equilibrium: {contact_force: 120, working_height: 3.5}
study: {type: modes}
YAML
