"""The step-wise interface (pcsim.Simulation, docs/python.md), on 1 or 2 ranks:
 1. stepping a scene one step at a time gives the contact force history of
    pcsim.run on the same scene bit for bit, on two ranks with deterministic
    linear solvers (sequential LU on every rank, as
    tests/contact/test_run_restart_np2.sh: MUMPS's parallel schedule makes
    two identical 2-rank runs differ by up to ~1e-10);
 2. a force set on the head acts on it: 20 N upwards from the start raises the
    mean contact force over the last two thirds of the run by 20 N, within
    1.5 N (measured 18.96 N: the sudden load's transient has not died out in
    the 1.2 s run, the pantograph's lowest mode being ~1 Hz; a force of the
    wrong sign, twice or not at all misses by >= 20 N);
 3. a base motion set step-wise acts on the pantograph: the base held 0.2 m
    up from the start loads the frame through its suspension (k2 = 50 N/m of
    the EN 50318 model) and raises the mean contact force over the last two
    thirds by k2 z_b = 10 N, within 1 N (measured 9.35 N, the same transient
    as the head force's; the wrong sign, twice or none misses by >= 10 N).
    (Not compared with the scene's base_motion: a scene's z_b(0) enters the
    static start, a step-wise one acts from the first step.)
 4. errors: an unknown pantograph name is an InputError naming the key;
 5. the DSA-380 step-wise (below).
usage: [mpirun -n N] /usr/bin/python3 stepping_check.py SOURCE_DIR
"""
import sys

from mpi4py import MPI  # noqa: F401  (MPI before pcsim under mpirun)
import pcsim  # before numpy, which starts BLIS: pcsim chooses its kernels first (docs/python.md)

import numpy as np

source = sys.argv[1]
scene = pcsim.Scene(source + "/tests/contact/data/three-span-lumped.yaml")
ranks = MPI.COMM_WORLD.Get_size()


# Deterministic solvers on several ranks (options stay in PETSc's database).
DETERMINISTIC = "-cheap_pc_type redundant -cheap_redundant_pc_factor_mat_ordering_type qmd " + " ".join(
    f"-{p}pc_type redundant -{p}redundant_pc_factor_mat_solver_type mumps"
    for p in ("static_", "start_", "start_load_"))
options = DETERMINISTIC if ranks > 1 else ""


def check(ok, message):  # decided on rank 0, raised on every rank (no hang)
    ok, message = MPI.COMM_WORLD.bcast((ok, message) if MPI.COMM_WORLD.Get_rank() == 0 else None)
    assert ok, message


def stepped(head_force):
    sim = pcsim.Simulation(scene, options=options)
    sim.set_head_force("lumped", head_force)
    assert sim.head_force(0) == head_force
    forces = [sim.contact_force()[0]]
    while not sim.finished:
        assert sim.advance() == 1
        forces.append(sim.contact_force()[0])
    assert abs(sim.time - sim.end_time) < 1e-12, (sim.time, sim.end_time)
    return np.array(forces)


reference = pcsim.run(scene, options=options)
free = stepped(0.0)
worst = 0.0
if MPI.COMM_WORLD.Get_rank() == 0:  # run()'s series are rank 0's
    f_ref = reference["pantographs"]["lumped"]["contact_force"]
    worst = np.max(np.abs(free - f_ref)) if len(free) == len(f_ref) else np.inf
check(worst == 0.0, f"stepped vs run on {ranks} rank(s): differ by {worst:.3e} N")
if MPI.COMM_WORLD.Get_rank() == 0:
    print(f"ok   stepped = run on {ranks} rank(s), bit for bit")

loaded = stepped(20.0)
third = len(free) // 3
rise = np.mean(loaded[third:] - free[third:])
assert abs(rise - 20.0) <= 1.5, f"20 N on the head raised the mean contact force by {rise:.2f} N"
if MPI.COMM_WORLD.Get_rank() == 0:
    print(f"ok   20 N upwards on the head: mean contact force +{rise:.2f} N")

raised = pcsim.Simulation(scene, options=options)
raised.set_base_motion("lumped", 0.2)
raised_forces = [raised.contact_force()[0]]
while not raised.finished:
    raised.advance()
    raised_forces.append(raised.contact_force()[0])
rise = np.mean(np.array(raised_forces)[third:] - free[third:])
assert abs(rise - 50 * 0.2) <= 1.0, f"the base 0.2 m up raised the mean contact force by {rise:.2f} N"
if MPI.COMM_WORLD.Get_rank() == 0:
    print(f"ok   base held 0.2 m up: mean contact force +{rise:.2f} N (k2 z_b = 10 N)")

