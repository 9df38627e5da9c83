#!/usr/bin/python3
"""Runs a Jupyter notebook's code cells in order, as a reader running it top
to bottom would, in a scratch directory (matplotlib without a display), and
fails on the first cell that raises.

    run_notebook.py NOTEBOOK.ipynb

Every file a cell names in savefig("...") must exist afterwards and be
non-empty. Exit 0 when every cell ran."""
import json
import os
import re
import sys
import tempfile
import traceback

path = os.path.abspath(sys.argv[1])
cells = [c for c in json.load(open(path))["cells"] if c["cell_type"] == "code"]
os.environ.setdefault("MPLBACKEND", "Agg")
with tempfile.TemporaryDirectory(prefix="raycast-notebook-") as scratch:
    os.chdir(scratch)
    scope = {"__name__": "__main__"}
    for k, cell in enumerate(cells):
        source = "".join(cell["source"])
        try:
            exec(compile(source, f"{path} cell {k + 1}", "exec"), scope)
        except Exception:
            print(f"{path}: cell {k + 1} failed:\n{source}\n", file=sys.stderr)
            traceback.print_exc()
            sys.exit(1)
        for name in re.findall(r'savefig\("([^"]+)"', source):
            if not os.path.getsize(name):
                print(f"{path}: cell {k + 1} wrote an empty {name}", file=sys.stderr)
                sys.exit(1)
    print(f"{path}: {len(cells)} cells ran")
