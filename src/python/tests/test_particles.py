"""The Python module over particle data: a trajectory's frames as arrays
(frames(), viewing the file's memory), one frame rendered (render(path,
frame=K)) with the command line's bytes, anything shaped like an ASE Atoms,
and arrays coloured as people colour them (color_by=, radius=, uint8
colours). The files are the fixture's, written by LAMMPS, ASE and gsd."""
import os
import subprocess

import numpy as np
import pytest

import raycast

FILES = os.environ.get("RAYCAST_FORMATS_FILES", "")
CLI = os.environ.get("RAYCAST_CLI", "raycast")
needs_files = pytest.mark.skipif(not os.path.isdir(FILES), reason="the formats fixture's files are not here")


def cli(tmp_path, *args):
    out = tmp_path / "cli.ppm"
    subprocess.run([CLI, "-q", *args, "-o", str(out)], check=True)
    data = out.read_bytes()
    return data


def as_ppm(img):
    h, w, _ = img.shape
    return b"P6\n%d %d\n255\n" % (w, h) + img.tobytes()


@needs_files
def test_frames_yields_each_frame_as_arrays():
    frames = list(raycast.frames(os.path.join(FILES, "melt.dump")))
    assert len(frames) == 5
    f = frames[0]
    assert f["positions"].shape == (f["types"].shape[0], 3)
    assert f["type_names"] == ["1", "2"]
    assert set(f["properties"]) >= {"id", "vx", "c_pe"}
    assert not f["positions"].flags.writeable
    assert frames[-1]["positions"].shape[0] < f["positions"].shape[0]  # atoms deleted on the way
    g = next(raycast.frames(os.path.join(FILES, "melt.gsd")))
    assert g["positions"].dtype == np.float32 and g["positions"].base is not None  # the file's memory, no copy


@needs_files
def test_a_frame_renders_the_command_lines_bytes(tmp_path):
    path = os.path.join(FILES, "melt.dump.gz")
    for k in (0, 2, -1):
        img = raycast.render(path, frame=k, color_by="c_pe", colormap="plasma")
        assert as_ppm(img) == cli(tmp_path, "--scene", path, "--frames", str(k), "--color-by", "c_pe",
                                  "--colormap", "plasma")
    with pytest.raises(ValueError) as e:
        raycast.render(path, frame=7)
    assert e.value.field == "frame" and "beyond the file's 5 frames" in str(e.value)
    with pytest.raises(ValueError) as e:
        raycast.render("world", frame=0)
    assert e.value.field == "frame"


@needs_files
def test_atoms_render_as_the_files_elements(tmp_path):
    ase_io = pytest.importorskip("ase.io")
    atoms = ase_io.read(os.path.join(FILES, "same.extxyz"))
    img = raycast.render(atoms=atoms, radius=0.2, shade="normal")
    # ASE's Atoms keeps no cell origin; its cell [0, 3] is framed, the same
    # picture as the file's box moved there.
    assert img.shape == (225, 400, 3) and (img[..., 2] != 255).sum() > 1000
    lit = raycast.render(atoms=atoms, type_radius={"Ar": 0.1, "Kr": 0.3})
    assert not np.array_equal(lit, img)


def test_arrays_are_coloured_as_particle_files_are():
    rng = np.random.default_rng(4)
    centers = rng.uniform([-1, -1, -4], [1, 1, -3], size=(300, 3))
    values = centers[:, 2].copy()
    by_column = raycast.render(centers=centers, radius=0.05, color_by=values, colormap="coolwarm", width=96)
    rgb = np.zeros((300, 3), dtype=np.uint8)
    rgb[:, 0] = 255
    red = raycast.render(centers=centers, radius=0.05, colors=rgb, width=96)  # uint8: value / 255, lit
    as_float = raycast.render(centers=centers, radius=0.05, colors=rgb / 255.0, width=96)
    assert np.array_equal(red, as_float)
    assert not np.array_equal(by_column, red)
    with pytest.raises(ValueError) as e:
        raycast.render(centers=centers, radius=0.05, colors=rgb, shade="normal")
    assert e.value.field == "colors"
