"""bench/report.py's scale tables and plot (scale/ and load/ rows): a new scene's
preparation and frame against N, ours and Embree's."""
from collections import defaultdict

from report_common import figure, of_kind

SCALE_FAMILIES = {"cloud": "sparse particle cloud (coverage 1.5)", "dense": "dense particle cloud (coverage 3)",
                  "box": "packed box seen from a corner (packing 0.3)",
                  "box-ortho": "the packed box along an axis, orthographic"}


def scale_cells(rows, family):
    """{(peer, threads '1'|'all'): {N: row}} of one family (rows without a family are clouds)."""
    cells = defaultdict(dict)
    for r in of_kind(rows, "scale"):
        if not r.error and r.get("family", "cloud") == family:
            cells[(r.peer, r.threads)][int(r.spheres)] = r
    return cells


def print_scale(rows, ctx):
    load = {int(r.spheres): r for r in of_kind(rows, "load") if not r.error}
    for family, what in SCALE_FAMILIES.items():
        print_scale_family(scale_cells(rows, family), load if family == "cloud" else {}, family, what, ctx)


def print_scale_family(cells, load, family, what, ctx):
    ns = sorted(set(load) | {n for c in cells.values() for n in c})
    if not ns:
        return
    ms = lambda s: "       -" if s is None else (lambda v: f"{v:8.3f}" if v < 10 else f"{v:8.2f}" if v < 100 else
                                                 f"{v:8.1f}" if v < 1e4 else f"{v:8.0f}")(s * 1e3)
    ratio = lambda a, b: "        " if a is None or not b else (lambda x: f" {x:6.2f}x" if x < 100 else f" {x:6.0f}x")(a / b)
    get = lambda peer, thr, n, k: (lambda r: (r.t if k == "t" else r.get(k)) if r else None)(cells[(peer, thr)].get(n))
    print(f"\nScale ({family}/): {what} (tests/support/cloud.h), 1920x1080, rgb8; ms (medians); tall = "
          f"{ctx.get('available_cores', '?')} threads\n"
          "                  ours t1           ours      embree t1         embree  embree    speedup tall"
          "          ns/px vs 1e3    load ns/sphere\n"
          "         N    prep  render   total    tall   build  render   total    tall   /ours    ours  render  embree"
          "    ours  embree   parse    bare    prep")
    for n in ns:
        o = [get("ours", "1", n, k) for k in ("prepare_s", "render_s", "t")] + [get("ours", "all", n, "t")]
        e = [get("embree", "1", n, k) for k in ("build_s", "render_s", "t")] + [get("embree", "all", n, "t")]
        ld = load.get(n)
        print(f"  {n:8d}" + "".join(ms(v) for v in o + e) + ratio(e[2], o[2]) + ratio(o[2], o[3]) +
              ratio(o[1], get("ours", "all", n, "render_s")) + ratio(e[2], e[3]) +
              ratio(get("ours", "1", n, "ns_per_px"), get("ours", "1", 1000, "ns_per_px")) +
              ratio(get("embree", "1", n, "ns_per_px"), get("embree", "1", 1000, "ns_per_px")) +
              "".join(f"{ld[k]:8.1f}" if ld and k in ld else "       -"
                      for k in ("parse_ns_per_sphere", "bare_simdjson_ns_per_sphere", "prepare_ns_per_sphere")))
    print("  total = prepare + render; embree / ours and ns/px growth at 1 thread; speedup = t1 / tall, of the\n"
          "  total (ours, embree) and of ours's render alone; load: our parse, simdjson's bare loop over the\n"
          "  same text (no checks), our preparation")


def plot_scale(rows, ctx, file):
    families = [(f, what, scale_cells(rows, f)) for f, what in SCALE_FAMILIES.items()]
    families = [x for x in families if x[2]]
    if not families:
        return False
    plt, fig, axes = figure((6 * len(families), 5.5), len(families))
    axes = axes if len(families) > 1 else [axes]
    colours = {"ours": "tab:blue", "embree": "tab:red"}
    for ax, (family, what, cells) in zip(axes, families):
        for (peer, thr), by_n in sorted(cells.items()):
            n = sorted(by_n)
            style = dict(color=colours[peer], marker="o" if thr == "1" else "s", alpha=1.0 if thr == "1" else 0.6)
            label = f"{peer} {'1 thread' if thr == '1' else 'all cores'}"
            ax.plot(n, [by_n[k].t for k in n], "-", label=label + ": prepare + render", **style)
            ax.plot(n, [by_n[k].render_s for k in n], "--", label=label + ": render", **style)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(f"spheres N ({what})")
        ax.set_ylabel("seconds per new scene, 1920x1080")
        ax.set_title(f"{family}: raycast vs Embree, {ctx.get('num_cpus', '?')} CPUs, {ctx.get('date', '')[:10]}")
        ax.grid(True, which="major", alpha=0.4)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(file)
    return True


def print_scale_compact(rows, ctx, families=("cloud", "box"), from_n=1000):
    """A few families' totals alone (prepare + render of a new scene) from N = from_n, ours and Embree's:
    the README's view."""
    fams = [(f, scale_cells(rows, f)) for f in families]
    fams = [(f, cells) for f, cells in fams if cells]
    if not fams:
        return
    ms = lambda s: "-" if s is None else f"{s * 1e3:.3f}" if s < 0.01 else f"{s * 1e3:.2f}" if s < 0.1 else \
        f"{s * 1e3:.1f}" if s < 10 else f"{s * 1e3:.0f}"
    print(f"\nScale ({', '.join(f + '/' for f, _ in fams)} rows from N = {from_n}; every row and column in the "
          "full report): a new scene's\n  prepare + render, "
          f"ms (medians), 1920x1080, rgb8; tall = {ctx.get('available_cores', '?')} threads; "
          "embree / ours at 1 thread")
    print(f"  {'family':8} {'N':>9} {'ours t1':>10} {'ours tall':>10} {'embree t1':>10} {'embree tall':>12} "
          f"{'embree/ours':>12}")
    for family, cells in fams:
        for n in sorted({n for by_n in cells.values() for n in by_n if n >= from_n}):
            t = [(lambda r: r.t if r else None)(cells[key].get(n)) if key in cells else None
                 for key in (("ours", "1"), ("ours", "all"), ("embree", "1"), ("embree", "all"))]
            ratio = f"{t[2] / t[0]:.2f}x" if t[0] and t[2] else "-"
            print(f"  {family:8} {n:9d} {ms(t[0]):>10} {ms(t[1]):>10} {ms(t[2]):>10} {ms(t[3]):>12} {ratio:>12}")
