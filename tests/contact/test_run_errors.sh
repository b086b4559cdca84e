#!/bin/bash
# Bad input for `pcsim run`: each case must fail with exit code != 0, print one
# error line naming the file and the key (or the missing file), and leave no
# output folder (neither DIR nor DIR.partial).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data=$PCSIM_SOURCE_DIR/tests/contact/data
model=$PCSIM_SOURCE_DIR/meshes/pantographs/en50318_two_mass.yaml

# scene NAME MODEL START_X SPEED_KMH [EXTRA PANTOGRAPH LINE]
scene() {
  cat > "$tmp/$1.yaml" <<YAML
name: $1
catenary: {design: $data/three-span.yaml}
pantographs:
  - name: p
    model: $2
    start_x: $3
${5:-}
simulation: {speed_kmh: $4, end_x: 80}
analysis: {from_span: 2, to_span: 2}
YAML
}

# expect_failure NAME PATTERN...: runs the scene NAME, checks the failure.
expect_failure() {
  local name=$1
  shift
  local status=0
  "$PCSIM_BIN" run "$tmp/$name.yaml" -o "$tmp/out-$name" > "$tmp/$name.out" 2> "$tmp/$name.err" ||
    status=$?
  if [ "$status" -eq 0 ]; then
    echo "FAIL $name: exit code 0"; exit 1
  fi
  if [ "$(grep -c . "$tmp/$name.err")" -ne 1 ]; then
    echo "FAIL $name: expected one error line, got:"; cat "$tmp/$name.err"; exit 1
  fi
  for pattern in "$@"; do
    if ! grep -qF -- "$pattern" "$tmp/$name.err"; then
      echo "FAIL $name: message lacks '$pattern':"; cat "$tmp/$name.err"; exit 1
    fi
  done
  if [ -e "$tmp/out-$name" ] || [ -e "$tmp/out-$name.partial" ]; then
    echo "FAIL $name: an output folder was left"; exit 1
  fi
  echo "ok $name (exit $status): $(cat "$tmp/$name.err")"
}

# A good scene runs (so that the failures below are due to the one change each).
scene good "$model" 13.1 200
"$PCSIM_BIN" run "$tmp/good.yaml" -o "$tmp/out-good" -ts_max_steps 2 > /dev/null
test -f "$tmp/out-good/results.h5"

# Contact-wire wave speed sqrt(20000 / 1.35) = 121.7 m/s = 438 km/h.
scene too_fast "$model" 13.1 500
expect_failure too_fast "$tmp/too_fast.yaml" "key 'simulation.speed_kmh'" "wave speed"

scene unknown_key "$model" 13.1 200 "    stiffnes: 3"
expect_failure unknown_key "$tmp/unknown_key.yaml" "key 'pantographs[0].stiffnes'" "unknown key"

scene before_line "$model" -10 200
expect_failure before_line "$tmp/before_line.yaml" "key 'pantographs[0].start_x'" "got -10"

scene after_end "$model" 95 200
expect_failure after_end "$tmp/after_end.yaml" "key 'pantographs[0].start_x'" "got 95"

scene missing_model "$tmp/no-such-pantograph.yaml" 13.1 200
expect_failure missing_model "$tmp/no-such-pantograph.yaml" "cannot open"
