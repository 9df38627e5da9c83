#!/usr/bin/env python3
"""raycast-bench's report, from Google Benchmark's JSON of a run.

    build/bin/raycast-bench --benchmark_out=run.json --benchmark_out_format=json
    python3 bench/report.py run.json [--plot p.svg] [--rows]

raycast-bench runs this itself at the end of a run. Every row carries its
fields in its label ("kind=render backend=avx2 ...") and what it measured in
its counters; this script takes each row's median over its repetitions (the
iteration runs, else the median aggregate), computes what needs other rows
(speedup, vs_memset, vs_none, Embree / ours, growth in N, the antialiasing
curves' slopes), prints the summaries and, with --plot FILE.svg (or .png),
draws FILE (when the run has summary rows), FILE-aa.svg and FILE-scale.svg
(the scale rows: time per new scene against N) with matplotlib (Debian:
python3-matplotlib); the tables need Python 3 alone.
"""
import argparse
import json
import math
import re
import statistics
import sys
from collections import defaultdict

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


def load(path):
    """(rows by name, context); none from an empty file (a run whose filter matched no row)."""
    with open(path) as f:
        text = f.read()
    data = json.loads(text) if text.strip() else {"benchmarks": []}
    runs, medians = defaultdict(list), {}
    for b in data["benchmarks"]:
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                medians[b["run_name"]] = b
        else:
            runs[b["run_name"]].append(b)
    rows = {}
    for name in set(runs) | set(medians):
        reps = [b for b in runs.get(name, []) if not b.get("error_occurred")] or runs.get(name) or [medians[name]]
        row = Row(name=name, error=reps[0].get("error_message") if reps[0].get("error_occurred") else None)
        row.update(kv.split("=", 1) for kv in re.split(r" (?=[a-z_]+=)", reps[0].get("label", "")) if "=" in kv)
        if "size" in row:
            row["w"], row["h"] = map(int, row["size"].split("x"))
            row["px"] = row["w"] * row["h"]
        for k, v in reps[0].items():
            if isinstance(v, (int, float)) and not isinstance(v, bool) and k not in row:
                row[k] = statistics.median(b[k] for b in reps if k in b)
        row["t"] = row.get("real_time", 0) * UNIT[reps[0].get("time_unit", "ns")]
        rows[name] = row
    return rows, data.get("context", {})


def of_kind(rows, kind, **match):
    return [r for r in rows.values() if r.kind == kind and all(r.get(k) == v for k, v in match.items())]


def err(e):
    return "0" if e == 0 else "inf" if not math.isfinite(e) else f"{e:.1e}"


def path_key(r):
    return (PATH_ORDER.index(r.backend) if r.backend in PATH_ORDER else len(PATH_ORDER), r.backend, r.precision != "exact")


# --- the error-vs-run-time summary -------------------------------------------------------

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


