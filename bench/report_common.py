"""What every part of bench/report.py shares: a row, the rows of a kind, the error's
format, the backends' order, and matplotlib's figure (imported only for a plot)."""
import math

PATH_ORDER = ["reference", "scalar", "autovec", "sse2", "avx2", "avx512", "neon"]
SHORTCUT_SETS = ["none", "lanes", "lanes+mirror", "channels", "clamps", "all"]
SAMPLERS = ["random", "stratified", "sobol"]
UNIT = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


class Row(dict):
    """A row's fields (its label, "key=value key=value", a value may hold spaces) and medians (t: seconds an iteration; counters)."""

    def __getattr__(self, k):
        return self.get(k)


def figure(size, columns=1):
    """(pyplot, figure, axes) of matplotlib without a display, imported only when a plot is asked for."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return (plt, *plt.subplots(1, columns, figsize=size))


def of_kind(rows, kind, **match):
    return [r for r in rows.values() if r.kind == kind and all(r.get(k) == v for k, v in match.items())]


def err(e):
    return "0" if e == 0 else "inf" if not math.isfinite(e) else f"{e:.1e}"


def path_key(r):
    return (PATH_ORDER.index(r.backend) if r.backend in PATH_ORDER else len(PATH_ORDER), r.backend, r.precision != "exact")
