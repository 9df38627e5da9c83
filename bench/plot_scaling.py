#!/usr/bin/env python3
"""Plot raycast-bench's scale rows: time per frame of a new scene against N.

    build/bin/raycast-bench --benchmark_filter='scale/' --benchmark_repetitions=3 \\
        --benchmark_out=scale.json --benchmark_format=json
    python3 bench/plot_scaling.py scale.json scale.svg

Reads Google Benchmark's JSON (the rows scale/ours|embree/N/t1|tall), takes
each row's median over its repetitions and draws, log-log, prepare + render
(solid) and render alone (dashed) for ours and Embree, one thread and all
cores. Needs matplotlib (Debian: python3-matplotlib).
"""
import json
import re
import statistics
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def medians(path):
    """{(who, threads): {N: (total_s, render_s)}}, medians of the repetitions."""
    runs = defaultdict(list)
    with open(path) as f:
        data = json.load(f)
    for b in data["benchmarks"]:
        m = re.fullmatch(r"scale/(ours|embree)/(\d+)/(t1|tall)", b.get("run_name", ""))
        if not m or b["run_type"] != "iteration" or b.get("error_occurred"):
            continue
        unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
        runs[(m[1], m[3], int(m[2]))].append((b["real_time"] * unit, b["render_s"]))
    out = defaultdict(dict)
    for (who, threads, n), v in runs.items():
        out[(who, threads)][n] = tuple(statistics.median(x) for x in zip(*v))
    return out, data["context"]


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_scaling.py BENCH.json OUT.svg|png")
    rows, context = medians(sys.argv[1])
    if not rows:
        sys.exit("no scale/ rows in " + sys.argv[1])
    fig, ax = plt.subplots(figsize=(8, 5.5))
    colours = {"ours": "tab:blue", "embree": "tab:red"}
    for (who, threads), by_n in sorted(rows.items()):
        n = sorted(by_n)
        style = dict(color=colours[who], marker="o" if threads == "t1" else "s",
                     alpha=1.0 if threads == "t1" else 0.6)
        label = f"{who} {'1 thread' if threads == 't1' else 'all cores'}"
        ax.plot(n, [by_n[k][0] for k in n], "-", label=label + ": prepare + render", **style)
        ax.plot(n, [by_n[k][1] for k in n], "--", label=label + ": render", **style)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("spheres N (particle cloud, coverage 1.5)")
    ax.set_ylabel("seconds per new scene, 1920x1080")
    ax.set_title(f"raycast vs Embree, {context.get('num_cpus', '?')} CPUs, {context.get('date', '')[:10]}")
    ax.grid(True, which="major", alpha=0.4)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2])


if __name__ == "__main__":
    main()
