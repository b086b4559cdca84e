#!/usr/bin/env python3
"""Independent estimate of the EN 50318 line's lateral deflection under a
uniform cross-wind (docs/conditions.md, "Blow-off"); shares no code with pcsim.

Each span alone (both wires held laterally at the supports: messenger
supports pinned, steady arms holding the contact wire's lateral position):
the contact wire and the messenger as taut strings of horizontal tension T
under their drag q = rho Cd d V^2 / 2, joined at the droppers by pendulums
of lateral stiffness N / h (the dropper's force over its length). Finite
differences along the span (dx = 0.1 m). Each dropper (stranded bronze,
d = 4 mm, Cd 1.2) carries its own drag q_d h, half onto each wire at its
station. N from the contact wire's weight
shared between neighbouring droppers (clamps, steady arm), h from the
messenger's parabola under its weight and the dropper forces. The wires are
anchored at the line's ends: their lateral sag stretches them, the tension
rises by EA (1/2 int y'^2 dx) / L, iterated.

  blowoff_estimate.py SPEED [--json]   mid-span lateral deflection [m]
"""
import json
import sys

import numpy as np

G = 9.81
SPAN, SPANS, SYSTEM_HEIGHT = 60.0, 10, 1.2
DROPPERS = [5.0, 10.5, 17.0, 23.5, 30.0, 36.5, 43.0, 49.5, 55.0]
CONTACT = dict(mass=1.35, EA=1.44e7, T=20000.0, d=0.0132, cd=1.0)
MESSENGER = dict(mass=1.07, EA=1.0e7, T=16000.0, d=0.0105, cd=1.2)
DROPPER = dict(d=0.004, cd=1.2)
CLAMP_CONTACT, CLAMP_MESSENGER, DROPPER_MASS, ARM = 0.165, 0.195, 0.117, 1.0
RHO = 1.25
DX = 0.1


def dropper_forces():
    """Each dropper carries the contact wire halfway to its neighbours (across
    a support to the next span's first dropper), its clamp and, next to a
    support, half the steady arm's mass (the arm holds only laterally)."""
    xs = [x - SPAN for x in DROPPERS[-1:]] + DROPPERS + [x + SPAN for x in DROPPERS[:1]]
    forces = []
    for i in range(1, len(xs) - 1):
        share = 0.5 * (xs[i + 1] - xs[i - 1])
        arm = 0.5 * ARM if i in (1, len(xs) - 2) else 0.0
        forces.append(G * (CONTACT["mass"] * share + CLAMP_CONTACT + arm))
    return np.array(forces)


def dropper_lengths(forces):
    """The messenger (held 1.2 m above the level contact wire at the
    supports) as a string under its weight and the dropper forces."""
    n = int(round(SPAN / DX))
    x = np.linspace(0, SPAN, n + 1)
    load = np.full(n + 1, MESSENGER["mass"] * G)
    for xd, f in zip(DROPPERS, forces):
        load[int(round(xd / DX))] += (f + G * (CLAMP_MESSENGER + DROPPER_MASS * SYSTEM_HEIGHT)) / DX
    sag = string(MESSENGER["T"], load)
    return np.array([SYSTEM_HEIGHT - sag[int(round(xd / DX))] for xd in DROPPERS]), x


def string(T, load, springs=None):
    """Deflection of a string T y'' + load = 0, y = 0 at both ends."""
    n = int(round(SPAN / DX))
    A = np.zeros((n - 1, n - 1))
    for i in range(n - 1):
        A[i, i] = 2 * T / DX**2
        if i > 0:
            A[i, i - 1] = -T / DX**2
        if i < n - 2:
            A[i, i + 1] = -T / DX**2
    y = np.zeros(n + 1)
    y[1:-1] = np.linalg.solve(A, load[1:-1])
    return y


def span_lateral(Tc, Tm, qc, qm, k, dropper_drag):
    """Lateral deflections of both wires in one span: strings coupled by the
    droppers' pendulum stiffnesses k (N/m) at the dropper stations, each
    dropper's drag (N) half on either wire there."""
    n = int(round(SPAN / DX))
    m = n - 1
    A = np.zeros((2 * m, 2 * m))
    b = np.zeros(2 * m)
    for w, T, q in ((0, Tc, qc), (1, Tm, qm)):
        for i in range(m):
            r = w * m + i
            A[r, r] = 2 * T / DX**2
            if i > 0:
                A[r, r - 1] = -T / DX**2
            if i < m - 1:
                A[r, r + 1] = -T / DX**2
            b[r] = q
    for xd, kd, fd in zip(DROPPERS, k, dropper_drag):
        i = int(round(xd / DX)) - 1
        for r, s in ((i, m + i), (m + i, i)):
            A[r, r] += kd / DX
            A[r, s] -= kd / DX
            b[r] += 0.5 * fd / DX
    y = np.linalg.solve(A, b)
    zero = np.zeros(1)
    return np.concatenate([zero, y[:m], zero]), np.concatenate([zero, y[m:], zero])


def estimate(speed):
    forces = dropper_forces()
    lengths, _ = dropper_lengths(forces)
    k = forces / lengths
    qc = 0.5 * RHO * CONTACT["cd"] * CONTACT["d"] * speed**2
    qm = 0.5 * RHO * MESSENGER["cd"] * MESSENGER["d"] * speed**2
    dropper_drag = 0.5 * RHO * DROPPER["cd"] * DROPPER["d"] * speed**2 * lengths
    Tc, Tm = CONTACT["T"], MESSENGER["T"]
    for _ in range(20):  # anchored wires: the lateral sag's stretch raises the tension
        yc, ym = span_lateral(Tc, Tm, qc, qm, k, dropper_drag)
        stretch = lambda y: 0.5 * np.sum(np.diff(y) ** 2) / DX / SPAN
        Tc = CONTACT["T"] + CONTACT["EA"] * stretch(yc)
        Tm = MESSENGER["T"] + MESSENGER["EA"] * stretch(ym)
    mid = len(yc) // 2
    return dict(speed=speed, q_contact=qc, q_messenger=qm, contact_mid=yc[mid],
                messenger_mid=ym[mid], contact_alone=qc * SPAN**2 / (8 * CONTACT["T"]),
                tension_contact=Tc, tension_messenger=Tm,
                dropper_stiffness=k.tolist(), dropper_length=lengths.tolist())


if __name__ == "__main__":
    r = estimate(float(sys.argv[1]))
    if "--json" in sys.argv:
        print(json.dumps(r))
    else:
        print("V %.1f m/s: q %.3f / %.3f N/m; contact wire mid-span %.4f m (alone %.4f m), "
              "messenger %.4f m; T %.0f / %.0f N" % (r["speed"], r["q_contact"], r["q_messenger"],
              r["contact_mid"], r["contact_alone"], r["messenger_mid"], r["tension_contact"],
              r["tension_messenger"]))
