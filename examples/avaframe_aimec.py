"""An AvaFrame folder run from Python and its AIMEC figures against AvaFrame's com1DFA.

    PYTHONPATH=build/python python3 examples/avaframe_aimec.py [OUT_DIR]

Runs data/scenes/wolfsgruben_avaframe.toml (the avaWog folder from ../shared/data, AvaFrame test
data, "Datenquelle: Land Tirol - data.tirol.gv.at", CC BY), then compares the peak flow thickness
with com1DFA's reference along the folder's AIMEC path: run-out, its difference, and the areas.
Exits with 77 (CTest's "skipped") and a message when ../shared is not beside the project.
"""
import glob
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

import talus

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
folder = os.path.join(root, "..", "shared", "data", "avaframe_avaWog")
if not os.path.isdir(folder):
    print(f"skipped: {folder} is not there (the AvaFrame test data beside the project)")
    sys.exit(77)
out = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "aimec_out")

scene = talus.Scene(os.path.join(root, "data", "scenes", "wolfsgruben_avaframe.toml"))
result = talus.Simulation(scene, out=out).run(progress=False)
ours = glob.glob(os.path.join(out, "peakFiles", "*_pft.asc"))[0]
reference = glob.glob(os.path.join(folder, "reference_com1DFA_*", "*_pft.asc"))[0]
a = talus.aimec(ours, reference, os.path.join(folder, "Inputs", "LINES", "path_aimec.shp"), threshold=1.0,
                dem=os.path.join(folder, "Inputs", "avaWog.asc"))
print(f"run-out along the path: Talus {a['s_runout']:.0f} m, com1DFA {a['s_runout_reference']:.0f} m "
      f"(difference {a['runout_difference']:+.0f} m)")
print(f"areas of pft >= 1 m: true positive {a['true_positive_area']:.0f} m2, false positive "
      f"{a['false_positive_area']:.0f} m2, false negative {a['false_negative_area']:.0f} m2")

fig, ax = plt.subplots(figsize=(7, 3))
ax.plot(a["s"], a["cross_max"], label="Talus (MPM)")
ax.plot(a["s"], a["cross_max_reference"], label="AvaFrame com1DFA")
ax.axhline(1.0, color="grey", lw=0.5)
ax.set(xlabel="s along the AIMEC path (m)", ylabel="peak flow thickness, cross-section max (m)")
ax.legend()
fig.tight_layout()
fig.savefig(os.path.join(out, "aimec_profile.png"), dpi=120)
print(f"{result['steps']} steps in {result['wall_seconds']:.1f} s; wrote {out}/aimec_profile.png")
