"""Runs a notebook's code cells in order as one script (what CI does with examples/*.ipynb:
Debian's Jupyter is not needed for it). Usage: run_notebook.py NOTEBOOK"""
import json
import sys

notebook = json.load(open(sys.argv[1]))
scope = {"__name__": "__main__"}
for i, cell in enumerate(notebook["cells"]):
    if cell["cell_type"] == "code":
        exec(compile("".join(cell["source"]), f"{sys.argv[1]}[cell {i}]", "exec"), scope)
print(f"{sys.argv[1]}: every code cell ran")
