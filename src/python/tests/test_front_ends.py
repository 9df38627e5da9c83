"""The three front ends agree: every row of the input table (the command
line's options, the scene file's keys, the Python keywords) walked with the
values users get wrong, through the command line, Python and a scene file
(a dict scene is one): the same verdict and the same words.

Run by CTest (python.pytest) with RAYCAST_CLI the raycast executable."""
import json
import os
import re
import subprocess

import pytest

import raycast
from raycast import _raycast

CLI = os.environ.get("RAYCAST_CLI", "raycast")

# Values users get wrong, per value type, as the command line spells them.
BAD = {
    "integer": ["0", "-1", "1.5", "1e3", "x", "", "99999999999999999999", "4096", "4097", "1025"],
    "real": ["0", "-1", "nan", "inf", "1e400", "x", "", "180", "1e-300"],
    "aspect": ["0", "-1", "16:0", "x", "1e400", "16:9:1"],
    "triple": ["1,2", "1,2,x", "nan,0,0", "0,0,0", "1e31,0,0", "1,2,3,4", ""],
    "name": ["bogus", ""],
    "seed": ["-1", "x", "18446744073709551616", "1.5"],
    "region": ["0,0,10.5,10", "1,2,3", "5,5,1,1", "0,0,100000,10", "x"],
    "interval": ["1", "1,x", "5,1", "1,1", "nan,1", "1,2,3", "0,1"],
}
JSON_NUMBER = re.compile(r"-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?$")


def rows():
    for r in _raycast.input_table():
        if r["keyword"] and r["option"] and r["type"] in BAD and r["keyword"] != "format":
            values = list(BAD[r["type"]])
            if r["type"] == "name":  # a slip of each name: its last letter dropped
                values += [n[:-1] for n in r["names"]]
            for v in values:
                yield pytest.param(r, v, id=f"{r['keyword']}={v}")


def cli_verdict(tmp_path, row, token):
    """None when the command line renders, else the words after '--option: '."""
    out = tmp_path / "out.ppm"
    p = subprocess.run([CLI, "-q", f"{row['option']}={token}", "-o", str(out)], capture_output=True, text=True)
    if p.returncode == 0:
        return None
    prefix = f"raycast: error: {row['option']}: "
    assert p.returncode == 2 and p.stderr.startswith(prefix) and p.stderr.count("\n") == 1, p.stderr
    assert not out.exists()
    return p.stderr[len(prefix):-1]


def python_verdict(field, call):
    """None when the call renders, else the words after 'FIELD: '."""
    try:
        call()
    except (ValueError, TypeError) as e:
        assert e.field == field, str(e)
        assert str(e).startswith(field + ": "), str(e)
        return str(e)[len(field) + 2:]
    return None


def json_text(row, token):
    """The token as a scene file would hold it, as written, or None where
    JSON has no such value (a number JSON cannot write is a JSON type error,
    in its own words)."""
    t = row["type"]
    if t in ("integer", "real"):
        return token if JSON_NUMBER.match(token) else None
    if t == "triple":
        parts = token.split(",")
        return f"[{token}]" if len(parts) == 3 and all(JSON_NUMBER.match(p) for p in parts) else None
    return json.dumps(token)  # names and aspects are strings in a file too


@pytest.mark.parametrize("row, token", rows())
def test_every_front_end_gives_the_same_verdict_in_the_same_words(tmp_path, row, token):
    keyword, key = row["keyword"], row["file_key"]
    field = key or keyword
    want = cli_verdict(tmp_path, row, token)
    assert python_verdict(field, lambda: raycast.render(**{keyword: token})) == want
    if not key:
        return
    value = json_text(row, token)
    if value is None:
        return
    section, name = key.split(".")
    f = tmp_path / "s.json"
    f.write_text(f'{{"{section}": {{"{name}": {value}}}}}')
    got = python_verdict(field, lambda: raycast.render(f))
    if got is not None:  # the file's name first, and its place last where the value has one
        assert got.startswith(f"{f}: "), got
        got = re.sub(r" \(at line \d+, column \d+: .*\)$", "", got[len(f"{f}: "):])
    assert got == want


def test_every_keyword_is_a_table_row_and_every_row_a_keyword():
    import inspect
    table = {r["keyword"] for r in _raycast.input_table() if r["keyword"]} - {"format", "path"}
    params = set(inspect.signature(raycast.render).parameters)
    own = {"scene", "atoms", "centers", "radii", "colors", "dtype"}
    assert params - own == table


def test_docstrings_list_the_tables_names():
    doc = raycast.render.__doc__
    assert not re.search(r"<[a-z]+>", doc)  # every placeholder filled
    for name in raycast.builtin_scenes():
        assert f'"{name}"' in doc
    for r in _raycast.input_table():
        if r["keyword"] in ("backend", "precision", "sampler", "projection"):
            for n in r["names"]:
                assert f'"{n}"' in doc, n
