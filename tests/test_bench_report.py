"""bench/report.py: its antialiasing arithmetic on exact power laws, and its tables and plots
from a short run of raycast-bench (RAYCAST_BENCH: the binary; CTest's bench.report), with the
rows interleaved and repeated, and the same report whatever the rows' order in the JSON; --into's
tables between a Markdown file's markers, and --check's finding of tables that drifted from the run."""
import importlib.util
import json
import math
import os
import random
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
REPORT = HERE.parent / "bench" / "report.py"
spec = importlib.util.spec_from_file_location("report", REPORT)
report = importlib.util.module_from_spec(spec)
spec.loader.exec_module(report)
sys.path.insert(0, str(REPORT.parent))
import report_aa  # noqa: E402  (the antialiasing arithmetic, beside report.py)

# Every section's rows, each a few: the sky and world at 400x225, one thread; the shortcuts of
# sse2/fast; two sobol points and the book on world; the regions; the cloud's scale rows at N = 1
# and ours on the box at 1000; a stiff sky case and a stiff sphere case.
FILTER = ("^bound/memset/400x225/|^render/[^/]+/[^/]+/400x225/t1/|^render/[^/]+/[^/]+/world/400x225/t1/rgb8"
          "|^shortcuts/sse2/fast/|^aa/[^/]+/sobol/world/96x54/s(1|4)$|^aa/book7/|^region/"
          "|^scale/cloud/[^/]+/1/t1$|^scale/box/ours/1000/t1$|^load/1$|^stiff/W=1/|^sphere_stiff/unit_sphere_at_10/")


def power_law(a, slope, ns):
    return [(n, a * n ** slope) for n in ns]


def test_slope_of_a_power_law_over_n_at_least_four():
    c = [(1, 1.0)] + power_law(0.1, -0.75, [4, 16, 64, 256])  # N = 1 is left out of the fit
    assert report_aa.loglog_slope(c) == pytest.approx(-0.75, abs=1e-12)
    assert report_aa.loglog_slope(power_law(0.1, -0.5, [1, 4])) is None  # one point at N >= 4


def test_samples_to_match_interpolates_in_log_log():
    c = power_law(0.1, -0.5, [1, 4, 16, 64, 256])
    n, extrapolated = report_aa.samples_to_match(c, 0.1 / math.sqrt(100))
    assert n == pytest.approx(100, abs=1e-9) and not extrapolated
    n, extrapolated = report_aa.samples_to_match(c, 0.1 / math.sqrt(1024))
    assert n == pytest.approx(1024, abs=1e-6) and extrapolated
    assert report_aa.samples_to_match(c, 0.5) is None  # worse than one sample


def run_report(*args):
    return subprocess.run([sys.executable, str(REPORT), *map(str, args)], check=True, capture_output=True,
                          text=True).stdout


@pytest.fixture(scope="module")
def run_json(tmp_path_factory):
    bench = os.environ.get("RAYCAST_BENCH")
    if not bench:
        pytest.skip("RAYCAST_BENCH (the raycast-bench binary) not set")
    tmp = tmp_path_factory.mktemp("bench")
    out = tmp / "run.json"
    subprocess.run([bench, "--quick", "--benchmark_filter=" + FILTER, "--benchmark_repetitions=2",
                    "--benchmark_enable_random_interleaving=true", "--summary-size=400x225",
                    "--aa-reference-dir=" + str(tmp / "cache"), "--benchmark_out=" + str(out),
                    "--benchmark_out_format=json"], check=True, capture_output=True, text=True)
    return out


def test_every_table_has_its_rows(run_json):
    text = run_report(run_json, "--rows")
    summary = text[text.index("Error vs run time"):text.index("Skipped backends")]
    for label in ["reference/exact", "scalar/exact", "sse2/fast", "autovec/exact", "reference/exact/world",
                  "book/exact/world", "embree16/float/world"]:
        line = next(l for l in summary.splitlines() if l[4:].startswith(label + " "))
        assert "x " in line, line  # its speedup against the reference of its scene
    assert "* reference/exact " in summary
    for section in ["Store bandwidth", "Every row:", "Regions (--region)", "Antialiasing: error vs run time",
                    "Samples to match the book's RMSE on world", "What each shortcut saves", "Peers on world, 400x225",
                    "Scale (cloud/): sparse particle cloud", "Scale (box/): packed box", "Stiff cases", "Stiff sphere cases", "| unit_sphere_at_10 | 200x112 |"]:
        assert section in text, section
    assert next(l for l in text.splitlines() if l.startswith("  sse2/fast ")).count(".") == 6  # every set
    assert next(l for l in text.splitlines() if l.startswith("  W=1 ")).split()[2:]  # a cell per path


