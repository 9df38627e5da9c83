"""raycast: Ray Tracing in One Weekend's sky and spheres, rendered on the
fastest vector unit this CPU has, into NumPy arrays.

    import numpy as np, raycast
    img = raycast.render("world", width=320, samples=16)      # (180, 320, 3) uint8
    raycast.write("world.png", img)

Errors are ValueError / TypeError / OSError whose message names the field
("camera.vfov: ...", "spheres[3].radius: ...", "threads: ..."); raycast's own
also carry .field, .message and .kind.
"""
import json as _json
import os as _os
import sys as _sys

import numpy as _np

from . import _raycast

__all__ = ["render", "write", "frames", "builtin_scenes"]


def builtin_scenes():
    """The built-in scene names, as the command line's --scene takes them."""
    return list(_raycast.builtin_scene_names())


def _type_error(field, message):
    """TypeError with .field, .message and .kind, as the library's ValueError."""
    e = TypeError(f"{field}: {message}")
    e.field, e.message, e.kind = field, message, "invalid_argument"
    return e


def _spheres_array(name, a, colours=False):
    """a as the library reads it in place: float32 or float64 (uint8 too for
    colours, read as value / 255); other real dtypes converted once."""
    if a is None:
        return None
    a = _np.asarray(a)
    if colours and a.dtype == _np.uint8:
        return a
    if a.dtype not in (_np.float32, _np.float64):
        if a.dtype.kind not in "iuf":
            raise _type_error(name, f"want real numbers, got dtype {a.dtype}")
        a = a.astype(_np.float64)  # integers and the like: converted once
    return a


def _type_map(name, v):
    """A dict of type -> radius or colour as the command line spells it:
    1=0.5,2=0.35 or Cu=#b87333."""
    if not isinstance(v, dict):
        return v
    def colour(c):
        if isinstance(c, str):
            return c
        r, g, b = (float(x) for x in c)
        return "#%02x%02x%02x" % tuple(int(round(255 * min(max(x, 0.0), 1.0))) for x in (r, g, b))
    return ",".join(f"{k}={colour(x) if name == 'type_color' else _scalar_token(name, x)}" for k, x in v.items())


def _atoms_arrays(atoms):
    """Anything shaped like an ASE Atoms (positions, numbers, cell) as
    particle arrays: types by element, the cell's box framed."""
    from . import _raycast as _r
    positions = _spheres_array("atoms", getattr(atoms, "positions", None))
    numbers = _np.asarray(getattr(atoms, "numbers", None))
    if positions is None or numbers.ndim != 1 or len(numbers) != len(positions):
        raise _type_error("atoms", "want an object with positions (N, 3) and numbers (N,), as ase.Atoms")
    zs, types = _np.unique(numbers, return_inverse=True)
    d = dict(centers=positions, types=types.astype(_np.int32), type_names=[_r.element_symbol(int(z)) for z in zs])
    cell = getattr(atoms, "cell", None)
    cell = _np.asarray(getattr(cell, "array", cell), dtype=float) if cell is not None else None
    if cell is not None and cell.shape == (3, 3) and _np.any(cell):
        d["cell"] = ((0.0, 0.0, 0.0), tuple(cell[0]), tuple(cell[1]), tuple(cell[2]))
    return d


def _scalar_token(name, v):
    if isinstance(v, str):
        return v
    if isinstance(v, (bool, _np.bool_)):
        return "true" if v else "false"
    if isinstance(v, (int, _np.integer)):
        return str(int(v))
    if isinstance(v, (float, _np.floating)):
        return repr(float(v))
    raise _type_error(name, f"want a number or a str, got {type(v).__name__}")


def _token(name, v):
    """A keyword's value as the command line would spell it, for the input
    table's parsers: the same spellings, ranges and messages. Nothing is
    rounded or coerced here: 10.5 for a whole number, True for a number or
    (1, 2) for x, y, z reach the parser as given and are refused there."""
    if isinstance(v, _np.ndarray) and v.ndim == 0:
        v = v.item()
    if isinstance(v, dict):
        return _type_map(name, v)
    if isinstance(v, str) or not hasattr(v, "__len__"):
        return _scalar_token(name, v)
    if isinstance(v, (bytes, dict)) or _np.ndim(v) != 1:
        raise _type_error(name, f"want a number, a str or a flat sequence, got {type(v).__name__}")
    return ",".join(_scalar_token(name, x) for x in v)


def _json_value(v):
    """NumPy's numbers and arrays inside a dict scene, as JSON's."""
    if isinstance(v, (_np.generic, _np.ndarray)):
        return v.tolist()
    raise _type_error("scene", f"a {type(v).__name__} is not a JSON value")


# The input table's keywords that render() takes (path and format are write()'s).
_TABLE = _raycast.input_table()
_RENDER_KEYWORDS = tuple(r["keyword"] for r in _TABLE if r["keyword"] and r["keyword"] not in ("format", "path"))
# What errors name: a scene file's key where the keyword has one (camera.vfov).
_FIELD = {r["keyword"]: r["file_key"] or r["keyword"] for r in _TABLE}


