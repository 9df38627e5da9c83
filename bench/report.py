#!/usr/bin/env python3
"""raycast-bench's report, from Google Benchmark's JSON of a run.

    build/bin/raycast-bench --benchmark_out=run.json --benchmark_out_format=json
    python3 bench/report.py run.json [--plot p.svg] [--rows]
    python3 bench/report.py bench/results/run.json --into bench/README.md [--check]

raycast-bench runs this itself at the end of a run. Every row carries its
fields in its label ("kind=render backend=avx2 ...") and what it measured in
its counters; this script takes each row's median over its repetitions (the
iteration runs, else the median aggregate), computes what needs other rows
(speedup, vs_memset, vs_none, Embree / ours, growth in N, the antialiasing
curves' slopes), prints the summaries and, with --plot FILE.svg (or .png),
draws FILE (when the run has summary rows), FILE-aa.svg, FILE-ao.svg and
FILE-scale.svg (the scale rows: time per new scene against N) with matplotlib
(Debian: python3-matplotlib); the tables need Python 3 alone.

With --into FILE.md it prints only what it wrote (and drew): a compact set of the
tables goes into FILE.md between its marker lines (report_markdown.py), the
whole report to report.txt beside the JSON (--full-report FILE); --check
compares instead of writing. The tables' code lies in the modules beside this
file, one for each family of rows (report_render, report_aa, report_light,
report_scale, report_files).
"""
import argparse
import contextlib
import io
import json
import os
import re
import statistics
import sys
from collections import defaultdict

# The report's parts lie beside this file (installed too: share/raycast/), wherever it is run from.
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))

from report_aa import plot_aa, print_aa  # noqa: E402
from report_common import UNIT, Row, of_kind  # noqa: E402
from report_files import print_formats, print_frames, print_particle_files  # noqa: E402
from report_light import plot_ao, print_ao, print_light  # noqa: E402
from report_markdown import BEGIN, END, into  # noqa: E402
from report_render import (plot_summary, print_bound, print_peers, print_rows, print_shortcuts,  # noqa: E402
                           print_sphere_stiff, print_stiff, summary_rows, print_summary)
from report_scale import plot_scale, print_scale  # noqa: E402


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


def plot_file(plot, suffix):
    """FILE.svg -> FILE-aa.svg."""
    dot, slash = plot.rfind("."), plot.rfind("/")
    return plot + suffix + ".svg" if dot < 0 or dot < slash else plot[:dot] + suffix + plot[dot:]


def report(rows, ctx, size, threads, every_row=False, plot=None, note=print):
    """Prints every table in order, drawing plot's files where the run has their rows (note: their
    "written to" lines); the summary's rows."""
    srows = summary_rows(rows, size, threads)
    print_summary(srows, ctx, size, threads)
    print_bound(rows, sorted({r.threads for r in of_kind(rows, "render")}, key=int))
    if every_row:
        print_rows(rows)
    if plot and srows:  # a run of other rows only (say scale/): its own plots only
        plot_summary(srows, ctx, size, threads, plot)
        note("Plot written to", plot)
    print_aa(rows, ctx)
    if plot and plot_aa(rows, ctx, plot_file(plot, "-aa")):
        note("Antialiasing plot written to", plot_file(plot, "-aa"))
    print_ao(rows, ctx)
    if plot and plot_ao(rows, ctx, plot_file(plot, "-ao")):
        note("Ambient occlusion plot written to", plot_file(plot, "-ao"))
    print_light(rows, ctx)
    print_shortcuts(rows)
    print_peers(rows, ctx, size)
    print_scale(rows, ctx)
    if plot and plot_scale(rows, ctx, plot_file(plot, "-scale")):
        note("Scale plot written to", plot_file(plot, "-scale"))
    print_particle_files(rows)
    print_formats(rows)
    print_frames(rows)
    print_stiff(rows)
    print_sphere_stiff(rows)
    return srows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("json", help="Google Benchmark's JSON of a raycast-bench run")
    ap.add_argument("--plot", help="FILE.svg|png: the error-vs-time scatter, and FILE-aa, FILE-ao, FILE-scale")
    ap.add_argument("--summary-size", help="WxH (default: the run's, raycast-bench --summary-size)")
    ap.add_argument("--summary-threads", type=int, help="(default: the run's)")
    ap.add_argument("--rows", action="store_true", help="also every row with speedup, vs_memset, vs_none")
    ap.add_argument("--into", metavar="FILE.md", help=f"write a compact set of the tables into FILE.md between its "
                    f"lines {BEGIN} and {END}, and the whole report (--rows included) to --full-report's file")
    ap.add_argument("--full-report", metavar="FILE", help="with --into: the whole report's file (default: "
                    "report.txt beside the JSON)")
    ap.add_argument("--check", action="store_true", help="with --into: write nothing; exit 1, with the "
                    "difference, where FILE.md's tables or the full report are not what this run makes")
    a = ap.parse_args(argv)
    if (a.full_report or a.check) and not a.into:
        ap.error("--full-report and --check go with --into")
    rows, ctx = load(a.json)
    if not rows and a.into:
        ap.error(f"{a.json} has no rows: nothing to write into {a.into}")
    if not rows:  # the filter matched none (Google Benchmark has said so)
        return 0
    size = a.summary_size or ctx.get("summary_size", "3840x2160")
    threads = a.summary_threads or int(ctx.get("summary_threads", 1))
    if not a.into:
        report(rows, ctx, size, threads, a.rows, a.plot)
        return 0
    console = sys.stdout
    with contextlib.redirect_stdout(io.StringIO()) as full:
        srows = report(rows, ctx, size, threads, True, None if a.check else a.plot,
                       note=lambda *m: print(*m, file=console))
    full_report = a.full_report or os.path.join(os.path.dirname(a.json), "report.txt")
    return into(a.into, full_report, full.getvalue().lstrip("\n"), rows, ctx, srows, size, threads, a.json, a.check)


if __name__ == "__main__":
    sys.exit(main())
