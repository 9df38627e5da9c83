"""bench/report.py's tables of the render/, scene, bound/, shortcuts/, peers' and stiff
rows: the error-vs-run-time summary (and its plot), the store bandwidth, every row,
what each shortcut saves, the peers on world, the stiff cases."""
import math
from collections import defaultdict

from report_common import SHORTCUT_SETS, Row, err, figure, of_kind, path_key

def summary_rows(rows, size, threads, out="rgb8"):
    """The sky's rows, then each scene's, fastest first, Pareto-optimal ones marked."""
    sel = [r for r in rows.values() if r.kind in ("render", "scene") and r.size == size and
           r.threads == str(threads) and r.out == out and ("max_abs_err" in r or "max_lsb" in r)]
    out_rows = []
    for r in sel:
        ref = rows.get(f"render/reference/exact{'/' + r.scene if r.scene else ''}/{size}/t{threads}/{out}")
        out_rows.append(dict(scene=r.scene or "", ns=r.t * 1e9 / r.px, speedup=ref.t / r.t if ref else None,
                             label=f"{r.backend}/{r.precision}" + (f"/{r.scene}" if r.scene else ""),
                             err=r.get("max_abs_err", math.nan), max_lsb=int(r.get("max_lsb", 0)),
                             mismatch=r.get("lsb_mismatch", 0)))
    out_rows.sort(key=lambda s: (s["scene"], s["ns"]))
    for s in out_rows:
        s["pareto"] = not math.isnan(s["err"]) and not any(
            o["scene"] == s["scene"] and o["ns"] < s["ns"] and o["err"] <= s["err"] for o in out_rows)
    return out_rows


def print_summary(srows, ctx, size, threads, legend=True):
    """The summary table; legend: with the lines that say what its columns are."""
    cores = ctx.get("available_cores", "?")
    print(f"\nError vs run time: {ctx.get('cpu_model', '?')}, {ctx.get('date', '')[:10]}, {size}, {threads} thread"
          f"{'' if threads == 1 else 's'} (of {cores} cores), rgb8 output")
    if legend:
        print("  ns/px: the median of a row's repetitions (--benchmark_repetitions=N; one by default)\n"
              "  errors vs the double reference over the whole image: max_abs_err in linear colour\n"
              "  (from the f32 rendering), max_lsb and lsb_mismatch from the 8-bit bytes;\n"
              "  * = Pareto-optimal: no other row of the same scene is both faster and at most as\n"
              "  wrong (max_abs_err; - where a row has no float output); the sky, then each sphere scene")
    if not srows:
        print("  (no rows measured at this size, thread count and output; see --benchmark_filter)")
    else:
        print(f"    {'backend/precision[/scene]':36} {'ns/px':>9} {'speedup':>9} {'max_abs_err':>12} "
              f"{'max_lsb':>8} {'lsb_mismatch':>13}")
    for k, s in enumerate(srows):
        if k and srows[k - 1]["scene"] != s["scene"]:
            print()
        speedup = f"{s['speedup']:.1f}x" if s["speedup"] else "-"
        e = "-" if math.isnan(s["err"]) else err(s["err"])
        print(f"  {'*' if s['pareto'] else ' '} {s['label']:36} {s['ns']:9.3f} {speedup:>9} {e:>12} "
              f"{s['max_lsb']:8d} {100 * s['mismatch']:12.4f}%")
    print("Skipped backends:", ctx.get("skipped_backends", "?"))


def print_bound(rows, threads):
    """Each size's fastest rgb8 sky row against memset of the same bytes."""
    lines = []
    for m in sorted(of_kind(rows, "bound"), key=lambda r: r.px):
        for t in threads:
            cand = of_kind(rows, "render", size=m.size, threads=t, out="rgb8")
            if cand:
                b = min(cand, key=lambda r: r.t)
                lines.append(f"  {m.size:>11} {'t' + t:>4} {m.t * 1e9 / m.px:9.3f}   {b.backend + '/' + b.precision:16}"
                             f" {b.t * 1e9 / b.px:9.3f} {b.t / m.t:8.2f}x")
    if lines:
        print("\nStore bandwidth (bound/memset rows): ns/px of memset of the same bytes and of the fastest\n"
              "rgb8 sky row; vs_memset = its time / memset's (--rows: every row's)\n"
              f"  {'size':>11} {'thr':>4} {'memset':>9}   {'fastest':16} {'ns/px':>9} {'vs_memset':>9}")
        print("\n".join(lines))


