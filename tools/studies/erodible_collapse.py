#!/usr/bin/env python3
"""Granular collapse over an erodible bed of the same grains (Mangeney et al. 2010, JGR 115,
F03040, set-up: a column L0 = 0.20 m long and H = 0.14 m high released down a plane of slope
theta, with or without a layer of thickness hi downstream of the gate). docs/convergence.md, §7.

  erodible_collapse.py scene THETA HI DX > scene.toml   # then: talus run scene.toml --out DIR
  erodible_collapse.py measure DIR HI [DX]              # run-outs from DIR/particles.h5 (h5py)

Glass beads as Drucker-Prager (friction angle 24 degrees, about their 23.5 degree repose), bed
Coulomb mu = tan 24 degrees; the slope is gravity turned by theta (x down the slope), the channel
two cells wide between slip walls (quasi-2-D). Material 0 is the column, 1 the layer.
"""
import math
import sys

L0, H, LENGTH, PHI = 0.20, 0.14, 1.8, 24.0


def scene(theta, hi, dx, end=3.0):
    t, mu = math.radians(theta), math.tan(math.radians(PHI))
    material = lambda name: f"""[[materials]]
name = "{name}"
density = 1500
youngs_modulus = 5e5
poisson_ratio = 0.3
model = "drucker_prager"
friction_angle = {PHI}
cone = "plane_strain"
"""
    box = lambda name, x0, x1, z1: f"""[[bodies]]
material = "{name}"
shape = "box"
min = [{x0}, 0, 0]
max = [{x1}, {2 * dx}, {z1}]
"""
    text = f"""[simulation]
dx = {dx}
end_time = {end}
gravity = [{9.81 * math.sin(t):.6f}, 0, {-9.81 * math.cos(t):.6f}]
gravity_ramp = 0.05
[domain]
min = [0, 0, 0]
max = [{LENGTH}, {2 * dx}, 0.2]
walls = "slip"
[terrain]
plane = {{ point = [0, 0, 0], normal = [0, 0, 1] }}
boundary = "friction"
friction = {mu:.5f}
""" + material("column") + box("column", 0, L0, H)
    if hi > 0:
        text += material("bed") + box("bed", L0, LENGTH, hi)
    return text + "[output]\nframe_interval = 0\n"


def measure(directory, hi, dx=0.005):
    import h5py
    import numpy as np
    f = h5py.File(directory + "/particles.h5")
    x, m, mat = f["particles/position"][:, 0], f["particles/mass"][:], f["particles/material"][:]
    bins = np.arange(0, LENGTH + dx, dx)
    volume, _ = np.histogram(x, bins, weights=m / 1500)
    h = volume / (dx * 2 * dx)
    i = int(round(L0 / dx))  # the first cell beyond the gate
    while i < len(h) and h[i] >= hi + 0.025 * L0:  # Lube's 0.025 L0 above the layer
        i += 1
    column = np.sort(x[mat == 0])
    x99 = column[int(0.99 * (len(column) - 1))]
    return {"front": (bins[i] - L0) / L0, "column_x99": (x99 - L0) / L0,
            "column_farthest": (column[-1] - L0) / L0}


if __name__ == "__main__":
    if sys.argv[1] == "scene":
        print(scene(float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])), end="")
    else:
        r = measure(sys.argv[2], float(sys.argv[3]), *(float(a) for a in sys.argv[4:5]))
        print(" ".join(f"{k} {v:.3f}" for k, v in r.items()))
