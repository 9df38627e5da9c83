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

import numpy as _np

from . import _raycast

__all__ = ["render", "write", "builtin_scenes"]


def builtin_scenes():
    """The built-in scene names: sky, red-sphere, normals, world."""
    return list(_raycast.builtin_scene_names())


def _spheres_array(name, a):
    if a is None:
        return None
    a = _np.asarray(a)
    if a.dtype not in (_np.float32, _np.float64):
        if a.dtype.kind not in "biuf":
            raise TypeError(f"{name}: want real numbers, got dtype {a.dtype}")
        a = a.astype(_np.float64)  # integers and the like: converted once
    if 0 in a.strides:
        a = _np.ascontiguousarray(a)  # broadcast rows: the library reads real ones
    return a


def _token(name, v):
    """A keyword's value as the command line would spell it, for the input
    table's parsers (the same spellings, ranges and messages)."""
    if isinstance(v, str):
        return v
    if isinstance(v, (bool, _np.bool_)):
        return "true" if v else "false"
    if isinstance(v, (int, _np.integer)) and not isinstance(v, bool):
        return str(int(v))
    try:
        return repr(float(v))
    except TypeError:
        pass
    t = [repr(float(x)) for x in v]
    if len(t) != 3:
        raise ValueError(f"{name}: want 3 numbers, got {len(t)}")
    return ",".join(t)


_CAMERA_KEYWORDS = ("width", "height", "aspect", "lookfrom", "lookat", "vup", "vfov", "viewport_height",
                    "focal_length", "projection", "sky_bottom", "sky_top", "light", "shadows", "ao",
                    "ao_distance")


def render(scene=None, *, centers=None, radii=None, colors=None, shade="normal",
           width=None, height=None, aspect=None, lookfrom=None, lookat=None, vup=None,
           vfov=None, viewport_height=None, focal_length=None, projection=None, sky_bottom=None, sky_top=None,
           light=None, shadows=None, ao=None, ao_distance=None, backend="auto", precision="exact", threads=0, samples=1, sampler="sobol", seed=0,
           region=None, dtype="uint8"):
    """Render a scene; returns a numpy.ndarray of shape (H, W, 3), rows top first.

    scene: None (the sky alone), a built-in name ("sky", "red-sphere",
        "normals", "world"), a scene file's path (str or os.PathLike), or a
        dict with a scene file's keys ({"camera": {...}, "sky": {...},
        "spheres": [{"center": [x, y, z], "radius": r}, ...]}).
    centers (N, 3), radii (N,), colors (N, 3): spheres as arrays, for a scene
        without spheres of its own. float32 and float64 arrays are read in
        place, whatever their strides (no copy); other dtypes are converted
        once to float64. They must not change during the call.
    shade: "normal" (0.5 (N + 1)), "flat" (colors, red without) or "lit",
        for every sphere of the arrays.
    width, height, aspect (a number or "W:H"), lookfrom, lookat, vup, vfov
        (degrees), viewport_height, focal_length, projection ("perspective" or
        "orthographic": parallel rays from an image plane through lookfrom,
        viewport_height high; vfov and focal_length then mean nothing),
        sky_bottom, sky_top: override the scene's camera and sky, as the
        command line's options do.
    light (x, y, z toward a directional light), shadows (True: hard shadows
        from it), ao (ambient occlusion rays per hit, 0 to 4096), ao_distance
        (how far they look; unbounded by default): how "lit" spheres are lit,
        over the scene's "light" and "ambient_occlusion" keys.
    backend: "auto", "reference", "scalar", "sse2", "avx2", "avx512", "neon".
    precision: "exact" or "fast". threads: 0 for all cores.
    samples, sampler ("random", "stratified", "sobol"), seed: antialiasing.
    region: (x0, y0, x1, y1), the pixels x0 <= x < x1, y0 <= y < y1 (y0 = 0
        at the top) of the image; the result is that window.
    dtype: "uint8" (the command line's bytes) or "float32" (linear colour).

    The GIL is released while rendering. Raises ValueError (a field out of
    range, an unknown name; .field names it), TypeError (a wrong type) or
    OSError (a scene file that cannot be read).
    """
    kind, source = "", ""
    if scene is None:
        pass
    elif isinstance(scene, dict):
        kind, source = "json", _json.dumps(scene)
    elif isinstance(scene, (str, _os.PathLike)):
        name = _os.fspath(scene)
        kind = "builtin" if name in builtin_scenes() else "file"
        source = name
    else:
        raise TypeError(f"scene: want a name, a path or a dict, got {type(scene).__name__}")
    if region is not None:
        region = tuple(int(x) for x in region)
        if len(region) != 4:
            raise ValueError(f"region: want 4 numbers (x0, y0, x1, y1), got {len(region)}")
    given = dict(width=width, height=height, aspect=aspect, lookfrom=lookfrom, lookat=lookat, vup=vup,
                 vfov=vfov, viewport_height=viewport_height, focal_length=focal_length,
                 projection=projection, sky_bottom=sky_bottom, sky_top=sky_top, light=light, shadows=shadows,
                 ao=ao, ao_distance=ao_distance)
    camera = {k: _token(k, given[k]) for k in _CAMERA_KEYWORDS if given[k] is not None}
    return _raycast.render(
        kind, source, _spheres_array("centers", centers), _spheres_array("radii", radii),
        _spheres_array("colors", colors), str(shade), camera,
        str(backend), str(precision), int(threads), int(samples), str(sampler), int(seed), region, str(dtype))


def write(path, image, format=""):
    """Write an (H, W, 3) image from render() to path, as the command line does.

    The format comes from the extension (.png, .ppm/.pnm, .jpg/.jpeg,
    .tif/.tiff, .exr) unless format names one; uint8 for all but EXR, which
    takes float32. The file is written under a temporary name and renamed
    into place: an error (OSError, ValueError) leaves path as it was.
    """
    image = _np.asarray(image)
    if image.ndim == 3 and image.dtype in (_np.uint8, _np.float32):
        image = _np.ascontiguousarray(image)
    _raycast.write(_os.fspath(path), image, str(format))