def print_rows(rows):
    """Every render, scene and shortcuts row with the ratios that need another row."""
    print(f"\nEvery row: {'name':58} {'ns/px':>9} {'speedup':>8} {'vs_memset':>9} {'vs_none':>8}")
    for r in sorted(rows.values(), key=lambda r: r.name):
        if r.kind not in ("render", "scene", "shortcuts", "bound"):
            continue
        base = r.name.rsplit("/", 1)[0]
        ref = rows.get(f"render/reference/exact{'/' + r.scene if r.scene else ''}/{r.size}/t{r.threads}/{r.out}")
        mem = rows.get(f"bound/memset/{r.size}/rgb8")
        none = rows.get(base + "/none") if r.kind == "shortcuts" else None
        cell = lambda o, inv=False: f"{(r.t / o.t if inv else o.t / r.t):.2f}x" if o else "-"
        print(f"  {r.name:68} {r.t * 1e9 / r.px:9.3f} {cell(ref) if r.kind != 'shortcuts' else '-':>8} "
              f"{cell(mem, True):>9} {cell(none):>8}")


def plot_summary(srows, ctx, size, threads, file):
    floor = 1e-9
    plt, fig, ax = figure((9.6, 6.4))
    pts = [s for s in srows if not math.isnan(s["err"])]
    xs = [s["ns"] for s in srows] or [1]
    yhi = max([floor * 10] + [s["err"] for s in pts if math.isfinite(s["err"])])
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(10 ** math.floor(math.log10(min(xs))), 10 ** max(math.floor(math.log10(min(xs))) + 1,
                                                                  math.ceil(math.log10(max(xs)))))
    ax.set_ylim(floor, 10 ** math.ceil(math.log10(yhi)))
    y = lambda e: max(e, floor) if math.isfinite(e) else ax.get_ylim()[1]
    for scene in sorted({s["scene"] for s in pts}):  # each scene's Pareto front, a staircase
        front = [s for s in pts if s["pareto"] and s["scene"] == scene]
        ax.step([s["ns"] for s in front], [y(s["err"]) for s in front], where="post", ls="--", color="#1f4e9c", alpha=0.6)
    for s in pts:
        ax.plot(s["ns"], y(s["err"]), "o", ms=8, mew=1.5, color="#1f4e9c", mfc="#1f4e9c" if s["pareto"] else "white")
    place_labels(fig, ax, [(s["ns"], y(s["err"]), s["label"]) for s in pts])
    ticks = ax.get_yticks()
    ax.set_yticks(ticks, ["0" if math.isclose(t, floor) else f"$10^{{{round(math.log10(t))}}}$" for t in ticks])
    ax.set_ylim(floor, 10 ** math.ceil(math.log10(yhi)))
    ax.grid(True, which="major", color="#ddd")
    ax.set_xlabel("time per pixel (ns, log)")
    ax.set_ylabel("max abs error, linear colour (log; 0 at the bottom)")
    fig.suptitle(f"raycast: error vs run time — {ctx.get('cpu_model', '?')}, {ctx.get('date', '')[:10]}")
    ax.set_title(f"{size}, {threads} thread{'' if threads == 1 else 's'}, rgb8 output; error vs the double "
                 "reference; filled = Pareto-optimal", fontsize=10, color="#444")
    fig.savefig(file)


