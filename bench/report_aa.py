"""bench/report.py's antialiasing tables and plot (aa/ and region/ rows): error vs run
time per sampler, the log-log slopes, the samples to match the book's RMSE."""
import math

from report_common import SAMPLERS, err, figure, of_kind

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
