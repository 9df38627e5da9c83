"""bench/report.py --into FILE.md: a compact set of the report's tables written into a Markdown
file between two marker lines, and the whole report into a text file beside the run's JSON;
with --check, both compared with what is there instead (exit 1 and a diff where they differ).

    <!-- tables: report.py begin -->
    ... (everything here is replaced)
    <!-- tables: report.py end -->
"""
import contextlib
import difflib
import io
import os
from collections import defaultdict

from report_common import of_kind
from report_files import print_formats, print_frames, print_particle_files
from report_light import print_light
from report_render import print_peers, print_summary
from report_scale import print_scale_compact

BEGIN = "<!-- tables: report.py begin -->"
END = "<!-- tables: report.py end -->"
LIGHT_N = 1_000_000  # the light rows the Markdown file shows: each family's at this N (or its largest below)


def captured(fn):
    """What fn prints, without its leading and trailing blank lines."""
    with contextlib.redirect_stdout(io.StringIO()) as buf:
        fn()
    return buf.getvalue().strip("\n")


def light_rows_at(rows, n=LIGHT_N):
    """rows with each family's light/ rows at N = n only (its largest N below n, or its smallest, where it has none)."""
    light = of_kind(rows, "light")
    ns = defaultdict(set)
    for r in light:
        ns[r.family].add(int(r.spheres))
    at = {family: max([k for k in s if k <= n] or [min(s)]) for family, s in ns.items()}
    keep = {r.name for r in light if int(r.spheres) == at[r.family]}
    return {name: r for name, r in rows.items() if r.kind != "light" or name in keep}


def views(rows, ctx, srows, size, threads):
    """The Markdown file's tables, each a function printing one: the sky's and world's summary (its
    columns said by the file's text), the peers, light, the scale rows' totals, particle files,
    formats and trajectories."""
    def light():
        print_light(light_rows_at(rows), ctx)
        if of_kind(rows, "light"):
            print("  (each family's rows at N = 10^6, or the nearest N it has; every N in the full report)")
    sky_and_world = [s for s in srows if s["scene"] in ("", "world")]
    return [lambda: print_summary(sky_and_world, ctx, size, threads, legend=False),
            lambda: print_peers(rows, ctx, size), light, lambda: print_scale_compact(rows, ctx),
            lambda: print_particle_files(rows), lambda: print_formats(rows), lambda: print_frames(rows)]


def block(rows, ctx, srows, size, threads, json_path, report_path, md_path):
    """The text between the markers: where the tables come from, then each table as a ```text block."""
    here = os.path.dirname(os.path.abspath(md_path))
    rel = lambda p: os.path.relpath(os.path.abspath(p), here)
    run = {"quick": "a `raycast-bench --quick` run", "full": "a `raycast-bench` run"}.get(ctx.get("pass"), "a run")
    head = (f"From [`{rel(json_path)}`]({rel(json_path)}), {run}: "
            f"{ctx.get('cpu_model', '?')}, {ctx.get('available_cores', '?')} cores, {ctx.get('date', '')[:10]}; "
            f"every table of the run: [`{rel(report_path)}`]({rel(report_path)}).")
    tables = [t for t in (captured(v) for v in views(rows, ctx, srows, size, threads)) if t]
    return "\n\n".join([head] + [f"```text\n{t}\n```" for t in tables])


def replaced(text, inner, path):
    """text with the lines between its BEGIN and END lines replaced by inner."""
    lines = text.split("\n")
    begins = [i for i, line in enumerate(lines) if line.strip() == BEGIN]
    ends = [i for i, line in enumerate(lines) if line.strip() == END]
    if len(begins) != 1 or len(ends) != 1 or ends[0] < begins[0]:
        raise SystemExit(f"report.py: {path} needs one line {BEGIN} and, after it, one line {END}")
    return "\n".join(lines[:begins[0] + 1] + ["", inner, ""] + lines[ends[0]:])


def write_or_check(files, check):
    """files: {path: new text}. Writes each (check: compares each with what is there); 0, or 1 when
    a checked file differs (its diff printed)."""
    stale = 0
    for path, text in files.items():
        old = open(path, encoding="utf-8").read() if os.path.exists(path) else ""
        if not check:
            if old != text:
                with open(path, "w", encoding="utf-8") as f:
                    f.write(text)
            print(f"{path}: {'rewritten' if old != text else 'unchanged'}")
        elif old != text:
            stale = 1
            print(f"{path}: not what report.py makes of the run; the difference:")
            print("".join(difflib.unified_diff(old.splitlines(True), text.splitlines(True), path, "report.py")))
        else:
            print(f"{path}: up to date")
    return stale


def into(md_path, report_path, full_text, rows, ctx, srows, size, threads, json_path, check):
    """--into: the Markdown file's tables and the full report file, written or checked."""
    md = open(md_path, encoding="utf-8").read()
    inner = block(rows, ctx, srows, size, threads, json_path, report_path, md_path)
    stale = write_or_check({md_path: replaced(md, inner, md_path), report_path: full_text}, check)
    if stale:
        print(f"To rewrite them from the run: python3 bench/report.py {json_path} --into {md_path}")
    return stale
