"""bench/report.py's light tables (ao/ and light/ rows): ambient occlusion's error vs
run time, and shadows and AO against Embree."""
from report_common import SAMPLERS, err, figure, of_kind

def ao_points(rows):
    return [r for r in of_kind(rows, "ao") if "rms_err" in r]


def ao_pareto(pts):
    """The rows no other row beats on both time and RMSE."""
    return {r.name for r in pts
            if not any(o.ns_per_px < r.ns_per_px and o.rms_err <= r.rms_err for o in pts if o is not r)}


def print_ao(rows, ctx):
    pts = ao_points(rows)
    if not pts:
        return
    best = ao_pareto(pts)
    print(f"\nAmbient occlusion: error vs run time (ao/ rows): {ctx.get('cpu_model', '?')}, "
          f"{ctx.get('date', '')[:10]}, {pts[0].scene} {pts[0].size}, 1 thread, rgb_f32, seed 0\n"
          f"  RMSE and max abs error of linear colour against {int(pts[0].converged_ao)} sobol AO rays a hit;\n"
          "  ns/px: the median of a row's repetitions; * = Pareto-optimal (no row both faster and at most as wrong)")
    print(f"  {'sampler':12} {'AO N':>6} {'ns/px':>10} {'RMSE':>10} {'max err':>10}")
    for s in SAMPLERS:
        for i, r in enumerate(sorted((r for r in pts if r.sampler == s), key=lambda r: int(r.ao))):
            mark = "*" if r.name in best else " "
            print(f"{mark} {s if i == 0 else '':12} {int(r.ao):6d} {r.ns_per_px:10.1f} {err(r.rms_err):>10} "
                  f"{err(r.max_abs_err):>10}")
    rnd = {int(r.ao): r.rms_err for r in pts if r.sampler == "random"}
    sob = {int(r.ao): r.rms_err for r in pts if r.sampler == "sobol"}
    pairs = [(n, sob[n], rnd[4 * n]) for n in sorted(sob) if 4 * n in rnd and n >= 16]
    if pairs:
        print("  sobol at N against random at 4N (the goal: sobol's RMSE at most random's):" +
              "".join(f" N={n} {err(a)} vs {err(b)}" for n, a, b in pairs))


def plot_ao(rows, ctx, file):
    pts = ao_points(rows)
    if not pts:
        return False
    plt, fig, ax = figure((8.4, 5.6))
    best = ao_pareto(pts)
    for s, colour in zip(SAMPLERS, ["#d62728", "#2ca02c", "#1f4e9c"]):
        c = sorted((r for r in pts if r.sampler == s), key=lambda r: int(r.ao))
        ax.plot([r.ns_per_px for r in c], [r.rms_err for r in c], "-", marker="o", mfc="white", color=colour, label=s)
        for r in c:
            if r.name in best:
                ax.plot(r.ns_per_px, r.rms_err, "o", color=colour)
        if c:
            ax.annotate(f"AO {int(c[-1].ao)}", (c[-1].ns_per_px, c[-1].rms_err), xytext=(6, -12),
                        textcoords="offset points", fontsize=8, color=colour)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, which="major", color="#ddd")
    ax.legend()
    ax.set_xlabel("time per pixel (ns, log), 1 thread")
    ax.set_ylabel("RMSE against the converged image, linear colour (log)")
    fig.suptitle(f"raycast: ambient occlusion error vs run time — {ctx.get('cpu_model', '?')}, {ctx.get('date', '')[:10]}")
    ax.set_title(f"{pts[0].scene} {pts[0].size}; filled: Pareto-optimal", fontsize=10, color="#444")
    fig.tight_layout()
    fig.savefig(file)
    return True


def light_cells(o, e, t, t2):
    """One light row's cells: ours, render/primary, Embree, Embree/ours, Tachyon, Tachyon/ours."""
    mine = o.prepare_s + o.render_s if o and "render_s" in o else None
    ours = f"{o.prepare_s * 1e3:.0f} + {o.render_s * 1e3:.0f} ({o.primary_s * 1e3:.0f})" if mine else "-"
    per = f"{o.render_s / o.primary_s:.1f}x" if mine and o.primary_s else "-"
    has_e = e and "build_s" in e
    emb = f"{e.build_s * 1e3:.0f} + {e.primary_s * 1e3:.0f} + {e.shadow_s * 1e3:.0f} + {e.ao_s * 1e3:.0f}" if has_e else "-"
    ratio = f"{(e.build_s + e.render_s) / mine:.2f}x" if mine and has_e else "-"
    has_t = t and "render_s" in t
    tach = f"{t.prepare_s * 1e3:.0f} + {t.render_s * 1e3:.0f}" if has_t else "-"
    if has_t and t2 and "render_s" in t2:
        tach += f" ({(t2.prepare_s + t2.render_s) * 1e3:.0f})"
    tratio = f"{(t.prepare_s + t.render_s) / mine:.2f}x" if mine and has_t else "-"
    return ours, per, emb, ratio, tach, tratio


def print_light(rows, ctx):
    cells = {}
    for r in of_kind(rows, "light"):
        cells.setdefault((r.family, int(r.spheres), r.variant), {})[(r.peer, r.threads)] = r
    if not cells:
        return
    print(f"\nLight (light/ rows): shadows, and shadows + 8 AO rays a hit, against Embree's rtcOccluded16 and "
          f"Tachyon; {ctx.get('cpu_model', '?')}, {ctx.get('date', '')[:10]}, 1 thread unless said (ms)")
    print("  render/primary: our lit frame's render over its primary frame's; Tachyon: its preprocessing + ray "
          "tracing (all cores)")
    print(f"  {'family':10} {'N':>8} {'variant':21} {'ours prep+render (primary)':>28} {'render/primary':>14}"
          f" {'Embree build+prim+shadow+AO':>30} {'Embree/ours':>11} {'Tachyon prep+trace (all)':>26}"
          f" {'Tachyon/ours':>12} {'2 thr/1':>8}")
    for (fam, n, var), c in sorted(cells.items()):
        o, o2 = c.get(("ours", "1")), c.get(("ours", "all"))
        ours, per, emb, ratio, tach, tratio = light_cells(o, c.get(("embree", "1")), c.get(("tachyon", "1")),
                                                          c.get(("tachyon", "all")))
        scale = f"{o.render_s / o2.render_s:.2f}x" if o and o2 and "render_s" in o and "render_s" in o2 else "-"
        print(f"  {fam:10} {n:8d} {var:21} {ours:>28} {per:>14} {emb:>30} {ratio:>11} {tach:>26} {tratio:>12}"
              f" {scale:>8}")
    bad = sorted({f"{r.frame_mismatch:.4f}" for r in of_kind(rows, "light", peer="tachyon") if "frame_mismatch" in r})
    if bad:
        print("  Tachyon's pictures against ours (480x270, hit or not): " + ", ".join(bad) + " of the pixels differ")
    for m in sorted({r.error for r in of_kind(rows, "light") if r.error}):
        print(f"  skipped rows: {m}")
