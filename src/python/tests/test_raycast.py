"""The Python module against the command line: the same bytes, arrays read
in place, errors naming the field, the safe writer and a free GIL.

Run by CTest (python.pytest) with PYTHONPATH=<build>/python and RAYCAST_CLI
the raycast executable."""
import json
import os
import sys
import subprocess
import threading
import time

import numpy as np
import pytest

import raycast

CLI = os.environ.get("RAYCAST_CLI", "raycast")


def ppm_pixels(data):
    """The (H, W, 3) pixels of a binary PPM."""
    parts = data.split(maxsplit=4)
    assert parts[0] == b"P6" and parts[3] == b"255"
    w, h = int(parts[1]), int(parts[2])
    return np.frombuffer(parts[4], dtype=np.uint8).reshape(h, w, 3)


def cli(tmp_path, *args):
    out = tmp_path / "cli.ppm"
    subprocess.run([CLI, "-q", "-o", str(out), *args], check=True)
    return out.read_bytes()


def cloud(n, seed=1):
    """n spheres whose values are exact in float32 (multiples of 1/64)."""
    rng = np.random.default_rng(seed)
    centers = np.round(rng.uniform([-4, -3, -12], [4, 3, -4], size=(n, 3)) * 64) / 64
    radii = np.round(rng.uniform(0.1, 0.6, size=n) * 64) / 64
    colors = np.round(rng.uniform(0, 1, size=(n, 3)) * 64) / 64
    return centers, radii, colors


def test_builtin_scene_is_the_clis_bytes(tmp_path):
    img = raycast.render("world", width=96, samples=4)
    assert img.shape == (54, 96, 3) and img.dtype == np.uint8
    assert np.array_equal(img, ppm_pixels(cli(tmp_path, "--scene", "world", "--width", "96", "--samples", "4")))


def test_scene_dict_is_the_clis_bytes(tmp_path):
    d = {"camera": {"width": 80, "height": 60, "lookfrom": [0, 1, 2], "lookat": [0, 0, -1], "vfov": 60},
         "sky": {"top": [0.2, 0.4, 0.9]},
         "spheres": [{"center": [0, 0, -1], "radius": 0.5, "shade": "flat", "color": [0.9, 0.3, 0.1]},
                     {"center": [0, -100.5, -1], "radius": 100}]}
    f = tmp_path / "s.json"
    f.write_text(json.dumps(d))
    expected = ppm_pixels(cli(tmp_path, "--scene", str(f)))
    assert np.array_equal(raycast.render(d), expected)
    assert np.array_equal(raycast.render(str(f)), expected)
    assert np.array_equal(raycast.render(f), expected)  # os.PathLike


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("shade", ["normal", "flat"])
def test_arrays_render_as_the_scene_file(tmp_path, dtype, shade):
    centers, radii, colors = cloud(200)
    spheres = [{"center": c.tolist(), "radius": float(r), "shade": shade} for c, r in zip(centers, radii)]
    if shade == "flat":
        for s, col in zip(spheres, colors):
            s["color"] = col.tolist()
    f = tmp_path / "cloud.json"
    f.write_text(json.dumps({"camera": {"width": 120, "height": 80}, "spheres": spheres}))
    expected = ppm_pixels(cli(tmp_path, "--scene", str(f), "--samples", "2"))
    img = raycast.render(width=120, height=80, centers=centers.astype(dtype), radii=radii.astype(dtype),
                         colors=colors.astype(dtype) if shade == "flat" else None, shade=shade, samples=2)
    assert np.array_equal(img, expected)
    # Strided views (every other sphere) and mixed dtypes, in place as well.
    both = np.repeat(centers, 2, axis=0).astype(dtype)[::2]
    img2 = raycast.render(width=120, height=80, centers=both, radii=radii.astype(np.float32),
                          colors=colors if shade == "flat" else None, shade=shade, samples=2)
    assert np.array_equal(img2, expected)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_arrays_are_read_in_place(dtype):
    centers, radii, _ = cloud(10)
    c = np.ascontiguousarray(centers, dtype=dtype)
    raycast.render(width=16, height=9, centers=c, radii=radii.astype(dtype))
    assert raycast._raycast._last_centers_address() == c.ctypes.data
    view = np.asfortranarray(c)  # columns contiguous: still no copy
    raycast.render(width=16, height=9, centers=view, radii=radii)
    assert raycast._raycast._last_centers_address() == view.ctypes.data