def place_labels(fig, ax, points):
    """Each label beside its point where it covers no point and no earlier label: right, left,
    below, above, then further out (display pixels; about 6.8 px a character)."""
    fig.canvas.draw()
    to_px, from_px = ax.transData.transform, ax.transData.inverted().transform
    W, H = fig.canvas.get_width_height()
    taken = [(x - 6, y - 6, x + 6, y + 6) for x, y in (to_px(p[:2]) for p in points)]
    hits = lambda a, b: a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]
    for px, py, label in points:
        x, y = to_px((px, py))
        w = 6.8 * len(label)
        for k in range(24):
            ring = k // 4
            side = 13.0 * ((ring + 1) // 2) * (1 if ring % 2 else -1)
            ha, tx, ty = [("left", x + 8, y - side), ("right", x - 8, y - side),
                          ("center", x, y - 15 - 13 * ring), ("center", x, y + 14 + 13 * ring)][k % 4]
            x0 = tx if ha == "left" else tx - w if ha == "right" else tx - w / 2
            box = (x0, ty - 6, x0 + w, ty + 7)
            if box[0] >= 0 and box[2] <= W and box[1] >= 30 and box[3] <= H - 20 and not any(hits(box, o) for o in taken):
                break
        taken.append(box)
        ax.text(*from_px((tx, ty)), label, ha=ha, va="center", fontsize=9)


def print_shortcuts(rows):
    grid = defaultdict(dict)
    for r in of_kind(rows, "shortcuts"):
        grid[(r.backend, r.precision)][r.shortcuts] = r
    if not grid:
        return
    any_row = next(iter(next(iter(grid.values())).values()))
    print(f"\nWhat each shortcut saves (shortcuts/ rows): ns/px at {any_row.size}, 1 thread, rgb8; none = the "
          "general path, all = every shortcut (the default)")
    print(f"  {'backend/precision':18}" + "".join(f"{s:>14}" for s in SHORTCUT_SETS))
    for (b, p), cells in sorted(grid.items()):
        print(f"  {b + '/' + p:18}" + "".join(f"{cells[s].t * 1e9 / cells[s].px:14.3f}" if s in cells else f"{'-':>14}"
                                              for s in SHORTCUT_SETS))


def print_peers(rows, ctx, size):
    ns = lambda name: (lambda r: r.t * 1e9 / r.px if r else None)(rows.get(name))
    best = ctx.get("best_sphere_path", "?")
    lines = [(best, ns(f"render/{best}/world/{size}/t1/rgb8")),
             ("embree16 (rtcIntersect16)", ns(f"render/embree16/float/world/{size}/t1/rgb8")),
             ("embree1 (rtcIntersect1)", ns(f"render/embree1/float/world/{size}/t1/rgb8")),
             ("book (double, virtual)", ns(f"render/book/exact/world/{size}/t1/rgb8"))]
    if not any(v for _, v in lines):
        return
    print(f"\nPeers on world, {size}, 1 thread, rgb8 (ns/px; x = peer / ours):")
    ours = lines[0][1]
    for label, v in lines:
        if v is not None:
            print(f"  {label:26} {v:9.2f}" + (f"   {v / ours:7.1f}x" if ours else ""))


def print_stiff(rows):
    stiff = of_kind(rows, "stiff")
    if not stiff:
        return
    cases = sorted({(int(r.index), r.case, r.size, r.error if not r.backend else None) for r in stiff})
    cols = sorted({(r.backend, r.precision) for r in stiff if r.backend},
                  key=lambda bp: path_key(Row(backend=bp[0], precision=bp[1])))
    cell = {(r.case, r.backend, r.precision): r for r in stiff}
    print("\nStiff cases (not timed): error vs the double reference (raycast::reference_pixel)")
    for title, fmt in [("max_abs_err, linear colour (f32 output):", lambda r: err(r.max_abs_err)),
                       ("max_lsb (rgb8 output):", lambda r: f"{int(r.max_lsb)}"),
                       ("NaN count (f32 output; should be 0):", lambda r: f"{int(r.nan_count)}")]:
        print(title + f"\n  {'case':40} {'size':9}" + "".join(f" {b:>9}" for b, _ in cols) +
              f"\n  {'':40} {'':9}" + "".join(f" {p:>9}" for _, p in cols))
        for _, case, size, refused in cases:
            print(f"  {case:40} {size:9}" + (f"  refused: {refused}" if refused else "".join(
                f" {fmt(cell[(case, b, p)]) if (case, b, p) in cell and not cell[(case, b, p)].error else '-':>9}"
                for b, p in cols)))


def print_sphere_stiff(rows):
    by_case = defaultdict(dict)
    for r in of_kind(rows, "sphere_stiff"):
        by_case[(int(r.index), r.case, r.size)][r.peer] = r
    if not by_case:
        return
    print("\nStiff sphere cases (not timed): ours / naive (the book's ch. 6 hit_sphere in float) / Embree\n"
          "(rtcIntersect1) against the double reference; counts are pixels away from silhouettes, (all)\n"
          "where they differ; distance error relative, where both hit the same sphere away from\n"
          "silhouettes; LSB: 8-bit error of the pixels the reference shades from a sphere.\n")
    print("| case | size | wrong object | false hits | false misses | max distance error | max LSB |\n"
          "|---|---|---|---|---|---|---|")
    count = lambda k: lambda r: (lambda a, b: f"{a}" if a == b else f"{a} ({b})")(int(r[k + "_away"]), int(r[k]))
    failures = []
    for (_, case, size), peers in sorted(by_case.items()):
        def cells(text):
            return " / ".join(text(peers[p]) if p in peers and not peers[p].error else "-"
                              for p in ("ours", "naive", "embree"))
        print(f"| {case} | {size} | " + " | ".join(cells(t) for t in (
            count("wrong_object"), count("false_hits"), count("false_misses"),
            lambda r: err(r.max_rel_distance_err), count("max_lsb"))) + " |")
        failures += [f"Embree, {case}: {peers['embree'].error}"] if "embree" in peers and peers["embree"].error else []
    for f in failures:
        print(f)
