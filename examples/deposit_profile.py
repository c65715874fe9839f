"""Particles into NumPy: the deposit's thickness along the valley from the particles themselves.

    PYTHONPATH=build/python python3 examples/deposit_profile.py [OUT_DIR]

Each particle stands for mass / density of material at rest; summed in 4 m bins along x within a
strip across the flow and divided by the bin's plan area, that is a thickness profile (m).
TALUS_EXAMPLE_QUICK=1 (what CI sets) stops the run after 3 s of simulated time.
"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import talus

out = sys.argv[1] if len(sys.argv) > 1 else "profile_out"
quick = os.environ.get("TALUS_EXAMPLE_QUICK") == "1"
scene = talus.Scene.default(set=["simulation.end_time=3"] if quick else [])
sim = talus.Simulation(scene, out=out)
sim.run(progress=False)

fig, ax = plt.subplots(figsize=(7, 3))
bin_width = 4.0
total_volume = 0.0
for name in sim.materials:
    p = sim.particles(name)
    x, volume = p["position"], p["mass"].astype(np.float64) / p["density"]
    total_volume += volume.sum()
    y_mid = np.median(x[:, 1])
    strip = np.abs(x[:, 1] - y_mid) < 20.0  # a 40 m wide strip across the flow
    edges = np.arange(x[:, 0].min(), x[:, 0].max() + bin_width, bin_width)
    v, _ = np.histogram(x[strip, 0], bins=edges, weights=volume[strip])
    thickness = v / (bin_width * 40.0)
    ax.step(edges[:-1] - edges[0], thickness, where="post", label=name)
ax.set(xlabel="distance along x from the westmost particle (m)", ylabel="thickness in the strip (m)")
ax.legend()
fig.tight_layout()
fig.savefig(f"{out}/deposit_profile.png", dpi=120)
print(f"particles' volume at rest {total_volume:.0f} m3; wrote {out}/deposit_profile.png")
