#!/bin/bash
# The installed package: `cmake --install` into a temporary prefix, then
#  - a consumer project (tests/package/consumer) finds it with find_package(pcsim),
#    links pcsim::all and reads a design with it;
#  - the same source builds with the flags of `pkg-config --cflags --libs pcsim`;
#  - the installed pcsim runs, finds its postproc scripts (share/pcsim/postproc) and
#    the EN 50318 ranges they read.
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
echo "ok: $out"
