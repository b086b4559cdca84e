#!/bin/bash
# Sobol indices (postproc/sensitivity.py) of the Ishigami function from a Saltelli design of
# postproc/sample.py: within 0.02 of the exact values (tests/studies/sobol_check.py).
set -euo pipefail
: "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
"$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/tests/studies/sobol_check.py" "$PCSIM_SOURCE_DIR"