def test_float32_output_matches_the_reference_bytes():
    f = raycast.render("normals", width=40, dtype="float32")
    assert f.dtype == np.float32 and f.shape == (22, 40, 3)
    b = raycast.render("normals", width=40)
    assert np.all(np.abs(np.clip(255.999 * f, 0, 255).astype(int) - b.astype(int)) <= 1)


def test_region_is_a_window_of_the_image():
    whole = raycast.render("world", width=64)
    assert np.array_equal(raycast.render("world", width=64, region=(5, 3, 40, 20)), whole[3:20, 5:40])


@pytest.mark.parametrize("kwargs, exc, field", [
    (dict(width=0), ValueError, "camera.width"),
    (dict(vfov=200, lookat=(0, 0, -1)), ValueError, "camera.vfov"),
    (dict(threads=-1), ValueError, "threads"),
    (dict(samples=0), ValueError, "samples"),
    (dict(backend="gpu"), ValueError, "backend"),
    (dict(sampler="halton"), ValueError, "sampler"),
    (dict(region=(0, 0, 1000, 10)), ValueError, "region"),
    (dict(dtype="int16"), ValueError, "dtype"),
    (dict(centers=np.zeros((2, 3)), radii=np.array([1.0, -1.0])), ValueError, "spheres[1].radius"),
    (dict(centers=np.zeros((2, 2)), radii=np.ones(2)), ValueError, "centers"),
    (dict(centers=np.zeros((2, 3)), radii=np.ones(3)), ValueError, "radii"),
    (dict(centers=np.zeros((1, 3)), radii=np.ones(1), shade="glossy"), ValueError, "shade"),
])
def test_errors_name_the_field(kwargs, exc, field):
    with pytest.raises(exc) as e:
        raycast.render(**kwargs)
    assert e.value.field == field
    assert str(e.value).startswith(field + ": ")


def test_keywords_override_the_scenes_keys_as_the_clis_options_do(tmp_path):
    f = tmp_path / "s.json"
    f.write_text(json.dumps({"camera": {"width": 64, "aspect": "2:1", "vup": [0.3, 1, 0]}}))
    # width over the file's: the height follows the file's aspect; lookfrom
    # over the file's: its vup looks down -z from there.
    img = raycast.render(str(f), width=40, lookfrom=(5, 0, 0))
    assert img.shape == (20, 40, 3)
    assert np.array_equal(img, ppm_pixels(cli(tmp_path, "--scene", str(f), "-w", "40", "--lookfrom", "5,0,0")))


@pytest.mark.parametrize("aspect", ["2:1", "2", 2, 2.0, "4:2"])
def test_aspect_spellings_are_the_clis(aspect):
    assert raycast.render(width=32, aspect=aspect).shape == (16, 32, 3)


@pytest.mark.parametrize("kwargs, message", [
    (dict(aspect=" 2:1"), "camera.aspect: ' 2' is not a number"),
    (dict(aspect="16:0"), "camera.aspect: '16:0': both sides of W:H must be positive"),
    (dict(width=0), "camera.width: '0' is too small (at least 1)"),
    (dict(width=16777217), "camera.width: '16777217' is too large (at most 16777216)"),
    (dict(width=64.5), "camera.width: '64.5' is not an integer"),
    (dict(vfov=180), "camera.vfov: '180' is too large (below 180)"),
    (dict(sky_top=(1, 1e31, 1)), "sky.top: component 2: '1e+31' is too large (at most 1e+30)"),
    (dict(vfov=90, viewport_height=2), "camera.viewport_height: give vfov or viewport_height, not both"),
    (dict(samples=0), "samples: '0' is too small (at least 1)"),
])
def test_messages_are_the_input_tables(kwargs, message):
    with pytest.raises(ValueError) as e:
        raycast.render(**kwargs)
    assert str(e.value) == message


def test_other_errors():
    with pytest.raises(TypeError):
        raycast.render(3)
    with pytest.raises(OSError):
        raycast.render("/nonexistent/scene.json")
    with pytest.raises(ValueError) as e:
        raycast.render({"spheres": [{"center": [0, 0, -1], "radius": "big"}]})
    assert e.value.field == "spheres[0].radius"
    with pytest.raises(TypeError):
        raycast.render(centers=np.zeros((1, 3), dtype=np.complex64), radii=np.ones(1))


