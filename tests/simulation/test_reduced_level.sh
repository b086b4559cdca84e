#!/bin/bash
# The reduced (modal) level at its default settings against linear FE at the
# same dt and mesh (issue 21's "Done means"), on two scenes no default was
# tuned on, each with its accuracy pilot (docs/fidelity.md):
#  - the short three-section line at 250 km/h (runs/lines/three-sections-short-250.yaml:
#    two overlaps, analysis spans 2-8, all of which the pilot runs: the spans differ);
#  - the rigid DSA-380 (nonlinear, damper) on the three-span test catenary
#    (tests/contact/data/three-span-dsa380.yaml with the linearised catenary).
# Every figure's actual error is within the targets (mean 0.5 %, σ, Fm+3σ and
# actual maximum 1 %, uplift 2 %, minima 2 % of Fm, loss of contact 0.1
# point), and every estimate within [actual, 3 actual + 0.3]
# (postproc/pilot_check.py --check --targets). The two-pantograph scene is in
# test_accuracy_pilot.sh.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
check() {  # name scene [--set ...]
  local name=$1 scene=$2
  shift 2
  "$PCSIM_BIN" run "$scene" "$@" --set catenary.model=modal -o "$name-modal" --cache cache \
    --no-report -pcsim_accuracy_pilot true > "$name-modal.log" 2>&1 ||
    { cat "$name-modal.log"; exit 1; }
  "$PCSIM_BIN" run "$scene" "$@" --set catenary.model=linear -o "$name-linear" \
    --no-report -pcsim_accuracy_pilot false > "$name-linear.log" 2>&1 ||
    { cat "$name-linear.log"; exit 1; }
  echo "== $name: $(grep 'accuracy pilot:' "$name-modal.log")"
  "$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/postproc/pilot_check.py" "$name-modal" \
    --reference "$name-linear" --check --targets
}
check three-sections "$PCSIM_SOURCE_DIR/runs/lines/three-sections-short-250.yaml"
# Its spans differ (overlaps): the pilot covers the whole section, not two spans.
grep -q "accuracy pilot: spans 2-8 .*(the spans differ: the whole analysis section)" \
  three-sections-modal.log || { echo "the pilot did not cover spans 2-8"; exit 1; }
check dsa380 "$PCSIM_SOURCE_DIR/tests/contact/data/three-span-dsa380.yaml" \
  --set effects.catenary_nonlinear=false
echo "reduced level: ok"