def test_the_rows_order_does_not_matter(run_json, tmp_path):
    data = json.loads(run_json.read_text())
    random.Random(1).shuffle(data["benchmarks"])
    shuffled = tmp_path / "shuffled.json"
    shuffled.write_text(json.dumps(data))
    assert run_report(shuffled) == run_report(run_json)


def test_plots(run_json, tmp_path):
    pytest.importorskip("matplotlib")
    text = run_report(run_json, "--plot", tmp_path / "p.svg")
    for f in ["p.svg", "p-aa.svg", "p-scale.svg"]:
        assert (tmp_path / f).read_text().startswith("<?xml"), f
    assert "Antialiasing plot written to" in text


def test_the_load_rows_carry_the_bare_simdjson_peer(run_json):
    load = [b for b in json.loads(run_json.read_text())["benchmarks"] if b["name"].startswith("load/1")]
    assert load and all(b["bare_simdjson_ns_per_sphere"] > 0 for b in load)
    line = next(l for l in run_report(run_json).splitlines() if l.split()[:1] == ["1"] and "-" in l)
    assert len(line.split()[-3:]) == 3 and "-" not in line.split()[-2]  # parse, bare, prep


def test_write_cloud_prints_the_scale_rows_cloud():
    bench = os.environ.get("RAYCAST_BENCH")
    if not bench:
        pytest.skip("RAYCAST_BENCH (the raycast-bench binary) not set")
    out = subprocess.run([bench, "--write-cloud", "50"], check=True, capture_output=True, text=True).stdout
    scene = json.loads(out)
    assert len(scene["spheres"]) == 50 and scene["camera"]["width"] == 1920
    assert len({s["radius"] for s in scene["spheres"]}) == 1  # one radius, the coverage's
    for bad in ["0", "x", "1e9", "200000000"]:
        r = subprocess.run([bench, "--write-cloud", bad], capture_output=True, text=True)
        assert r.returncode == 2 and r.stdout == "" and r.stderr.count("\n") == 1, (bad, r)
        assert "--write-cloud" in r.stderr


def test_into_writes_the_tables_between_the_markers_and_check_finds_drift(tmp_path):
    run = HERE.parent / "bench" / "results" / "run.json"  # the committed run: no raycast-bench needed
    md, full = tmp_path / "t.md", tmp_path / "full.txt"
    md.write_text("# t\n\nbefore\n\n<!-- tables: report.py begin -->\nold\n<!-- tables: report.py end -->\n\nafter\n")
    args = [sys.executable, str(REPORT), str(run), "--into", str(md), "--full-report", str(full)]
    subprocess.run(args, check=True, capture_output=True, text=True)
    text = md.read_text()
    assert text.startswith("# t\n\nbefore\n\n<!-- tables: report.py begin -->\n") and text.endswith(
        "<!-- tables: report.py end -->\n\nafter\n")
    assert "old" not in text and "```text\nError vs run time" in text and "Peers on world" in text
    assert full.read_text() == run_report(run, "--rows").lstrip("\n")  # the whole report, every row included
    assert subprocess.run(args + ["--check"], capture_output=True).returncode == 0
    md.write_text(text.replace("Peers on world", "Peers on wrld"))
    r = subprocess.run(args + ["--check"], capture_output=True, text=True)
    assert r.returncode == 1 and "+Peers on world" in r.stdout and "Peers on wrld" in md.read_text()  # nothing written
    md.write_text("no markers\n")
    assert subprocess.run(args, capture_output=True).returncode != 0 and md.read_text() == "no markers\n"
