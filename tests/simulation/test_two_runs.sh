#!/bin/bash
# Two cases in one process give the figures of two processes: run_cases runs
# two scenes one after the other through the run pipeline in one process
# (the second on what the first left behind: PETSc objects, log stages, the
# modal cache, static variables), `pcsim run` runs each in a process of its
# own; every figure of summary.json and the contact-force history must be
# equal bit for bit (one rank: the same operations in the same order).
# The cases: the small test line with the EN 50318 pantograph (linear FE),
# then the same line with the modal catenary and the nonlinear DSA-380, then
# that again with another static force: the third takes the static
# configuration and the modal basis the second kept in memory
# (src/simulation/setup_memory.hpp), a process of its own reads the basis
# from the cache folder and solves the statics.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cases=$(dirname "$PCSIM_BIN")/tests/run_cases
data=$PCSIM_SOURCE_DIR/tests/contact/data
cat > "$tmp/modal-dsa380.yaml" <<YAML
base: $data/three-span-dsa380.yaml
name: modal-dsa380
set: {catenary.model: modal, catenary.max_frequency_hz: 150, effects.catenary_nonlinear: false}
YAML
cat > "$tmp/modal-dsa380-force.yaml" <<YAML
base: $tmp/modal-dsa380.yaml
name: modal-dsa380-force
set: {"pantographs[0].static_force": 110}
YAML
scenes=("$data/three-span-lumped.yaml" "$tmp/modal-dsa380.yaml" "$tmp/modal-dsa380-force.yaml")
cd "$tmp"  # the modal cache (out/.pcsim-cache) of both ways in the same place
"$cases" "$tmp/one-process" "${scenes[@]}" > one.log 2>&1 || { cat one.log; exit 1; }
for i in 1 2 3; do
  "$PCSIM_BIN" run "${scenes[$((i - 1))]}" -o "$tmp/process-$i" --no-report > p$i.log 2>&1 ||
    { cat p$i.log; exit 1; }
done
"$PCSIM_PYTHON" - "$tmp" <<'PY'
import json, sys
import h5py
import numpy as np
d = sys.argv[1]
for i in (1, 2, 3):
    a = json.load(open(f"{d}/one-process/{i}/summary.json"))
    b = json.load(open(f"{d}/process-{i}/summary.json"))
    assert a["en50318"] and a["en50318"] == b["en50318"], (i, a["en50318"], b["en50318"])
    assert a["steps"] == b["steps"] and a["newton_iterations"] == b["newton_iterations"]
    with h5py.File(f"{d}/one-process/{i}/results.h5") as fa, h5py.File(f"{d}/process-{i}/results.h5") as fb:
        for name in fa["pantographs"]:
            x = fa[f"pantographs/{name}/contact_force"][:]
            y = fb[f"pantographs/{name}/contact_force"][:]
            assert np.array_equal(x, y), (i, name, np.max(np.abs(x - y)))
            assert x.max() - x.min() > 10, (i, name)  # a dynamic run
    print(f"case {i}: {a['steps']} steps, figures and contact force equal bit for bit")
    if i == 3:  # kept in memory in one process, read and solved by a process of its own
        assert a["modal"]["basis_kept_in_memory"] and a["statics_kept_in_memory"], a["modal"]
        assert a["modal"]["cache_file"] == b["modal"]["cache_file"], (a["modal"], b["modal"])
        assert not b["modal"]["basis_kept_in_memory"] and not b["statics_kept_in_memory"]
        print("case 3: static configuration and modal basis kept in memory from case 2")
PY
