#!/usr/bin/env python3
"""A plate striking a wall: how much of its speed it keeps, against the step and the grid.

The impulse-wave flume's slide brakes by the number of steps where it lands on the floor
(docs/impulse_waves.md, "Where the step enters"). This isolates the landing: a plate 0.6 m long
and h = 0.12 m thick (density 1620 kg/m3, E = 1 MPa, nu = 0.3: the flume slide's material,
elastic or Drucker-Prager 43 deg), no gravity, strikes the floor z = 0 at 1.82 m/s normal and
1.82 m/s along it (45 deg, the flume's landing), in a slab one plate wide between slip walls.
Printed: the plate's mean normal velocity after the impact over the one before (the rebound; an
elastic plate on a rigid frictionless wall keeps nearly all of it, e -> 1 for a long thin plate)
and, on a Coulomb floor, its tangential over normal momentum change (mu while it slides). Each
row is one run of 0.25 s; the set below took about 10 minutes on 2 cores here.

  PYTHONPATH=build/python python3 tools/studies/impact_rebound.py [--out DIR] [--fine]
"""
import argparse
import os
import sys

import numpy as np

import talus

H, SPEED, MU = 0.12, 1.82, 0.4452


def scene(model, floor, dx, cfl, max_dt):
    extra = "\nfriction_angle = 43" if model == "drucker_prager" else ""
    law = '"slip"' if floor == "slip" else f'{{ law = "friction", friction = {MU} }}'
    return f"""
[simulation]
dx = {dx}
end_time = 0.25
gravity = [0, 0, 0]
cfl = {cfl}
max_dt = {max_dt}
[domain]
min = [0, 0, 0]
max = [3.0, {2 * 0.0375}, 0.6]
walls = "slip"
z_min = {law}
z_max = "open"
[[materials]]
name = "plate"
model = "{model}"
density = 1620
youngs_modulus = 1e6
poisson_ratio = 0.3{extra}
[[bodies]]
material = "plate"
shape = "box"
center = [0.8, 0.0375, {H / 2 + 0.04}]
size = [0.6, 0.075, {H}]
velocity = [{SPEED}, 0, {-SPEED}]
[output]
series = false
maps = false
"""


def mean_velocity(sim):
    p = sim.particles("plate")
    m = np.asarray(p["mass"], dtype=np.float64)
    return (m[:, None] * np.asarray(p["velocity"], dtype=np.float64)).sum(0) / m.sum()


def rebound(model, floor, dx, cfl, max_dt, out):
    name = f"{model}_{floor}_dx{dx:g}_cfl{cfl:g}_dt{max_dt:g}"
    sim = talus.Simulation(talus.Scene.from_text(scene(model, floor, dx, cfl, max_dt), name=name + ".toml"),
                           out=os.path.join(out, name), threads=0)
    v0 = mean_velocity(sim)
    sim.run()
    v1 = mean_velocity(sim)
    ratio = (v1[0] - v0[0]) / (v1[2] - v0[2])
    return -v1[2] / v0[2], -ratio, sim.steps


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="/tmp/talus_impact_rebound")
    ap.add_argument("--fine", action="store_true", help="add h/dx = 25.6 (each run 16 times the 12.8 one: over an hour more)")
    a = ap.parse_args()
    cells = [3.2, 6.4, 12.8] + ([25.6] if a.fine else [])
    print("model floor h/dx cfl max_dt steps rebound dp_t/dp_n")
    for model in ("elastic", "drucker_prager"):
        for floor in ("slip", "coulomb"):
            for n in cells:
                # The step held (max_dt below the CFL step), then the CFL step alone at 0.4 and 0.1.
                for cfl, max_dt in ((0.4, 1e-4), (0.4, 3e-5), (0.4, 1.0), (0.1, 1.0)):
                    e, r, steps = rebound(model, floor, H / n, cfl, max_dt, a.out)
                    print(f"{model} {floor} {n} {cfl} {max_dt:g} {steps} {e:.3f} {r:.3f}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
