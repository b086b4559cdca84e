"""Step times of the step-wise interface (pcsim.Simulation, docs/python.md), the
hardware-in-the-loop path: each step is advance(1) and a read of the contact
force through Python, timed from the caller. One rank; run on an idle machine.

  PYTHONPATH=build/python /usr/bin/python3 runs/bench_stepping.py [STEPS]

Scenes: the modal level on runs/interaction/two-pantographs-300.yaml at 20
spans (its whole line) and at 1000 spans (the modal window auto chooses),
with the accuracy pilot off (its cut-off is the scene's default); each
set-up is timed twice, the first with an empty cache (the script works in a
new temporary folder), the second in a new process from the cache the first
filled (out/.pcsim-cache under it). Prints one row a scene:
set-up (first, cached) [s], median, 99th, 99.9th percentile and max of the
step [ms], real-time factor (simulated over wall time of the steps).
"""
import os
import subprocess
import sys
import tempfile
import time

import pcsim  # before numpy (docs/python.md)

import numpy as np

STEPS = int(sys.argv[1]) if len(sys.argv) > 1 else 9000
HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "interaction", "two-pantographs-300.yaml")
OPTIONS = "-pcsim_accuracy_pilot false"


def timed_setup(scene):
    start = time.perf_counter()
    sim = pcsim.Simulation(scene, options=OPTIONS)
    return sim, time.perf_counter() - start


def cached_setup(spans):
    # In a process of its own: a second Simulation in this one would find
    # what the first built still in memory.
    code = (f"import time, pcsim; s = pcsim.Scene({SCENE!r}, {{'catenary.design.spans.count': "
            f"{spans}, 'catenary.model': 'modal'}}); t = time.perf_counter(); "
            f"pcsim.Simulation(s, options={OPTIONS!r}); print(time.perf_counter() - t)")
    # The child runs in the temporary folder: it finds pcsim where this
    # process did (PYTHONPATH=build/python is relative to the repository).
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(
        [os.path.dirname(os.path.abspath(pcsim.__file__))] +
        [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True,
                         env=env)
    return float(out.stdout.split()[-1])


def row(label, spans):
    scene = pcsim.Scene(SCENE, {"catenary.design.spans.count": spans, "catenary.model": "modal"})
    sim, first = timed_setup(scene)
    cached = cached_setup(spans)
    walls = []
    t0 = sim.time
    while len(walls) < STEPS and not sim.finished:
        start = time.perf_counter()
        sim.advance(1)
        sim.contact_force()
        walls.append(time.perf_counter() - start)
    ms = 1e3 * np.array(walls)
    rtf = (sim.time - t0) / (1e-3 * ms.sum())
    print(f"| {label} | {first:.1f} | {cached:.2f} | {len(ms)} | {np.median(ms):.3f} | "
          f"{np.percentile(ms, 99):.3f} | {np.percentile(ms, 99.9):.3f} | {ms.max():.2f} | "
          f"{rtf:.1f} |", flush=True)


os.chdir(tempfile.mkdtemp(prefix="pcsim-bench-stepping-"))
print("| scene (modal) | set-up s | cached s | steps | median ms | 99 % | 99.9 % | max | RTF |")
print("|---|---|---|---|---|---|---|---|---|")
row("two-pantographs-300, 20 spans", 20)
row("two-pantographs-300, 1000 spans (window)", 1000)
