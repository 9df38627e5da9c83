#!/usr/bin/python3
"""Runs every ```sh block of a Markdown file, as a reader would, and checks
what the blocks promise.

    run_readme_blocks.py --source SRC --bindir BIN FILE.md

The blocks of one file run in order, each as `bash -e -o pipefail`, in one
scratch directory that looks like the repository root: every top-level entry
of SRC is linked there, and `build` links to the build tree (BIN's parent), so
a block may say `raycast …` (BIN is first on PATH), `build/bin/raycast …` or
read `tests/golden/…`, and whatever it writes lands in the scratch directory.
HOME is a scratch folder too (with ~/.parallel/will-cite: GNU parallel's
citation notice is not ours to print).

After each block: every file it names with `-o FILE` / `--output FILE` (no
shell expansion in the name; not on a line with `||`, which shows a command
failing), every file an `outputs:` marker names, must
exist, be new or rewritten, and be what its extension says (PNG, PPM, EXR,
TIFF, JPEG by their first bytes; SVG; JSON that parses).

HTML comments on the lines just before a block (blank lines between are
fine) are markers:

    <!-- not run: WHY -->           the block is skipped; the reason is printed
    <!-- outputs: A B … -->         files the block must write
    <!-- same pixels: A B -->       after the block, A and B have the same size
                                    and bit-identical pixels (oiiotool --diff
                                    with zero thresholds), whatever their
                                    metadata; several markers may be given

A command shown failing promises its exit status, and the message it
quotes is the one printed, word for word:

    raycast -w 0 -o x.png || echo "exit status $?"   # 2: raycast: error: --width: '0' is too small (at least 1)
    raycast --scene bad.json -o x.png || echo "exit status $?"   # 2, and no x.png (the status only)

Exit 0 when every block that runs succeeds and every check holds; otherwise
the first failure's block, output and cause, and exit 1.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

FAILING = re.compile(r'^(?P<cmd>\s*\S.*?)\s*\|\|\s*echo "exit status \$\?"\s*#\s*(?P<code>\d+)\b'
                     r'(?::\s*(?P<message>raycast: error: .*?)|[^:].*)?\s*$')
SHOWN_FAILING = re.compile(r'\|\|\s*echo "exit status \$\?"')
FENCE = re.compile(r"^(```+)\s*([A-Za-z0-9_+-]*)\s*$")
MARKER = re.compile(r"^<!--\s*(not run|outputs|same pixels)\s*:\s*(.*?)\s*-->\s*$")
OUTPUT_OPTION = re.compile(r"(?:^|\s)(?:-o|--output)(?:\s+|=)([^\s;&|)'\"]+)")
MAGIC = {
    ".png": [b"\x89PNG\r\n\x1a\n"],
    ".ppm": [b"P6", b"P3"],
    ".pnm": [b"P6", b"P3"],
    ".exr": [b"\x76\x2f\x31\x01"],
    ".tif": [b"II*\x00", b"MM\x00*"],
    ".tiff": [b"II*\x00", b"MM\x00*"],
    ".jpg": [b"\xff\xd8\xff"],
    ".jpeg": [b"\xff\xd8\xff"],
}


def read_blocks(path):
    """(line number, language, text, markers) of each fenced block."""
    lines = open(path, encoding="utf-8").read().splitlines()
    markers, i = [], 0
    while i < len(lines):
        line = lines[i]
        m = MARKER.match(line)
        f = FENCE.match(line)
        if m:
            markers.append((m.group(1), m.group(2)))
        elif f:
            fence, lang = f.groups()
            j = i + 1
            while j < len(lines) and lines[j].strip() != fence:
                j += 1
            if j == len(lines):
                raise SystemExit(f"{path}:{i + 1}: a ``` block that never closes")
            yield i + 1, lang, "\n".join(lines[i + 1:j]) + "\n", markers
            markers, i = [], j
        elif line.strip():
            markers = []  # a marker belongs to the block right after it
        i += 1


def promised_outputs(text, markers):
    names = []
    for line in text.splitlines():
        if line.lstrip().startswith("#") or "||" in line:
            continue  # a comment, or a command shown failing (`cmd || echo ...`)
        for name in OUTPUT_OPTION.findall(line):
            if name != "-" and not name.startswith("/dev/") and not any(c in name for c in "${}*?"):
                names.append(name)
    for kind, arg in markers:
        if kind == "outputs":
            names += arg.split()
    return list(dict.fromkeys(names))


def watch_failing(text, scratch, tag):
    """The block with each command shown failing made to record its exit
    status and standard error (still shown), and what each promised:
    (status file, error file, code, message or None, the line)."""
    lines, promises = [], []
    for line in text.splitlines():
        m = FAILING.match(line)
        if SHOWN_FAILING.search(line) and not m:
            raise SystemExit(f"a command shown failing without '# CODE' or '# CODE: raycast: error: ...': {line}")
        if m:
            k = len(promises)
            status, err = os.path.join(scratch, f"status-{tag}-{k}"), os.path.join(scratch, f"stderr-{tag}-{k}")
            line = (f'{{ {m["cmd"]} ; }} 2>{err} || echo "exit status $?" | tee {status}; cat {err} >&2')
            promises.append((status, err, int(m["code"]), m["message"], m["cmd"].strip()))
        lines.append(line)
    return "\n".join(lines) + "\n", promises


def broken_promises(promises):
    """Why a command shown failing did not fail as its comment says."""
    problems = []
    for status, err, code, message, cmd in promises:
        got = int(open(status).read().split()[-1]) if os.path.exists(status) else 0
        if got != code:
            problems.append(f"`{cmd}` exited {got}, its comment says {code}")
        printed = open(err, encoding="utf-8", errors="replace").read() if os.path.exists(err) else ""
        if message is not None and printed != message + "\n":
            problems.append(f"`{cmd}` printed {printed.strip()!r}, its comment quotes {message!r}")
    return problems


def stat_key(path):
    try:
        s = os.stat(path)
        return (s.st_ino, s.st_mtime_ns, s.st_size)
    except FileNotFoundError:
        return None


def check_file(path, before):
    """None when path is a new or rewritten file of its kind, else why not."""
    key = stat_key(path)
    if key is None:
        return "was not written"
    if key == before:
        return "was not rewritten (it is the file from before this block)"
    data = open(path, "rb").read(64 * 1024)
    if not data:
        return "is empty"
    ext = os.path.splitext(path)[1].lower()
    if ext in MAGIC and not any(data.startswith(m) for m in MAGIC[ext]):
        return f"is not a {ext[1:].upper()} file (it starts {data[:8]!r})"
    if ext == ".svg" and b"<svg" not in data:
        return "is not an SVG file"
    if ext == ".json":
        try:
            json.load(open(path, encoding="utf-8"))
        except ValueError as e:
            return f"is not JSON ({e})"
    return None


def same_pixels(pairs, cwd, env):
    """None when each pair (A, B) has the same size and bit-identical pixels.
    One oiiotool process for all pairs (loading OpenImageIO is most of the
    cost): each --diff compares the two images pushed before it, and the exit
    status is 1 when any comparison failed."""
    if shutil.which("oiiotool", path=env["PATH"]) is None:
        return "oiiotool is missing (Debian openimageio-tools, installed by .ci/deps)"
    cmd = ["oiiotool", "--fail", "0", "--warn", "0", "--hardfail", "0"]
    for a, b in pairs:
        cmd += [a, b, "--diff"]
    r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        return f"pixels differ (oiiotool --diff, exit {r.returncode}):\n{r.stdout}{r.stderr}"
    return None


def make_scratch(source, bindir):
    """(scratch, work, env): a scratch directory whose repo/ links the source tree's entries and the build,
    and the environment the blocks run in (a HOME of their own, the build's bin first on PATH)."""
    scratch = tempfile.mkdtemp(prefix="raycast-docs-")
    work, home = os.path.join(scratch, "repo"), os.path.join(scratch, "home")
    os.makedirs(work)
    os.makedirs(os.path.join(home, ".parallel"))
    open(os.path.join(home, ".parallel", "will-cite"), "w").close()
    for entry in os.listdir(source):
        if entry not in (".git", "build") and not entry.startswith("build-"):
            os.symlink(os.path.join(source, entry), os.path.join(work, entry))
    os.symlink(os.path.dirname(bindir), os.path.join(work, "build"))
    env = dict(os.environ)
    for var in ("PYTHONPATH", "OMP_NUM_THREADS", "SOURCE_DATE_EPOCH", "RAYCAST_MAX_ISA"):
        env.pop(var, None)
    env.update(HOME=home, XDG_CACHE_HOME=os.path.join(home, ".cache"), LC_ALL="C.UTF-8",
               PATH=bindir + os.pathsep + env.get("PATH", "/usr/bin:/bin"))
    return scratch, work, env


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True, help="the repository root")
    ap.add_argument("--bindir", required=True, help="the build's bin folder (raycast, raycast-bench)")
    ap.add_argument("--keep", action="store_true", help="keep the scratch directory")
    ap.add_argument("markdown")
    args = ap.parse_args()
    source = os.path.abspath(args.source)
    bindir = os.path.abspath(args.bindir)
    doc = os.path.relpath(os.path.abspath(args.markdown), source)

    scratch, work, env = make_scratch(source, bindir)
    failed, ran, skipped, started = None, 0, 0, time.monotonic()
    try:
        for line, lang, text, markers in read_blocks(args.markdown):
            if lang != "sh":
                continue
            where = f"{doc}:{line}"
            not_run = [arg for kind, arg in markers if kind == "not run"]
            if not_run:
                print(f"{where}: not run: {not_run[0]}")
                skipped += 1
                continue
            outputs = promised_outputs(text, markers)
            before = {o: stat_key(os.path.join(work, o)) for o in outputs}
            t0 = time.monotonic()
            watched, promises = watch_failing(text, scratch, line)
            r = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", watched], cwd=work, env=env,
                               stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=300)
            took = time.monotonic() - t0
            problems = []
            if r.returncode != 0:
                problems.append(f"the block exited {r.returncode}")
            else:
                problems += broken_promises(promises)
                for o in outputs:
                    why = check_file(os.path.join(work, o), before[o])
                    if why:
                        problems.append(f"{o} {why}")
                pairs = [arg.split() for kind, arg in markers if kind == "same pixels"]
                for pair in pairs:
                    if len(pair) != 2:
                        problems.append(f"a same pixels marker names {len(pair)} files, not 2")
                if pairs and not problems:
                    why = same_pixels(pairs, work, env)
                    if why:
                        problems.append(why)
            if problems:
                failed = (where, text, r, problems)
                break
            ran += 1
            checks = ", ".join(outputs) if outputs else "no files"
            pixels = [arg for kind, arg in markers if kind == "same pixels"]
            if pixels:
                checks += "; same pixels: " + ", ".join(p.replace(" ", " = ") for p in pixels)
            print(f"{where}: ok in {took:.1f} s (checked {checks})")
    finally:
        if args.keep:
            print(f"scratch directory kept: {work}")
        else:
            shutil.rmtree(scratch, ignore_errors=True)

    if failed:
        where, text, r, problems = failed
        print(f"\n{where}: FAILED: " + "; ".join(problems))
        print("---- the block ----\n" + text.rstrip())
        if r.stdout.strip():
            print("---- its standard output (the end) ----\n" + r.stdout[-4000:].rstrip())
        if r.stderr.strip():
            print("---- its standard error (the end) ----\n" + r.stderr[-4000:].rstrip())
        return 1
    print(f"{doc}: {ran} block(s) ran, {skipped} not run, in {time.monotonic() - started:.1f} s")
    if ran + skipped == 0:
        print(f"{doc}: no ```sh block (nothing to run)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
