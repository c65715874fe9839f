#!/usr/bin/env python3
"""A steady water sheet turned by a wall: where on the wall the load lands (docs/convergence.md,
"Wall pressure", the corner study). A slug h wide (or 2h, mirrored) runs at U into the closed
x_max face, quasi-2-D (two cells deep between slip walls), with a [[panels]] row on every node
row of the wall; the rows' pressures are averaged while 30-70 % of the slug arrives and in bands
of three rows (a single row alternates with its neighbours, docs/convergence.md).

  wall_jet.py scene KIND DX > scene.toml   # KIND: symmetric | corner | corner_gravity
  talus run scene.toml --out DIR
  wall_jet.py measure KIND DIR DX          # bands of p / p0 from the floor (or the axis) up

symmetric: a jet 2h = 0.24 m wide at 4 m/s, no gravity, its axis at z = 0 (the lower half
mirrors the upper). corner: its upper half along a slip floor. corner_gravity: that sheet at
Froude number U / sqrt(g h) = 2.5 (U = 2.7 m/s) under gravity, the dam break's arriving sheet
(docs/convergence.md). p0 = rho U^2 / 2 (+ rho g h with gravity).
"""
import csv
import math
import sys

H, LENGTH = 0.12, 1.2


def speed(kind):
    return 2.7 if kind == "corner_gravity" else 4.0


def scene(kind, dx):
    corner, depth, u = kind != "symmetric", 2 * dx, speed(kind)
    gravity = "[0, 0, -9.81]" if kind == "corner_gravity" else "[0, 0, 0]"
    text = f"""[simulation]
dx = {dx}
end_time = {0.2 / u + LENGTH / u + 0.15}
gravity = {gravity}
[domain]
min = [0, 0, {0 if corner else -1.0}]
max = [2.0, {depth}, 1.0]
walls = "open"
x_max = "slip"
y_min = "slip"
y_max = "slip"
{'z_min = "slip"' if corner else ''}
[[materials]]
name = "water"
model = "water"
density = 1000
sound_speed = 40
[[bodies]]
material = "water"
shape = "box"
min = [0.6, 0, {0 if corner else -H}]
max = [1.8, {depth}, {H}]
velocity = [{u}, 0, 0]
[output]
series_interval = 0.0025
"""
    for j in range(int(round(0.6 / dx)) + 1):
        text += (f'[[panels]]\nname = "r{j}"\nface = "x_max"\nmin = [0, -1, {(j - 0.25) * dx}]\n'
                 f'max = [0, {depth + 1}, {(j + 0.25) * dx}]\n')
    return text


def measure(kind, out, dx):
    u = speed(kind)
    p0 = 0.5 * 1000 * u * u + (1000 * 9.81 * H if kind == "corner_gravity" else 0)
    rows = list(csv.DictReader(open(f"{out}/series.csv")))
    arrived = lambda r: (float(r["time_s"]) - 0.2 / u) * u / LENGTH
    sel = [r for r in rows if 0.3 < arrived(r) < 0.7]
    p = []
    while f"pressure_Pa_r{len(p)}" in rows[0]:
        key = f"pressure_Pa_r{len(p)}"
        p.append(sum(float(r[key]) for r in sel) / len(sel) / p0)
    bands = [sum(p[j:j + 3]) / 3 for j in range(0, len(p) - 2, 3)]
    print(f"{kind}, dx {dx}: p / p0 in bands of three rows from z = 0 (z / h = 0, "
          f"{3 * dx / H:.2f}, ...):", " ".join(f"{b:.2f}" for b in bands if b > 0.005))


if __name__ == "__main__":
    if sys.argv[1] == "scene":
        print(scene(sys.argv[2], float(sys.argv[3])))
    else:
        measure(sys.argv[2], sys.argv[3], float(sys.argv[4]))
