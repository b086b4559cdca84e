"""The Python API's accuracy pilot (docs/python.md, "Runs"), run by
test_python_api.sh on 1 and 2 ranks (under mpirun with mpi4py): a modal scene
through pcsim.run gets the pilot `pcsim run` runs, the same raised cut-off and
the same contact force, and pcsim.Simulation steps at that cut-off too;
-pcsim_accuracy_pilot false keeps the default cut-off, as `pcsim run` does.

argv: SOURCE_DIR PILOT_RUN DEFAULT_RUN  (result folders of `pcsim run SCENE
--set catenary.model=modal`, without and with -pcsim_accuracy_pilot false)
"""
import json
import sys

from mpi4py import MPI  # first: MPI started by mpi4py, PETSc joins it

import pcsim  # before numpy (docs/python.md, BLAS kernels)
import h5py
import numpy as np

source, with_pilot, without = sys.argv[1], sys.argv[2], sys.argv[3]
comm = MPI.COMM_WORLD
scene = pcsim.Scene(f"{source}/tests/contact/data/three-span-lumped.yaml",
                    set={"catenary.model": "modal"})


def reference(folder):
    summary = json.load(open(f"{folder}/summary.json"))
    with h5py.File(f"{folder}/results.h5", "r") as f:
        force = f["pantographs/lumped/contact_force"][:]
    return summary, force


def check(result, folder, what):
    summary, force = reference(folder)
    cutoff = result["facts"]["modal"]["cutoff_hz"]
    # The cut-off is chosen, not computed: equal to the last bit on any rank count.
    assert cutoff == summary["modal"]["cutoff_hz"], (what, cutoff, summary["modal"]["cutoff_hz"])
    if comm.rank == 0:
        got = result["pantographs"]["lumped"]["contact_force"]
        # One rank: the same arithmetic as `pcsim run`, bit for bit. Two: the
        # static solution's MUMPS scatter (test_python_api.sh's own check),
        # 1e-10 of the 120 N static force.
        tolerance = 0.0 if comm.size == 1 else 1.2e-8
        assert got.shape == force.shape and np.abs(got - force).max() <= tolerance, \
            (what, np.abs(got - force).max())
    return cutoff


result = pcsim.run(scene)
raised = check(result, with_pilot, "pilot")
assert "pilot" in result["facts"]["accuracy_estimate"], result["facts"]["accuracy_estimate"]
# The scene's default cut-off misses the targets on this line: the pilot raises it.
assert result["facts"]["accuracy_estimate"]["pilot"]["cutoff_raises"] >= 1

stepped = pcsim.Simulation(scene)
stepped.advance(10**6)
if comm.rank == 0:
    last = float(result["pantographs"]["lumped"]["contact_force"][-1])
    # The step-wise run is the same run at the same cut-off: the same last force.
    assert abs(stepped.contact_force()[0] - last) <= (0.0 if comm.size == 1 else 1.2e-8), \
        (stepped.contact_force()[0], last)
del stepped

default = pcsim.run(scene, options="-pcsim_accuracy_pilot false")
kept = check(default, without, "no pilot")
assert "pilot" not in default["facts"]["accuracy_estimate"]
assert kept < raised, (kept, raised)
if comm.rank == 0:
    print(f"python API pilot on {comm.size} rank(s): cut-off {raised:.1f} Hz "
          f"(default {kept:.1f} Hz), forces as `pcsim run`'s")
