"""The step-wise interface (pcsim.Simulation, docs/python.md) with a moving
window, on 1 or 2 ranks: the window shifts as in pcsim.run and the contact
stations are the line's. Until 2026-12-06 such a scene was refused
(InputError on 'window'), and with it the modal level on a long line, which
takes a window itself: the hardware-in-the-loop case of a long line.
 1. small-window-linear.yaml (12 spans in a window of 4, two shifts), the
    linearised FE and the modal window: stepping one step at a time gives
    pcsim.run's contact force and contact stations bit for bit (on two ranks
    with the deterministic solvers of stepping_check.py); the stations reach
    the run's end at 100 m, beyond the window's 64 m.
 2. Two pantographs in a window over the train (window-two-pantographs.yaml,
    8 spans of 12, two shifts): the same, except the run's last step, whose
    contact force differs by round-off (measured 4.0e-10 N of ~150 N; the
    same without a window, on the whole line: not the window's; 1e-8 N
    allowed, 25 x that).
usage: [mpirun -n N] /usr/bin/python3 window_stepping_check.py SOURCE_DIR
"""
import sys

from mpi4py import MPI  # noqa: F401  (MPI before pcsim under mpirun)
import pcsim  # before numpy (docs/python.md)

import numpy as np

source = sys.argv[1]
ranks = MPI.COMM_WORLD.Get_size()
root = MPI.COMM_WORLD.Get_rank() == 0
DETERMINISTIC = "-cheap_pc_type redundant -cheap_redundant_pc_factor_mat_ordering_type qmd " + " ".join(
    f"-{p}pc_type redundant -{p}redundant_pc_factor_mat_solver_type mumps"
    for p in ("static_", "start_", "start_load_"))
options = DETERMINISTIC if ranks > 1 else ""


def check(ok, message):  # decided on rank 0, raised on every rank (no hang)
    ok, message = MPI.COMM_WORLD.bcast((ok, message) if root else None)
    assert ok, message


def compare(label, scene, last_step_tolerance):
    reference = pcsim.run(scene, options=options)
    sim = pcsim.Simulation(scene, options=options)
    forces, stations = [sim.contact_force()], [sim.contact_position()]
    while not sim.finished:
        assert sim.advance() == 1
        forces.append(sim.contact_force())
        stations.append(sim.contact_position())
    forces, stations = np.array(forces), np.array(stations)
    ok, message = True, ""
    if root:  # run()'s series are rank 0's
        for p, name in enumerate(reference["pantographs"]):
            series = reference["pantographs"][name]
            f, x = series["contact_force"], series["position"]
            if len(f) != len(forces):
                ok, message = False, f"{label} {name}: {len(forces)} steps, run {len(f)}"
                break
            gap = np.abs(forces[:, p] - f)
            worst = (gap[:-1].max(), gap[-1], np.abs(stations[:, p] - x).max())
            if worst[0] != 0 or worst[1] > last_step_tolerance or worst[2] != 0:
                ok, message = False, f"{label} {name}: stepped vs run differ by {worst}"
                break
            print(f"ok   {label}, {name}: stepped = run on {ranks} rank(s) "
                  f"(last step {worst[1]:.1e} N), stations to {stations[-1, p]:.1f} m")
    check(ok, message)
    return stations


small = source + "/tests/assembly/data/small-window-linear.yaml"
stations = compare("FE window", pcsim.Scene(small), 0.0)
check(abs(stations[-1, 0] - 100.0) < 1e-9, f"the stations end at {stations[-1, 0]}, not 100 m")
compare("modal window", pcsim.Scene(small, {"catenary.model": "modal"}), 0.0)
train = pcsim.Scene(source + "/tests/contact/data/window-two-pantographs.yaml",
                    {"window.spans_behind": 2, "window.spans_ahead": 2})
compare("window over two pantographs", train, 1e-8)
