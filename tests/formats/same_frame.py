"""The same frame in every format, each by its own writer: LAMMPS's dump
(in.same, written by lmp), ASE's extended XYZ and gsd's HOOMD GSD from it.

  same_frame.py DIR       (DIR holds same.lammpstrj)
Writes same.extxyz and same.gsd beside it."""
import os
import sys

import numpy as np
import ase.io
import gsd.hoomd

d = sys.argv[1]
atoms = ase.io.read(os.path.join(d, "same.lammpstrj"), format="lammps-dump-text")
atoms.info["Origin"] = np.array([-1.5, -1.5, -1.5])  # the box's lower corner, as OVITO writes it (ASE keeps no origin)
ase.io.write(os.path.join(d, "same.extxyz"), atoms, format="extxyz")
symbols = atoms.get_chemical_symbols()
types = sorted(set(symbols))
frame = gsd.hoomd.Frame() if hasattr(gsd.hoomd, "Frame") else gsd.hoomd.Snapshot()
frame.particles.N = len(atoms)
frame.particles.position = atoms.positions.astype(np.float32)
frame.particles.types = types
frame.particles.typeid = np.array([types.index(s) for s in symbols], dtype=np.uint32)
frame.configuration.box = [3.0, 3.0, 3.0, 0.0, 0.0, 0.0]
with gsd.hoomd.open(os.path.join(d, "same.gsd"), "wb") as f:
    f.append(frame)
