"""A parameter sweep from Python: the default scene (a rock avalanche onto a snow slope) at three
basal frictions, its run-out and flow area plotted against the friction.

    PYTHONPATH=build/python python3 examples/parameter_sweep.py [OUT_DIR]

TALUS_EXAMPLE_QUICK=1 (what CI sets) stops each run after 3 s of simulated time.
"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import talus

out = sys.argv[1] if len(sys.argv) > 1 else "sweep_out"
quick = os.environ.get("TALUS_EXAMPLE_QUICK") == "1"
frictions = [0.3, 0.4, 0.5]
runouts, areas = [], []
for mu in frictions:
    overrides = [f"terrain.friction={mu}"] + (["simulation.end_time=3"] if quick else [])
    scene = talus.Scene.default(set=overrides)
    sim = talus.Simulation(scene, out=f"{out}/mu_{mu}")
    start = sim.particles("rock")["position"].copy()  # world coordinates (m), a copy to keep
    sim.run(progress=False)
    end = sim.particles("rock")["position"]
    # Run-out: the farthest rock particle's horizontal distance from the release's centre.
    centre = start[:, :2].mean(axis=0)
    runouts.append(float(np.max(np.hypot(*(end[:, :2] - centre).T))))
    areas.append(talus.map_stats(f"{out}/mu_{mu}/maps/max_flow_height_vertical.tif", threshold=0.5)["area"])
    print(f"friction {mu}: run-out {runouts[-1]:.0f} m, area of flow heights >= 0.5 m {areas[-1]:.0f} m2")

fig, ax = plt.subplots(1, 2, figsize=(8, 3.2))
ax[0].plot(frictions, runouts, "o-")
ax[0].set(xlabel="basal friction coefficient", ylabel="rock run-out from release centre (m)")
ax[1].plot(frictions, np.array(areas) / 1e4, "s-", color="C1")
ax[1].set(xlabel="basal friction coefficient", ylabel="area with flow height >= 0.5 m (ha)")
fig.tight_layout()
fig.savefig(f"{out}/sweep.png", dpi=120)
# More friction, shorter travel: the sweep's physics in one line.
assert runouts[0] >= runouts[-1], runouts
print(f"wrote {out}/sweep.png")