def _names(keyword):
    return ", ".join(f'"{n}"' for r in _TABLE if r["keyword"] == keyword for n in r["names"])


def render(scene=None, *, frame=None, atoms=None, centers=None, radii=None, colors=None, shade=None,
           width=None, height=None, aspect=None, lookfrom=None, lookat=None, vup=None,
           vfov=None, viewport_height=None, focal_length=None, projection=None, sky_bottom=None, sky_top=None,
           light=None, shadows=None, ao=None, ao_distance=None, radius=None, type_radius=None, type_color=None,
           color_by=None, colormap=None, color_range=None, view=None, backend="auto", precision="exact",
           threads=0, samples=1, sampler="sobol", seed=0, region=None, dtype="uint8"):
    """Render a scene; returns a numpy.ndarray of shape (H, W, 3), rows top first.

    scene: None (the sky alone), a built-in name (<scenes>), a path (str or
        os.PathLike) to a .json scene file or a particle file (a LAMMPS dump,
        extended XYZ, GSD or PLY file, told by its content), as the command
        line's --scene takes them, or a dict with a scene file's keys
        ({"camera": {...}, "sky": {...}, "spheres": [{"center": [x, y, z],
        "radius": r}, ...]}; NumPy numbers and arrays in it are read as JSON's).
    frame: a trajectory's frame (negative: from the end); its first by default.
        A particle file without a camera is framed as OVITO frames it: its
        box whole in the picture, seen from a corner (view: <views>), the
        camera its first frame's.
    atoms: anything shaped like an ASE Atoms (positions, numbers, cell):
        its atoms by element (van der Waals radii, Jmol's colours), framed.
    centers (N, 3), radii (N,), colors (N, 3): spheres as arrays, for a scene
        without spheres of its own. float32 and float64 arrays are read in
        place, whatever their strides (no copy); colors also as uint8 (0-255,
        read as value / 255); other dtypes are converted once. radius=R
        instead of radii gives every sphere R. They must not change during
        the call.
    shade: "normal" (0.5 (N + 1)), "flat" or "lit" (both show colours) for
        every sphere; by default lit where there are colours (colors,
        color_by, types), else normal. colors= with shade="normal" is refused.
    color_by: a column of a particle file (or "type", "element"), or an array
        (N,) for the arrays' spheres, shown through colormap (<colormaps>)
        over color_range ((lo, hi), or ("p1", "p99") in percentiles; default
        the values' min and max). type_radius, type_color: {type: radius},
        {type: "#rrggbb" or (r, g, b)}, a type as the file names it.
    width, height, aspect (a number or "W:H"), lookfrom, lookat, vup, vfov
        (degrees), viewport_height, focal_length, projection (<projections>;
        orthographic: parallel rays from an image plane through lookfrom,
        viewport_height high; vfov and focal_length then mean nothing),
        sky_bottom, sky_top: override the scene's camera and sky, as the
        command line's options do.
    light (x, y, z toward a directional light), shadows (True: hard shadows
        from it), ao (ambient occlusion rays per hit, 0 to 4096), ao_distance
        (how far they look; unbounded by default): how "lit" spheres are lit,
        over the scene's "light" and "ambient_occlusion" keys.
    backend: <backends>.
    precision: <precisions>. threads: 0 for all cores.
    samples, sampler (<samplers>), seed: antialiasing.
    region: (x0, y0, x1, y1), the pixels x0 <= x < x1, y0 <= y < y1 (y0 = 0
        at the top) of the image; the result is that window.
    dtype: "uint8" (the command line's bytes) or "float32" (linear colour).

    Every keyword of the command line's (its option with _ for -) is parsed
    as the command line parses it: the same values are accepted and refused
    with the same words, and nothing is rounded or coerced (10.5 for a whole
    number, True for a number). The GIL is released while rendering. Raises
    ValueError (a value out of range, an unknown name), TypeError (a wrong
    type) or OSError (a scene file that cannot be read); each has .field
    naming the keyword or the scene file's key.
    """
    kind, source = _scene_source(scene)
    if not isinstance(dtype, str):
        raise _type_error("dtype", f"want a str, got {type(dtype).__name__}")
    if frame is not None and (isinstance(frame, bool) or not isinstance(frame, (int, _np.integer))):
        raise _type_error("frame", f"want an int, got {type(frame).__name__}")
    particles = _particle_arrays(scene, atoms, centers, radii, colors, color_by, shade, radius)
    if particles is not None and isinstance(color_by, _np.ndarray):
        color_by = "color_by"  # the arrays' column of that name
    given = dict(width=width, height=height, aspect=aspect, lookfrom=lookfrom, lookat=lookat, vup=vup,
                 vfov=vfov, viewport_height=viewport_height, focal_length=focal_length,
                 projection=projection, sky_bottom=sky_bottom, sky_top=sky_top, light=light, shadows=shadows,
                 ao=ao, ao_distance=ao_distance, radius=radius, type_radius=type_radius, type_color=type_color,
                 color_by=color_by, colormap=colormap, color_range=color_range, shade=shade, view=view,
                 backend=backend, precision=precision, threads=threads, samples=samples, sampler=sampler,
                 seed=seed, region=region, frame=None)
    keywords = {k: _token(_FIELD[k], given[k]) for k in _RENDER_KEYWORDS if given[k] is not None}
    return _raycast.render(kind, source, None if frame is None else int(frame), particles, keywords, dtype)