def print_summary(srows, ctx, size, threads):
    cores = ctx.get("available_cores", "?")
    print(f"\nError vs run time: {ctx.get('cpu_model', '?')}, {ctx.get('date', '')[:10]}, {size}, {threads} thread"
          f"{'' if threads == 1 else 's'} (of {cores} cores), rgb8 output\n"
          "  ns/px: the median of a row's repetitions (--benchmark_repetitions=N; one by default)\n"
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


# --- antialiasing ------------------------------------------------------------------------

def loglog_slope(curve, min_samples=4):
    """Least-squares slope of log(rmse) against log(samples) over (samples, rmse) with samples >= min_samples."""
    pts = [(n, e) for n, e in curve if n >= min_samples]
    if len(pts) < 2 or any(not (e > 0) for _, e in pts):
        return None
    xs, ys = [math.log(n) for n, _ in pts], [math.log(e) for _, e in pts]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    den = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / den if den > 0 else None


def samples_to_match(curve, target, min_samples=4):
    """(N*, extrapolated): where the curve's RMSE is target, in log-log; None where it cannot say."""
    c = sorted(curve)
    if not c or not (target > 0) or any(not (e > 0) for _, e in c) or target > c[0][1]:
        return None
    lt = math.log(target)
    for (n0, e0), (n1, e1) in zip(c, c[1:]):
        y0, y1 = math.log(e0), math.log(e1)
        if y1 <= lt <= y0:
            t = 0 if y0 == y1 else (lt - y0) / (y1 - y0)
            return math.exp(math.log(n0) + t * (math.log(n1) - math.log(n0))), False
    if target == c[-1][1]:
        return c[-1][0], False
    slope = loglog_slope(c, min_samples)
    if slope is None or not slope < 0:
        return None
    return c[-1][0] * math.exp((lt - math.log(c[-1][1])) / slope), True


def aa_points(rows):
    return [r for r in of_kind(rows, "aa") if "rms_err" in r]


def curve(pts, scene, sampler):
    return sorted((r for r in pts if r.scene == scene and r.sampler == sampler), key=lambda r: int(r.samples))


def scenes_of(pts):
    return sorted({r.scene for r in pts}, key=lambda s: (s != "world", s != "sky", s))


def strata(n):
    nx = max(d for d in range(1, math.isqrt(n) + 1) if n % d == 0)
    return f"{n} ({nx}x{n // nx} strata)"


def print_regions(rows):
    reg = {r.part: r for r in of_kind(rows, "region")}
    if "full" not in reg:
        return
    print(f"\nRegions (--region) of world {reg['full'].size}, 16 samples, 1 thread: each quadrant rendered on its "
          "own (edges inside batches)")
    for part in ["full", "q0", "q1", "q2", "q3"]:
        if part in reg:
            print(f"  {reg[part].name:44} {reg[part].t * 1e3:9.2f} ms  {reg[part].ns_per_px:6.2f} ns per region pixel")
    if all(f"q{q}" in reg for q in range(4)):
        s = sum(reg[f"q{q}"].t for q in range(4))
        print(f"  the four quadrants together: {s * 1e3:.2f} ms, {s / reg['full'].t:.3f} x the whole frame's time")


def print_aa(rows, ctx):
    print_regions(rows)
    pts = aa_points(rows)
    ours = [r for r in pts if r.sampler]
    if not pts:
        return
    ns = lambda r: r.t * 1e9 / r.px
    size, backend = pts[0].size, (ours or pts)[0].backend
    ref_samples = int((ours or pts)[0].ref_samples)
    print(f"\nAntialiasing: error vs run time (aa/ rows): {ctx.get('cpu_model', '?')}, {ctx.get('date', '')[:10]}, "
          f"{size}, 1 thread, rgb_f32, {backend}/exact, seed 0\n"
          "  error of linear colour against the converged reference (the double reference,\n"
          f"  stratified, {strata(ref_samples)} a pixel): RMSE over every pixel and channel, and max\n"
          "  abs error; ns/px: the median of a row's repetitions. N = 1 is the pixel point for every\n"
          "  sampler (the same image; its rows differ in time only). book7: the book's ch. 7\n"
          "  program (double, rand(), virtual hits), the same reference.")
    for scene in scenes_of(pts):
        r = next((r for r in pts if r.scene == scene and r.sampler), None) or next(r for r in pts if r.scene == scene)
        where = {1: f"read from the cache in {ctx.get('aa_reference_dir')}", -1: "not cached",
                 0: f"now cached in {ctx.get('aa_reference_dir')}"}[int(r.ref_cached)]
        print(f"  reference {scene:6} built in {r.ref_built_s:.1f} s on {int(r.ref_threads)} thread"
              f"{'' if r.ref_threads == 1 else 's'} ({where})")
    line = lambda label, r: (f"  {label:12} {int(r.samples):6d} {ns(r):10.2f} {r.ns_per_sample:10.3f} "
                             f"{err(r.rms_err):>10} {err(r.get('max_abs_err', math.nan)):>10}")
    for scene in scenes_of(pts):
        print(f"\n{scene}{'N':>{19 - len(scene)}} {'ns/px':>10} {'ns/sample':>10} {'RMSE':>10} {'max err':>10}")
        for s in SAMPLERS:
            for i, r in enumerate(curve(pts, scene, s)):
                print(line(s if i == 0 else "", r))
        for r in curve(pts, scene, None):
            print(line("book7", r))
        slopes = {s: loglog_slope([(int(r.samples), r.rms_err) for r in curve(pts, scene, s)]) for s in SAMPLERS}
        print("  log-log slope of RMSE against N (least squares, N >= 4):" +
              "".join(f" {s} {'-' if v is None else f'{v:.2f}'}" for s, v in slopes.items()))
        strat = curve(pts, scene, "stratified")
        if slopes["stratified"] is not None and slopes["stratified"] < 0:
            last = strat[-1]
            print(f"  the reference's own RMSE, the stratified curve extrapolated to {ref_samples}: about "
                  f"{err(last.rms_err * (ref_samples / int(last.samples)) ** slopes['stratified'])}\n"
                  "  (an RMSE within a few times of it measures the reference as much as the row)")
    for b in (r for r in pts if not r.sampler):
        bn = int(b.samples)
        print(f"\nSamples to match the book's RMSE on {b.scene} ({err(b.rms_err)} at {bn} random samples):\n"
              f"  N* interpolated in log-log; the goal for the default sampler, {ctx.get('default_sampler', '?')}: "
              f"N*/{bn} <= 0.25")
        for s in SAMPLERS:
            m = samples_to_match([(int(r.samples), r.rms_err) for r in curve(pts, b.scene, s)], b.rms_err)
            print(f"  {s:12} " + ("N* -  (the curve does not reach it)" if m is None else
                                  f"N* {m[0]:8.1f}   N*/{bn} = {m[0] / bn:.3f}" +
                                  ("  (extrapolated past the last N)" if m[1] else "")))
        print(f"Per-sample speed on {b.scene}, book7 s{bn} {b.ns_per_sample:.2f} ns/sample against ours (goal: >= 50x):")
        ns_all = sorted({int(r.samples) for r in ours})
        at = sorted({n for n in (64, ns_all[-1] if ns_all else 0) if n in ns_all})
        for s in SAMPLERS:
            cells = [r for r in curve(pts, b.scene, s) if int(r.samples) in at]
            print(f"  {s:12}" + "".join(f"  s{int(r.samples):<4d} {r.ns_per_sample:7.3f} ns/sample "
                                         f"{b.ns_per_sample / r.ns_per_sample:7.1f}x" for r in cells))


def plot_aa(rows, ctx, file):
    pts = aa_points(rows)
    if not pts:
        return False
    plt, fig, ax = figure((9.6, 6.4))
    colours = dict(zip(SAMPLERS, ["#d62728", "#2ca02c", "#1f4e9c"]))
    ns = lambda r: r.t * 1e9 / r.px
    for i, scene in enumerate(scenes_of(pts)):
        for s in SAMPLERS:
            c = curve(pts, scene, s)
            if c:
                ax.plot([ns(r) for r in c], [r.rms_err for r in c], "-" if i == 0 else "--", marker="o", mfc="white",
                        color=colours[s], label=f"{s} / {scene}")
                ax.annotate(f"s{int(c[-1].samples)}", (ns(c[-1]), c[-1].rms_err), xytext=(6, -12),
                            textcoords="offset points", fontsize=8, color=colours[s])
    for r in curve(pts, "world", None) + curve(pts, "sky", None):
        ax.plot(ns(r), r.rms_err, "D", color="black")
        ax.annotate(f"book7 s{int(r.samples)} ({r.scene})", (ns(r), r.rms_err), xytext=(-10, 0),
                    textcoords="offset points", ha="right", va="center")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.grid(True, which="major", color="#ddd")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=9)
    ax.set_xlabel("time per pixel (ns, log), 1 thread")
    ax.set_ylabel("RMSE against the converged reference, linear colour (log)")
    samples = ", ".join(str(n) for n in sorted({int(r.samples) for r in pts if r.sampler}))
    fig.suptitle(f"raycast: antialiasing error vs run time — {ctx.get('cpu_model', '?')}, {ctx.get('date', '')[:10]}")
    ax.set_title(f"{pts[0].size}, {next((r.backend for r in pts if r.sampler), '?')}/exact, rgb_f32; points N = "
                 f"{samples} samples a pixel; solid: world, dashed: sky", fontsize=10, color="#444")
    fig.tight_layout()
    fig.savefig(file)
    return True


