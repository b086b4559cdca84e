#!/bin/bash
# The Python API (docs/python.md) on 1 and 2 ranks against `pcsim run` on the
# same scene (tests/python/python_api_check.py says what is checked), the
# step-wise interface (tests/python/stepping_check.py; with a moving window,
# tests/python/window_stepping_check.py), the accuracy pilot
# of a modal scene (tests/python/pilot_api_check.py), and the
# worked study of docs/python.md, executed as written.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export PYTHONPATH="$(dirname "$PCSIM_BIN")/python${PYTHONPATH:+:$PYTHONPATH}"
mpirun=$PCSIM_SOURCE_DIR/scripts/mpirun.sh
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
cd "$tmp"
for np in 1 2; do
  "$mpirun" -n $np "$PCSIM_BIN" run "$scene" -o "ref-$np" --no-report > "ref-$np.log" 2>&1 ||
    { cat "ref-$np.log"; exit 1; }
  # -m mpi4py: an uncaught exception (a failed check on one rank) aborts every
  # rank instead of leaving the others waiting in a collective.
  "$mpirun" -n $np "$PCSIM_PYTHON" -m mpi4py "$PCSIM_SOURCE_DIR/tests/python/python_api_check.py" \
    "$PCSIM_SOURCE_DIR" "ref-$np/summary.json"
  "$mpirun" -n $np "$PCSIM_PYTHON" -m mpi4py "$PCSIM_SOURCE_DIR/tests/python/stepping_check.py" \
    "$PCSIM_SOURCE_DIR"
  "$mpirun" -n $np "$PCSIM_PYTHON" -m mpi4py \
    "$PCSIM_SOURCE_DIR/tests/python/window_stepping_check.py" "$PCSIM_SOURCE_DIR"
  # A modal scene: the API runs the accuracy pilot `pcsim run` runs.
  for pilot in true false; do
    "$mpirun" -n $np "$PCSIM_BIN" run "$scene" --set catenary.model=modal -o "modal-$pilot-$np" \
      --no-report -pcsim_accuracy_pilot $pilot > "modal-$pilot-$np.log" 2>&1 ||
      { cat "modal-$pilot-$np.log"; exit 1; }
  done
  # Without the suite's PETSC_OPTIONS (-pcsim_accuracy_pilot false): the API's default.
  PETSC_OPTIONS='' "$mpirun" -n $np "$PCSIM_PYTHON" -m mpi4py "$PCSIM_SOURCE_DIR/tests/python/pilot_api_check.py" \
    "$PCSIM_SOURCE_DIR" "modal-true-$np" "modal-false-$np"
done
# docs/python.md's study (its first ```python block) and its step-wise
# example (the second), run from the repository as written.
for block in 0 1; do
  "$PCSIM_PYTHON" - "$PCSIM_SOURCE_DIR/docs/python.md" $block > "block$block.py" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
print(re.findall(r"```python\n(.*?)```", text, re.S)[int(sys.argv[2])])
PY
  (cd "$PCSIM_SOURCE_DIR" && PCSIM_STUDY_PLOT="$tmp/speeds.png" "$PCSIM_PYTHON" "$tmp/block$block.py") \
    > "block$block.log"
  cat "block$block.log"
done
[ -s "$tmp/speeds.png" ] || { echo "the study wrote no plot"; exit 1; }
grep -q "km/h" block0.log
grep -q "gain 0.3: raw sigma" block1.log
# BLAS kernels (docs/python.md): imported first, pcsim chooses BLIS's vector
# kernels where BLIS's detection would take its generic ones; after numpy,
# which starts BLIS, it cannot, says so in pcsim.blas and warns. On a
# processor BLIS knows, neither import order warns.
"$PCSIM_PYTHON" - <<'PY'
import subprocess, sys
def run(code):
    r = subprocess.run([sys.executable, "-W", "always", "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r
first = run("import pcsim; print(pcsim.blas)")
late = run("import numpy, pcsim; print(pcsim.blas)")
print("pcsim first:", first.stdout.strip())
print("numpy first:", late.stdout.strip())
assert "RuntimeWarning" not in first.stderr, first.stderr
if "chosen by pcsim" in first.stdout:
    assert "BLIS started before pcsim could choose" in late.stdout, late.stdout
    assert "RuntimeWarning: pcsim: BLAS:" in late.stderr, late.stderr
else:
    assert "before pcsim could choose" not in late.stdout, late.stdout
    assert "RuntimeWarning" not in late.stderr, late.stderr
PY
