#!/usr/bin/env python3
"""The acceleration error of a roof record read by the natural cubic spline
(`base_motion: {type: file, interpolation: cubic}`, docs/conditions.md,
"Vehicle excitation"), measured with SciPy's natural CubicSpline (the same
spline as pcsim::NaturalCubicSpline; shares no pcsim code):
 1. 2 mm at 5 Hz sampled every 1 ms, written with 6, 10 and 17 significant
    digits: the largest a_b error over 0.05-0.95 s, relative to the
    amplitude, and the six-digit record's error at t = 0.4321 s (pcsim's
    spline gives the same to 12 digits, tests/scene/test_time_signal.cpp);
 2. runs/conditions/roof.csv (3 mm at 1.2 Hz plus 0.5 mm at 8 Hz, every
    5 ms, seven decimals) against the two sines' exact a_b over 0.5-7 s, and
    the same samples unrounded.
  /usr/bin/python3 runs/conditions/roof_spline_error.py
"""
import os

import numpy as np
from scipy.interpolate import CubicSpline

w = 2 * np.pi * 5
t = np.arange(0, 1.0005, 1e-3)
x = np.linspace(0.05, 0.95, 20001)
exact = -2e-3 * w * w * np.sin(w * x)
for digits in (6, 10, 17):
    z = np.array([float(f"{2e-3 * np.sin(w * s):.{digits}g}") for s in t])
    tt = np.array([float(f"{s:.{digits}g}") for s in t])
    spline = CubicSpline(tt, z, bc_type="natural")
    err = np.max(np.abs(spline(x, 2) - exact)) / (2e-3 * w * w)
    line = f"2 mm, 5 Hz, 1 ms samples, {digits:2d} digits: largest a_b error {err:.2g} of the amplitude"
    if digits == 6:
        at = spline(0.4321, 2) + 2e-3 * w * w * np.sin(w * 0.4321)
        line += f" ({100 * err:.1f} %); at t = 0.4321 s {at:.12f} m/s^2"
    print(line)

roof = np.loadtxt(os.path.join(os.path.dirname(os.path.abspath(__file__)), "roof.csv"),
                  delimiter=",")
w1, w2 = 2 * np.pi * 1.2, 2 * np.pi * 8
x = np.linspace(0.5, 7.0, 200001)
exact = -0.003 * w1**2 * np.sin(w1 * x) - 0.0005 * w2**2 * np.sin(w2 * x)
for name, z in (("roof.csv", roof[:, 1]),
                ("unrounded", 0.003 * np.sin(w1 * roof[:, 0]) + 0.0005 * np.sin(w2 * roof[:, 0]))):
    e = CubicSpline(roof[:, 0], z, bc_type="natural")(x, 2) - exact
    print(f"{name}: a_b error over 0.5-7 s: largest {np.max(np.abs(e)):.2g} m/s^2, "
          f"rms {np.sqrt(np.mean(e**2)):.2g} m/s^2 (the 8 Hz component's amplitude "
          f"{0.0005 * w2**2:.2f} m/s^2)")
