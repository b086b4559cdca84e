#!/bin/bash
# The installed package: `cmake --install` into a temporary prefix, then
#  - a consumer project (tests/package/consumer) finds it with find_package(pcsim),
#    links pcsim::all and reads a design with it;
#  - the same source builds with the flags of `pkg-config --cflags --libs pcsim`;
#  - the installed pcsim runs, finds its postproc scripts (share/pcsim/postproc) and
#    the EN 50318 ranges they read;
#  - the example scenes, study scripts, designs and pantograph models are installed
#    (share/pcsim/runs, share/pcsim/meshes; not meshes/bad, the error tests' inputs),
#    every installed scene passes `pcsim check` with the installed binary, from a
#    folder outside the source tree, and the installed EN 50318 scene runs.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
build=$(dirname "$PCSIM_BIN")
prefix=$tmp/prefix
design=$PCSIM_SOURCE_DIR/meshes/en50318-reference.yaml
cmake --install "$build" --prefix "$prefix" > "$tmp/install.log" || { cat "$tmp/install.log"; exit 1; }
cmake -S "$PCSIM_SOURCE_DIR/tests/package/consumer" -B "$tmp/consumer" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" > "$tmp/configure.log" 2>&1 || { cat "$tmp/configure.log"; exit 1; }
cmake --build "$tmp/consumer" > "$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; exit 1; }
out=$("$tmp/consumer/consumer" "$design")
version=$(sed -n 's/^project(pcsim VERSION \([0-9.]*\).*/\1/p' "$PCSIM_SOURCE_DIR/CMakeLists.txt")
[[ "$out" =~ ^pcsim\ $version:\ design\ en50318-reference,\ [0-9]+\ nodes,\ 10\ spans$ ]] ||
  { echo "consumer: $out"; exit 1; }

export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
flags=$(pkg-config --cflags --libs pcsim)
mpicxx -std=c++17 "$PCSIM_SOURCE_DIR/tests/package/consumer/consumer.cpp" -o "$tmp/consumer-pc" $flags ||
  { echo "pkg-config flags: $flags"; exit 1; }
[ "$("$tmp/consumer-pc" "$design")" = "$out" ] || exit 1

cd "$tmp"
"$prefix/bin/pcsim" --version | grep -q "^pcsim $version "
"$prefix/bin/pcsim" run "$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml" -o run \
  -ts_max_steps 2 > run.log 2>&1 || { cat run.log; exit 1; }
grep -q "report: report.html" run.log || { cat run.log; exit 1; }  # postproc found
"$PCSIM_PYTHON" "$prefix/share/pcsim/postproc/interaction_table.py" --help > /dev/null

# The example scenes, designs and models, with their relative paths intact.
share=$prefix/share/pcsim
for f in runs/en50318-300.yaml runs/en50318-static.yaml runs/en50318-300-modal.yaml \
         runs/interaction/two-pantographs-300.yaml runs/interaction/en50318-250.yaml \
         runs/pantograph/force-step.csv runs/bench/table.py \
         meshes/en50318-reference.yaml meshes/en50318-ranges.json \
         meshes/pantographs/en50318_two_mass.yaml meshes/pantographs/dsa380_rigid.yaml \
         meshes/pantographs/dsa380_flexible.yaml meshes/lines/stitched.yaml \
         meshes/lines/profiles/measured-dz.csv; do
  [ -f "$share/$f" ] || { echo "not installed: share/pcsim/$f"; exit 1; }
done
for f in runs/interaction/run_studies.sh runs/bench_interaction.sh runs/lines/elasticity.sh; do
  [ -x "$share/$f" ] || { echo "not installed as an executable: share/pcsim/$f"; exit 1; }
done
[ ! -e "$share/meshes/bad" ] || { echo "share/pcsim/meshes/bad installed"; exit 1; }
# Every source scene and design is installed.
(cd "$PCSIM_SOURCE_DIR" && find runs meshes -name '*.yaml' -not -path 'meshes/bad/*') | sort > sources.txt
(cd "$share" && find runs meshes -name '*.yaml') | sort > installed.txt
diff sources.txt installed.txt || { echo "installed scenes and designs differ from the sources"; exit 1; }

# Every installed run, static/modes and pantograph scene passes `pcsim check` with the
# installed binary (relative paths resolved inside share/pcsim, not the source tree).
mkdir -p elsewhere && cd elsewhere
checked=0
while read -r scene; do
  grep -qE '^(name|base):' "$share/$scene" || continue  # designs and models
  grep -qE '^(type|kind|title):' "$share/$scene" && continue  # title: a criteria set
  "$prefix/bin/pcsim" check "$share/$scene" -o "check-$checked" > check.log 2>&1 ||
    { echo "pcsim check $scene (installed):"; cat check.log; exit 1; }
  grep -q "the command would start" check.log || { echo "check $scene:"; cat check.log; exit 1; }
  checked=$((checked + 1))
done < ../installed.txt
[ "$checked" -ge 50 ] || { echo "only $checked installed scenes checked"; exit 1; }
# The installed EN 50318 scene runs (a few steps).
"$prefix/bin/pcsim" run "$share/runs/en50318-300.yaml" -o en50318-300 -ts_max_steps 5 \
  --no-report > run.log 2>&1 || { cat run.log; exit 1; }
"$PCSIM_PYTHON" - "$share" en50318-300/summary.json <<'EOF'
import json, os, sys
share, summary = sys.argv[1], sys.argv[2]
inputs = {i["role"]: os.path.realpath(i["path"])
          for i in json.load(open(summary))["provenance"]["inputs"]}
for role, want in [("catenary.design", "meshes/en50318-reference.yaml"),
                   ("pantographs[0].model", "meshes/pantographs/en50318_two_mass.yaml")]:
    if inputs.get(role) != os.path.realpath(os.path.join(share, want)):
        sys.exit(f"the installed scene read {role} from {inputs.get(role)}, not share/pcsim/{want}")
EOF
echo "ok: $out; $checked installed scenes checked"