def test_lit_is_rendered_or_refused_clearly():
    c, r, col = cloud(5)
    try:
        img = raycast.render(width=32, height=18, centers=c, radii=r, colors=col, shade="lit")
    except ValueError as e:
        assert e.field == "shade" and "not supported yet" in str(e)
    else:
        assert img.shape == (18, 32, 3)


def test_write_round_trips_the_clis_ppm(tmp_path):
    img = raycast.render("world", width=96, samples=4)
    out = tmp_path / "py.ppm"
    raycast.write(out, img)
    assert out.read_bytes() == cli(tmp_path, "--scene", "world", "--width", "96", "--samples", "4")


def test_write_png(tmp_path):
    out = tmp_path / "a.png"
    raycast.write(out, raycast.render("red-sphere", width=32))
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_write_errors_leave_nothing(tmp_path):
    img = raycast.render(width=8, height=4)
    with pytest.raises(OSError):
        raycast.write(tmp_path / "missing" / "x.ppm", img)
    keep = tmp_path / "keep.ppm"
    keep.write_bytes(b"old")
    with pytest.raises(ValueError) as e:
        raycast.write(keep, img, format="exr")  # EXR takes float32
    assert e.value.field == "image"
    with pytest.raises(ValueError) as e:
        raycast.write(tmp_path / "noext", img)
    assert e.value.field == "path"
    os.chmod(tmp_path, 0o500)
    try:
        if not os.access(tmp_path, os.W_OK):  # root writes anyway
            with pytest.raises(OSError):
                raycast.write(keep, img)
    finally:
        os.chmod(tmp_path, 0o700)
    assert keep.read_bytes() == b"old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keep.ppm"]  # no temporary left


def test_render_releases_the_gil():
    count = 0
    stop = threading.Event()

    def counter():
        nonlocal count
        while not stop.is_set():
            count += 1

    t = threading.Thread(target=counter)
    t.start()
    try:
        time.sleep(0.01)
        before = count
        start = time.perf_counter()
        centers, radii, _ = cloud(20000)
        raycast.render(width=1280, height=720, centers=centers, radii=radii / 4, samples=16, threads=1)
        took = time.perf_counter() - start
        during = count - before
    finally:
        stop.set()
        t.join()
    assert took > 0.05, took
    # Held, the GIL would let the counter run only at the switch interval's
    # edges (a handful of times); free, it counts all along.
    assert during > 10000, (during, took)


