#!/bin/bash
# The user documentation holds together (tests/app/doc_links.py): every relative
# link of README.md and docs/**/*.md names an existing file (and heading), no page
# names a path outside the repository (../shared, /work/..., /home/...), and every
# repository path named in the text (include/..., runs/..., ...) exists.
set -euo pipefail
: "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
"$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/tests/app/doc_links.py" "$PCSIM_SOURCE_DIR"