try:
    pcsim.Simulation(scene).set_head_force("nobody", 1.0)
    raise AssertionError("an unknown pantograph was accepted")
except pcsim.InputError as e:
    assert e.key == "pantograph" and "nobody" in e.reason, e
if MPI.COMM_WORLD.Get_rank() == 0:
    print("ok   unknown pantograph: InputError")

# 5. the DSA-380 (moving frame) step-wise: without the acceleration an
#    InputError; with z_b, v_b, a_b of 5 mm at 5 Hz set before each step at the
#    step's end time, the contact force of the scene with that harmonic
#    base_motion (three-span-dsa380-base.yaml), to round-off. The values set
#    hold after the current time: the step's
#    alpha-term at its start reads the ones before, as the scene's motion is
#    read.
flat = {"effects.catenary_nonlinear": False}
dsa = pcsim.Scene(source + "/tests/contact/data/three-span-dsa380.yaml", flat)
try:
    pcsim.Simulation(dsa).set_base_motion(0, 0.001)
    raise AssertionError("a base motion without acceleration on the DSA-380 was accepted")
except pcsim.InputError as e:
    assert e.key == "base motion" and "acceleration" in e.reason, e
if MPI.COMM_WORLD.Get_rank() == 0:
    print("ok   base motion on a DSA-380 without its acceleration: InputError")

moved = pcsim.run(pcsim.Scene(source + "/tests/contact/data/three-span-dsa380-base.yaml", flat),
                  options=options)
# rank 0 holds pcsim.run's arrays; every rank steps the same times
times = MPI.COMM_WORLD.bcast(moved["time"] if MPI.COMM_WORLD.Get_rank() == 0 else None)
amplitude, omega = 0.005, 2 * np.pi * 5.0
sim = pcsim.Simulation(dsa, options=options)
stepped = [sim.contact_force()[0]]
for t in times[1:]:  # each step's end time (the last step split in two)
    sim.set_base_motion(0, amplitude * np.sin(omega * t), amplitude * omega * np.cos(omega * t),
                        -amplitude * omega**2 * np.sin(omega * t))
    sim.advance(1)
    stepped.append(sim.contact_force()[0])
assert sim.finished
if MPI.COMM_WORLD.Get_rank() == 0:
    expected = moved["pantographs"]["dsa380"]["contact_force"]
    assert len(stepped) == len(expected), (len(stepped), len(expected))
    gap = np.max(np.abs(np.array(stepped) - expected))
    print(f"ok   DSA-380 base moved step-wise: contact force within {gap:.3g} N of the scene's "
          f"harmonic base_motion ({len(stepped)} values)")
    # Round-off: the two runs take different steps' alpha-terms from the last
    # residual (the DSA-380's inertia at the state) and evaluate the others;
    # measured 9.7e-9 N on one rank, 1.5e-8 N on two (1e-7 allowed: 1e-9 of the
    # ~120 N force), while a base motion read at the wrong time or not at all
    # moves the force by over 1 N (test_run_base_motion_dsa380.sh)
    assert gap <= 1e-7, gap

# 6. A head force changed between steps reaches the next step's HHT alpha-term:
#    Simulation.set_head_force makes the next step evaluate it instead of taking
#    it from the last residual (solvers::DynamicSolver::residual_changed). The
#    force switched between 0 and 20 N every 50 steps: the run equals the one
#    that evaluates every alpha-term to round-off (measured 1.4e-8 N on 1 rank,
#    1.3e-8 N on 2; 1e-9 of the ~120 N force allowed). A stale alpha-term (the
#    old force for a step: measured with the invalidation removed) differs by
#    0.18 N.
def switched(extra):
    sim = pcsim.Simulation(scene, options=(options + " " + extra).strip())
    out, k = [sim.contact_force()[0]], 0
    while not sim.finished:
        if k % 50 == 0:
            sim.set_head_force("lumped", 20.0 if (k // 50) % 2 else 0.0)
        sim.advance(1)
        k += 1
        out.append(sim.contact_force()[0])
    return np.array(out)


reused, evaluated = switched(""), switched("-ts_hht_reuse_alpha_term 0")
gap = np.max(np.abs(reused - evaluated))
check(gap <= 1.2e-7, f"head force switched step-wise: alpha-term reused vs evaluated {gap:.3e} N")
if MPI.COMM_WORLD.Get_rank() == 0:
    print(f"ok   head force switched every 50 steps: alpha-term reused = evaluated ({gap:.2g} N)")
