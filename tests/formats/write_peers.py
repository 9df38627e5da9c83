"""Writes the formats tests' peer files with the real writers: ASE's extended
XYZ writer and the gsd package's HOOMD writer, from LAMMPS's own dump.

  write_peers.py DIR

DIR holds melt-elements.lammpstrj (in.melt's dump with element symbols).
Written there:
  melt.extxyz   every frame of the dump, by ase.io.write(format="extxyz"):
                species, positions, Lattice, Origin (the box's lower corner),
                pbc, step
  melt.gsd      the same frames by gsd.hoomd (HOOMD's schema): positions
                shifted into HOOMD's box centred on the origin, types,
                typeids, the box, the step
  inherit.gsd   three frames for the schema's inheritance: frame 0 has every
                chunk; frame 1 changes only positions and the step (gsd.hoomd
                leaves out what equals frame 0's); frame 2 has six particles,
                not four, and neither diameters nor typeids (the defaults)
  v1.gsd        gsd's own file of its 1.0 file layer (its test suite's,
                test_gsd_v1.gsd, written by gsd 1.x; no schema), and
  v1_chunks.txt what gsd.fl reads of it: "frame name value" a chunk (each an
                int32)
Positions are rounded to float32 first, as GSD stores them, so that every
file holds the same numbers.
"""
import os
import shutil
import sys

import numpy as np
import ase
import ase.io
import gsd
import gsd.fl
import gsd.hoomd


def dump_frames(path):
    """The frames of a LAMMPS custom dump with columns id element x y z."""
    lines = open(path).read().split("\n")
    frames, i = [], 0
    while i < len(lines) and lines[i].startswith("ITEM: TIMESTEP"):
        step = int(lines[i + 1])
        n = int(lines[i + 3])
        flags = lines[i + 4].split()[3:]
        lo, hi = [], []
        for d in range(3):
            a, b = lines[i + 5 + d].split()[:2]
            lo.append(float(a))
            hi.append(float(b))
        assert lines[i + 8].split()[2:] == ["id", "element", "x", "y", "z"]
        rows = [r.split() for r in lines[i + 9:i + 9 + n]]
        symbols = [r[1] for r in rows]
        pos = np.array([[float(v) for v in r[2:5]] for r in rows]).astype(np.float32)
        frames.append(dict(step=step, lo=np.array(lo), hi=np.array(hi), pbc=[f == "pp" for f in flags],
                           symbols=symbols, pos=pos))
        i += 9 + n
    return frames


def write_extxyz(frames, path):
    images = []
    for f in frames:
        a = ase.Atoms(symbols=f["symbols"], positions=f["pos"].astype(np.float64),
                      cell=np.diag(f["hi"] - f["lo"]), pbc=f["pbc"])
        a.info["Origin"] = f["lo"]
        a.info["step"] = f["step"]
        images.append(a)
    ase.io.write(path, images, format="extxyz")


def write_gsd(frames, path):
    types = sorted(set(s for f in frames for s in f["symbols"]))
    with gsd.hoomd.open(path, "wb") as t:
        for f in frames:
            s = gsd.hoomd.Snapshot()
            s.configuration.step = f["step"]
            length = f["hi"] - f["lo"]
            s.configuration.box = [length[0], length[1], length[2], 0, 0, 0]
            s.particles.N = len(f["symbols"])
            s.particles.types = types
            s.particles.typeid = [types.index(x) for x in f["symbols"]]
            centre = (f["lo"] + length / 2).astype(np.float32)
            s.particles.position = f["pos"] - centre
            t.append(s)


def write_inherit(path):
    with gsd.hoomd.open(path, "wb") as t:
        s = gsd.hoomd.Snapshot()
        s.configuration.step = 100
        s.configuration.box = [10, 12, 14, 0.5, 0.25, -0.5]
        s.particles.N = 4
        s.particles.types = ["A", "B", "C"]
        s.particles.typeid = [0, 2, 1, 2]
        s.particles.diameter = [1.0, 2.0, 0.5, 3.0]
        s.particles.position = [[0, 0, 0], [1, 2, 3], [-1, -2, -3], [4, 0, -4]]
        s.particles.velocity = [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]]
        t.append(s)
        s.configuration.step = 200
        s.particles.position = [[0.5, 0, 0], [1.5, 2, 3], [-0.5, -2, -3], [4.5, 0, -4]]
        t.append(s)
        u = gsd.hoomd.Snapshot()
        u.configuration.step = 300
        u.particles.N = 6
        u.particles.position = [[k, k, k] for k in range(6)]
        t.append(u)


def write_v1(d):
    src = os.path.join(os.path.dirname(gsd.__file__), "test", "test_gsd_v1.gsd")
    if not os.path.exists(src):
        return
    shutil.copyfile(src, d + "/v1.gsd")
    with gsd.fl.open(name=d + "/v1.gsd", mode="rb") as f, open(d + "/v1_chunks.txt", "w") as out:
        for k in range(f.nframes):
            for name in f.find_matching_chunk_names(""):
                if f.chunk_exists(frame=k, name=name):
                    data = f.read_chunk(frame=k, name=name)
                    assert data.dtype == np.int32 and data.shape == (1,)
                    out.write(f"{k} {name} {int(data[0])}\n")


if __name__ == "__main__":
    d = sys.argv[1]
    frames = dump_frames(d + "/melt-elements.lammpstrj")
    write_extxyz(frames, d + "/melt.extxyz")
    write_gsd(frames, d + "/melt.gsd")
    write_inherit(d + "/inherit.gsd")
    write_v1(d)
