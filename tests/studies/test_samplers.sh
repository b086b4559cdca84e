#!/bin/bash
# postproc/sample.py's designs and errors (tests/studies/samplers_check.py).
set -euo pipefail
: "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/tests/studies/samplers_check.py" "$PCSIM_SOURCE_DIR" "$tmp"
