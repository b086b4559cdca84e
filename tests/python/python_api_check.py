"""Checks of the Python API (src/python/module.cpp, docs/python.md), run by
test_python_api.sh on 1 and 2 ranks (under mpirun with mpi4py).

argv: SOURCE_DIR REFERENCE_SUMMARY  (summary.json of `pcsim run` on the same scene)
"""
import json
import sys
import time

from mpi4py import MPI  # first: MPI started by mpi4py, PETSc joins it

import pcsim  # before numpy, which starts BLIS: pcsim chooses its kernels first (docs/python.md)
import numpy as np

source, reference = sys.argv[1], sys.argv[2]
comm = MPI.COMM_WORLD
scene_file = f"{source}/tests/contact/data/three-span-lumped.yaml"

# 1. The same figures as `pcsim run` on the same scene: bit for bit on one
# rank; on two, MUMPS (the static solutions) schedules its work dynamically:
# within 1e-10 (README "Interrupted runs and restarts") of the largest figure
# in the same unit. Relative to itself a difference of larger figures moves
# more: Fm-3sigma (50.7 N) once differed by 5.1e-9 N, 1.0e-10 of itself and
# 2.7e-11 of the 190 N statistical maximum.
scene = pcsim.Scene(scene_file)
start = time.perf_counter()
result = pcsim.run(scene)
call_s = time.perf_counter() - start
ref = json.load(open(reference))["en50318"]
got = result["en50318"]
if comm.rank == 0:
    for name, figures in ref.items():
        scale = {}
        for a in figures["figures"]:
            scale[a["unit"]] = max(scale.get(a["unit"], 0.0), abs(a["value"]))
        for a, b in zip(figures["figures"], got[name]["figures"]):
            assert a["key"] == b["key"], (a, b)
            if comm.size == 1:
                assert a["value"] == b["value"], (a, b)
            else:
                assert abs(a["value"] - b["value"]) <= 1e-10 * scale[a["unit"]], (a, b)
    f = result["pantographs"]["lumped"]["contact_force"]
    t = result["time"]
    assert len(t) == result["facts"]["steps"] + 1 and len(f) == len(t)
    assert f.min() > 10 and f.max() - f.min() > 20, (f.min(), f.max())  # a dynamic run
    ff = result["pantographs"]["lumped"]["contact_force_filtered"]
    assert np.std(ff) < np.std(f)  # the 20 Hz low-pass takes out the high band
    assert result["support_z"].shape == (len(t), 4)  # the 4 supports of the 3 spans
    # What the call costs beyond the run's own set-up and time loop: reading the
    # scene, the statistics and summary, the arrays (measured ~0.02 s).
    facts = result["facts"]
    overhead = call_s - facts["setup_s"] - facts["wall_time_s"]
    print(f"rank 0: figures equal to pcsim run; call {call_s:.3f} s, "
          f"of which beyond set-up and time loop {overhead:.3f} s")

# 2. Input errors are exceptions carrying file, key and reason.
try:
    pcsim.Scene(scene_file, set={"simulation.speed_kmh": -5})
    raise AssertionError("a negative speed was accepted")
except pcsim.InputError as e:
    assert e.key == "simulation.speed_kmh" and "positive" in e.reason, (e.key, e.reason)
    assert isinstance(e, ValueError)

# 3. A scene from a dict, and two runs in one process (re-entrant): the
# second equals the first.
d = {"base": scene_file, "set": {"simulation.speed_kmh": 150}}
a = pcsim.run(pcsim.Scene.from_dict(d))
b = pcsim.run(pcsim.Scene(scene_file, set={"simulation.speed_kmh": 150}))
if comm.rank == 0:
    assert a["en50318"] == b["en50318"] or comm.size > 1, "dict scene differs"

# 4. Modes of the EN 50318 catenary: the first frequency as pinned by the
# regression test (tests/regression/expected: 0.9537 Hz).
m = pcsim.modes(pcsim.Scene(f"{source}/runs/en50318-300.yaml"), count=5)
if comm.rank == 0:
    assert len(m["frequencies_hz"]) == 5
    assert abs(m["frequencies_hz"][0] - 0.9537) < 5e-5, m["frequencies_hz"][0]
    print("rank 0: input errors, dict scenes, repeated runs and modes as expected")
