#!/usr/bin/env bash
# Installs what is missing, then configures and builds pcsim in build/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-deps.sh
BUILD_DIR=${PCSIM_BUILD_DIR:-build}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)"
# The Python API: `import pcsim` in Debian's /usr/bin/python3 (and in the
# python3 on PATH when it is another interpreter of the same version) finds
# this build's module (docs/python.md).
if [ -d "$BUILD_DIR/python" ]; then
  module_dir=$(cd "$BUILD_DIR/python" && pwd)
  for py in /usr/bin/python3 "$(command -v python3 || true)"; do
    [ -x "$py" ] || continue
    site=$("$py" -c 'import site, sys; print(site.getsitepackages()[0])' 2> /dev/null) || continue
    same=$("$py" -c 'import sys; print(sys.version_info[:2] == (3, 11))' 2> /dev/null || true)
    [ "$same" = "True" ] || continue
    mkdir -p "$site" && echo "$module_dir" > "$site/pcsim-build.pth" ||
      echo "pcsim build: cannot register the Python module with $py ($site)" >&2
  done
fi