# --- light: ambient occlusion's error, shadows and AO against Embree --------------------------

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
        o, e, o2 = c.get(("ours", "1")), c.get(("embree", "1")), c.get(("ours", "all"))
        t, t2 = c.get(("tachyon", "1")), c.get(("tachyon", "all"))
        ours = f"{o.prepare_s * 1e3:.0f} + {o.render_s * 1e3:.0f} ({o.primary_s * 1e3:.0f})" if o and "render_s" in o else "-"
        per = f"{o.render_s / o.primary_s:.1f}x" if o and o.primary_s else "-"
        emb = (f"{e.build_s * 1e3:.0f} + {e.primary_s * 1e3:.0f} + {e.shadow_s * 1e3:.0f} + {e.ao_s * 1e3:.0f}"
               if e and "build_s" in e else "-")
        mine = o.prepare_s + o.render_s if o and "render_s" in o else None
        ratio = f"{(e.build_s + e.render_s) / mine:.2f}x" if mine and e and "build_s" in e else "-"
        tach = "-"
        if t and "render_s" in t:
            tach = f"{t.prepare_s * 1e3:.0f} + {t.render_s * 1e3:.0f}"
            if t2 and "render_s" in t2:
                tach += f" ({(t2.prepare_s + t2.render_s) * 1e3:.0f})"
        tratio = f"{(t.prepare_s + t.render_s) / mine:.2f}x" if mine and t and "render_s" in t else "-"
        scale = f"{o.render_s / o2.render_s:.2f}x" if o and o2 and "render_s" in o2 else "-"
        print(f"  {fam:10} {n:8d} {var:21} {ours:>28} {per:>14} {emb:>30} {ratio:>11} {tach:>26} {tratio:>12}"
              f" {scale:>8}")
    bad = sorted({f"{r.frame_mismatch:.4f}" for r in of_kind(rows, "light", peer="tachyon") if "frame_mismatch" in r})
    if bad:
        print("  Tachyon's pictures against ours (480x270, hit or not): " + ", ".join(bad) + " of the pixels differ")
    missing = sorted({r.error for r in of_kind(rows, "light") if r.error})
    for m in missing:
        print(f"  skipped rows: {m}")


