#!/bin/bash
# Bad input to `pcsim static` / `pcsim modes`: each case must fail with a
# non-zero exit code, print exactly ONE message on stderr that names the file,
# the key and the reason, and leave no result files (neither the output folder
# nor "<folder>.partial", nor a default out/ folder).
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
D=$PCSIM_SOURCE_DIR/tests/catenary/data
failures=0

# expect_error NAME COMMAND SCENE NEEDLE... : runs `pcsim COMMAND SCENE -o $tmp/NAME`
# in $tmp and checks the failure; every NEEDLE must occur in the stderr message.
expect_error() {
  local name=$1 command=$2 scene=$3
  shift 3
  local status=0
  (cd "$tmp" && "$PCSIM_BIN" "$command" "$scene" -o "$tmp/$name" \
      > "$tmp/$name.stdout" 2> "$tmp/$name.stderr") || status=$?
  local msg
  msg=$(cat "$tmp/$name.stderr")
  local problems=()
  [ "$status" -ne 0 ] || problems+=("exit code 0")
  local lines
  lines=$(grep -c . "$tmp/$name.stderr" || true)
  [ "$lines" -eq 1 ] || problems+=("$lines lines on stderr instead of 1")
  local needle
  for needle in "$@"; do
    grep -qF -- "$needle" "$tmp/$name.stderr" || problems+=("message lacks '$needle'")
  done
  [ ! -e "$tmp/$name" ] || problems+=("output folder $name was created")
  [ ! -e "$tmp/$name.partial" ] || problems+=("$name.partial was left behind")
  [ ! -e "$tmp/out" ] || problems+=("a default out/ folder was created")
  if [ ${#problems[@]} -gt 0 ]; then
    echo "FAIL $name (exit $status): $(IFS=';'; echo "${problems[*]}")" >&2
    echo "  stderr: $msg" >&2
    failures=$((failures + 1))
  else
    echo "ok   $name: $msg"
  fi
}

# Design errors, through a scene (file = the design, key = the key path in it).
# A missing design file: the message names the scene, the key 'catenary.design',
# the design file and the reason.
expect_error missing-design static "$D/bad-missing-design.yaml" \
  "bad-missing-design.yaml" "catenary.design" "no-such-design.yaml" "cannot open"
expect_error unknown-key static "$D/bad-unknown-key.yaml" \
  "meshes/bad/unknown-key.yaml" "droppers.stiffnes" "unknown key"
expect_error negative-tension static "$D/bad-negative-tension.yaml" \
  "meshes/bad/negative-tension.yaml" "wires.contact.tension" "must be positive"
expect_error dropper-outside-span modes "$D/bad-dropper-outside-span.yaml" \
  "meshes/bad/dropper-outside-span.yaml" "droppers.positions[3]" "outside the span"

# A design with a string where a number is expected.
sed 's/spans: {count: 2, length: 60.0}/spans: {count: 2, length: sixty}/' "$D/two-span.yaml" \
  > "$tmp/wrong-type-design.yaml"
grep -q "length: sixty" "$tmp/wrong-type-design.yaml"
printf 'name: wrong-type-design\ncatenary: {design: wrong-type-design.yaml}\n' > "$tmp/wrong-type-design-scene.yaml"
expect_error wrong-type-design static "$tmp/wrong-type-design-scene.yaml" \
  "wrong-type-design.yaml" "spans.length" "number"

# Scene errors (file = the scene).
expect_error unknown-section modes "$D/bad-scene-unknown-section.yaml" \
  "bad-scene-unknown-section.yaml" "modez" "unknown key"
expect_error wrong-type-scene modes "$D/bad-scene-wrong-type.yaml" \
  "bad-scene-wrong-type.yaml" "modes.count" "integer"
expect_error missing-scene static "$tmp/no-such-scene.yaml" \
  "no-such-scene.yaml" "cannot open"

# On 2 ranks the message is still printed once (by rank 0); mpirun's own
# report about the failed job is not pcsim's and is left out of the count.
status=0
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
  mpirun --oversubscribe -n 2 "$PCSIM_BIN" static "$D/bad-negative-tension.yaml" -o "$tmp/np2" \
  > "$tmp/np2.stdout" 2> "$tmp/np2.stderr" || status=$?
n=$(grep -c "^pcsim" "$tmp/np2.stderr" || true)
if [ "$status" -eq 0 ] || [ "$n" -ne 1 ] || [ -e "$tmp/np2" ] || [ -e "$tmp/np2.partial" ]; then
  echo "FAIL 2 ranks: exit $status, $n pcsim messages" >&2
  cat "$tmp/np2.stderr" >&2
  failures=$((failures + 1))
else
  echo "ok   2 ranks: one message"
fi

if [ "$failures" -ne 0 ]; then
  echo "$failures bad-input case(s) failed" >&2
  exit 1
fi
echo OK