def _scene_source(scene):
    """(kind, source) of render's scene= for the module: none, a dict's JSON text, or a name or path."""
    if scene is None:
        return "", ""
    if isinstance(scene, dict):
        return "json", _json.dumps(scene, default=_json_value)
    if isinstance(scene, (str, _os.PathLike)):
        return "name", _os.fspath(scene)  # a built-in name or a file, as --scene
    raise _type_error("scene", f"want a name, a path or a dict, got {type(scene).__name__}")


def _particle_arrays(scene, atoms, centers, radii, colors, color_by, shade, radius):
    """The arrays of render()'s particles, for the C++ half, or None."""
    if atoms is not None:
        if scene is not None or centers is not None:
            raise _type_error("atoms", "give atoms, or centers, or a scene, not two of them")
        d = _atoms_arrays(atoms)
        d["framed"] = True
    elif centers is not None or radii is not None or colors is not None:
        if centers is None or (radii is None and radius is None):
            field = "centers" if centers is None else "radii"
            e = ValueError(f"{field}: is required with centers/radii/colors (radius=R gives every sphere R)")
            e.field, e.message, e.kind = field, e.args[0][len(field) + 2:], "invalid_argument"
            raise e
        if scene is not None and not isinstance(scene, str):
            raise _type_error("centers", "the arrays are the scene's spheres: give no scene with them")
        d = dict(centers=_spheres_array("centers", centers), framed=False)
        if radii is not None:
            d["radii"] = _spheres_array("radii", radii)
        if colors is not None:
            d["colors"] = _spheres_array("colors", colors, colours=True)
    else:
        if isinstance(color_by, _np.ndarray):
            raise _type_error("color_by", "an array colours the arrays' spheres (centers=...); give a column's name")
        return None
    if colors is not None and shade == "normal":
        e = ValueError("colors: normal shading shows no colours (give shade=\"lit\" or \"flat\", or no colors)")
        e.field, e.message, e.kind = "colors", e.args[0][8:], "invalid_argument"
        raise e
    if isinstance(color_by, _np.ndarray) or isinstance(color_by, (list, tuple)):
        d["color_by"] = _spheres_array("color_by", color_by)
    return d


def frames(path):
    """Each frame of a particle file (a LAMMPS dump, extended XYZ, GSD or PLY
    file) as a dict of NumPy arrays: positions (N, 3), and where the file
    gives them radii (N,), colors (N, 3), types (N,) with type_names, cell
    (origin, a, b, c, pbc), timestep, and properties {name: array}. The
    arrays view the file's memory where its layout allows (no copy; GSD's,
    PLY's), and are read-only. Frames are read one at a time: memory is one
    frame's."""
    if not isinstance(path, (str, _os.PathLike)):
        raise _type_error("path", f"want a str or os.PathLike, got {type(path).__name__}")
    t = _raycast.trajectory(_os.fspath(path))
    for k in range(len(t)):
        yield t.read(k)


def write(path, image, format=""):
    """Write an (H, W, 3) image from render() to path, as the command line does.

    The format comes from the extension (.png, .ppm/.pnm, .jpg/.jpeg,
    .tif/.tiff, .exr) unless format names one; uint8 for all but EXR, which
    takes float32. The file is written under a temporary name and renamed
    into place: an error (OSError, ValueError) leaves path as it was. "-"
    writes a binary PPM to standard output, as the command line's -o -.
    """
    if not isinstance(path, (str, _os.PathLike)) or isinstance(_os.fspath(path), bytes):
        raise _type_error("path", f"want a str or os.PathLike, got {type(path).__name__}")
    if not isinstance(format, str):
        raise _type_error("format", f"want a str, got {type(format).__name__}")
    path = _os.fspath(path)
    image = _np.asarray(image)
    if image.ndim == 3 and image.dtype in (_np.uint8, _np.float32):
        image = _np.ascontiguousarray(image)
    if path == "-":
        _sys.stdout.flush()  # what Python printed comes first
    _raycast.write(path, image, format)


if render.__doc__:  # (python -OO drops docstrings)
    render.__doc__ = (render.__doc__.replace("<scenes>", ", ".join(f'"{n}"' for n in builtin_scenes()))
                      .replace("<projections>", _names("projection")).replace("<backends>", _names("backend"))
                      .replace("<precisions>", _names("precision")).replace("<samplers>", _names("sampler"))
                      .replace("<colormaps>", _names("colormap")).replace("<views>", _names("view")))