# --- shortcuts, peers, scale, stiff cases --------------------------------------------------

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


def print_particle_files(rows):
    """load-ply/N against the JSON load/N rows (the cloud's text) and the bare bandwidths; big/ rows."""
    ply = {int(r.spheres): r for r in of_kind(rows, "load-ply") if not r.error}
    json_rows = {int(r.spheres): r for r in of_kind(rows, "load") if not r.error}
    if ply:
        print("\nParticle files (load-ply/): a PLY file of the packed box (19 bytes a sphere) from the page cache;\n"
              "ns a sphere (medians)\n"
              "         N    PLY load    GB/s   pread  memcpy   prepare   JSON parse (load/, the cloud's text)")
        for n in sorted(ply):
            r, j = ply[n], json_rows.get(n)
            print(f"  {n:8d}" + "".join(f"{r.get(k, 0):10.1f}" if k != "load_GBps" else f"{r.get(k, 0):8.2f}"
                                          for k in ("load_ns_per_sphere", "load_GBps")) +
                  "".join(f"{r.get(k, 0):8.2f}" for k in ("pread_ns_per_sphere", "memcpy_ns_per_sphere")) +
                  f"{r.get('prepare_ns_per_sphere', 0):10.1f}" +
                  (f"{j.get('parse_ns_per_sphere'):13.1f}" if j and "parse_ns_per_sphere" in j else "            -"))
        print("  pread: the same file read into memory; memcpy: its bytes copied; the load reads, checks every\n"
              "  value and fills the scene's columns (first touch of fresh memory included)")
    for r in of_kind(rows, "big"):
        if r.error:
            print(f"\n{r.name}: {r.error}")
            continue
        print(f"\n{r.name} (3840x2160, all cores, raycast end to end): load {r.get('load_s', 0):.2f} s, prepare "
              f"{r.get('prepare_s', 0):.2f} s, render {r.get('render_s', 0):.2f} s, total {r.get('total_s', 0):.2f} s, "
              f"peak RSS {r.get('peak_rss_mb', 0) / 1e3:.2f} GB")


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


def plot_file(plot, suffix):
    """FILE.svg -> FILE-aa.svg."""
    dot, slash = plot.rfind("."), plot.rfind("/")
    return plot + suffix + ".svg" if dot < 0 or dot < slash else plot[:dot] + suffix + plot[dot:]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("json", help="Google Benchmark's JSON of a raycast-bench run")
    ap.add_argument("--plot", help="FILE.svg|png: the error-vs-time scatter, and FILE-aa, FILE-ao, FILE-scale")
    ap.add_argument("--summary-size", help="WxH (default: the run's, raycast-bench --summary-size)")
    ap.add_argument("--summary-threads", type=int, help="(default: the run's)")
    ap.add_argument("--rows", action="store_true", help="also every row with speedup, vs_memset, vs_none")
    a = ap.parse_args(argv)
    rows, ctx = load(a.json)
    if not rows:  # the filter matched none (Google Benchmark has said so)
        return
    size = a.summary_size or ctx.get("summary_size", "3840x2160")
    threads = a.summary_threads or int(ctx.get("summary_threads", 1))
    srows = summary_rows(rows, size, threads)
    print_summary(srows, ctx, size, threads)
    print_bound(rows, sorted({r.threads for r in of_kind(rows, "render")}, key=int))
    if a.rows:
        print_rows(rows)
    if a.plot and srows:  # a run of other rows only (say scale/): its own plots only
        plot_summary(srows, ctx, size, threads, a.plot)
        print("Plot written to", a.plot)
    print_aa(rows, ctx)
    if a.plot and plot_aa(rows, ctx, plot_file(a.plot, "-aa")):
        print("Antialiasing plot written to", plot_file(a.plot, "-aa"))
    print_ao(rows, ctx)
    if a.plot and plot_ao(rows, ctx, plot_file(a.plot, "-ao")):
        print("Ambient occlusion plot written to", plot_file(a.plot, "-ao"))
    print_light(rows, ctx)
    print_shortcuts(rows)
    print_peers(rows, ctx, size)
    print_scale(rows, ctx)
    if a.plot and plot_scale(rows, ctx, plot_file(a.plot, "-scale")):
        print("Scale plot written to", plot_file(a.plot, "-scale"))
    print_particle_files(rows)
    print_stiff(rows)
    print_sphere_stiff(rows)


if __name__ == "__main__":
    sys.exit(main())