def test_readme_python_example_runs(tmp_path):
    """README.md's Python example, as written, writes its 1280x720 PNG."""
    readme = open(os.path.join(os.path.dirname(__file__), "..", "..", "..", "README.md")).read()
    section = readme[readme.index("## Python"):]
    block = section[section.index("```python\n") + len("```python\n"):]
    block = block[:block.index("```")]
    assert len(block.strip().splitlines()) <= 10
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        exec(compile(block, "README.md", "exec"), {})
    finally:
        os.chdir(cwd)
    png = (tmp_path / "cloud.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert int.from_bytes(png[16:20], "big") == 1280 and int.from_bytes(png[20:24], "big") == 720


def test_orthographic_is_the_clis_bytes(tmp_path):
    img = raycast.render("world", width=160, projection="orthographic", viewport_height=3)
    out = tmp_path / "o.ppm"
    subprocess.run([CLI, "--scene", "world", "-w", "160", "--projection", "orthographic",
                    "--viewport-height", "3", "-o", str(out)], check=True)
    assert img.tobytes() == out.read_bytes()[-img.size:]
    with pytest.raises(ValueError) as e:
        raycast.render("world", projection="orthographic", vfov=30)
    assert "means nothing with" in str(e.value)


def test_light_shadows_and_ao_are_the_clis_bytes(tmp_path):
    img = raycast.render("lit-world", width=160, light=(1, 1, 0.5), shadows=True, ao=4, ao_distance=2)
    out = tmp_path / "l.ppm"
    subprocess.run([CLI, "--scene", "lit-world", "-w", "160", "--light", "1,1,0.5", "--shadows", "--ao", "4",
                    "--ao-distance", "2", "-o", str(out)], check=True)
    assert img.tobytes() == out.read_bytes()[-img.size:]
    assert img.tobytes() != raycast.render("lit-world", width=160, light=(1, 1, 0.5), shadows=False).tobytes()
    with pytest.raises(ValueError) as e:
        raycast.render("lit-world", shadows=True)
    assert e.value.field == "light.shadows" and "needs a directional light" in str(e.value)


@pytest.mark.parametrize("kwargs, exc, message", [
    # The binding layer's types never show: every keyword is parsed as the command line's.
    (dict(seed=-1), ValueError, "seed: '-1' is not a whole number from 0 to 18446744073709551615"),
    (dict(threads="x"), ValueError, "threads: 'x' is not an integer"),
    (dict(samples=2.5), ValueError, "samples: '2.5' is not an integer"),
    (dict(width=True), ValueError, "camera.width: 'true' is not an integer"),
    # Nothing is cut or coerced that the command line would refuse.
    (dict(region=(0, 0, 10.5, 10)), ValueError, "region: number 3: '10.5' is not an integer"),
    (dict(lookfrom=(1, 2)), ValueError, "camera.lookfrom: '1,2' has 2 component(s), want 3 (x,y,z)"),
    (dict(lookfrom=[[1, 2, 3]]), TypeError, "camera.lookfrom: want a number, a str or a flat sequence, got list"),
    (dict(vfov=object()), TypeError, "camera.vfov: want a number or a str, got object"),
    (dict(centers=np.zeros((1, 3)), radii=np.array([True])), TypeError, "radii: want real numbers, got dtype bool"),
    (dict(shade=3), ValueError, "shade: '3' is not one of normal, flat, lit"),
    # Names: the nearest one suggested, as on the command line.
    (dict(backend="avx"), ValueError,
     "backend: 'avx' is not one of auto, reference, scalar, sse2, avx2, avx512, neon; did you mean avx2?"),
    (dict(scene="wrld"), ValueError, "scene: 'wrld' is not one of sky, red-sphere, normals, world, lit-world, "
                                     "a .json scene file or a particle file (LAMMPS dump, extended XYZ, GSD, PLY); did you mean world?"),
    (dict(dtype="float"), ValueError, "dtype: 'float' is not one of uint8, float32; did you mean float32?"),
    # Colours with a shading that cannot show them.
    (dict(centers=np.zeros((2, 3)) - [0, 0, 2], radii=np.ones(2), colors=np.ones((2, 3)), shade="normal"), ValueError,
     'colors: normal shading shows no colours (give shade="lit" or "flat", or no colors)'),
])
def test_mistakes_are_answered_in_the_command_lines_words(kwargs, exc, message):
    with pytest.raises(exc) as e:
        raycast.render(width=8, **kwargs) if "width" not in kwargs else raycast.render(**kwargs)
    assert str(e.value) == message
    assert e.value.field == message.split(":")[0]


def test_numpy_numbers_in_a_dict_scene_are_jsons():
    d = {"camera": {"width": np.int64(32), "vfov": np.float32(60)},
         "spheres": [{"center": np.array([0.0, 0.0, -1.0]), "radius": np.float64(0.5)}]}
    plain = {"camera": {"width": 32, "vfov": 60.0}, "spheres": [{"center": [0, 0, -1], "radius": 0.5}]}
    assert np.array_equal(raycast.render(d), raycast.render(plain))
    with pytest.raises(TypeError) as e:
        raycast.render({"spheres": [{"center": {1, 2, 3}, "radius": 1}]})
    assert e.value.field == "scene"


def test_a_dash_writes_a_ppm_to_standard_output(tmp_path):
    script = ("import raycast; raycast.write('-', raycast.render('world', width=96, samples=4))")
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, env=dict(os.environ), check=True)
    assert p.stdout == cli(tmp_path, "--scene", "world", "--width", "96", "--samples", "4")
    assert not os.path.exists("-")
    with pytest.raises(ValueError) as e:
        raycast.write("-", raycast.render(width=8), format="png")
    assert str(e.value) == "format: standard output takes ppm only, got png"


def test_a_file_that_cannot_be_read_is_oserror_and_bad_text_valueerror(tmp_path):
    with pytest.raises(OSError) as e:
        raycast.render(tmp_path / "missing.json")
    assert str(e.value) == f"scene: {tmp_path / 'missing.json'}: No such file or directory" and e.value.kind == "io"
    bad = tmp_path / "bad.json"
    bad.write_text('{"spheres": [{"center": [0, 0, -1], "radius": 1},, ]}')
    with pytest.raises(ValueError) as e:
        raycast.render(bad)
    assert e.value.field == "scene" and str(e.value).startswith(f"scene: {bad}: not valid JSON")
