#!/usr/bin/env bash
# Whole-process timings of the antialiased picture (SPEC.md "Antialiasing (ch.
# 7)"): `raycast --scene world --samples 100` at 400x225 on all cores against
# the book's own ch. 7 program (build/bin/book-ch7: one thread, double, virtual
# hittable_list, 100 samples a pixel, P3 on standard output). Each command is
# run RUNS times (after one warm-up); the medians and their ratio are printed,
# with the CPU. hyperfine is used when installed, else a plain loop. Not run by
# CI or the tests.
#   usage: bench/aa_end_to_end.sh [build-dir] [runs]     (default: build 11)
set -uo pipefail
build=${1:-build}
runs=${2:-11}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "CPU: $(lscpu | sed -n 's/^Model name: *//p' | head -1) ($(nproc) cores available)"
ours=("$build/bin/raycast" --scene world --samples 100 -o "$out/aa.ppm")
book=("$build/bin/book-ch7")

# Median wall time in seconds of `runs` runs of "$@" (stdout to $out/stdout,
# stderr to $out/stderr); fails when a run fails.
median_seconds() {
  "$@" >"$out/stdout" 2>"$out/stderr" || return 1  # warm-up, and the check that it runs
  local times=() t0 t1
  for ((k = 0; k < runs; ++k)); do
    t0=$(date +%s%N)
    "$@" >"$out/stdout" 2>"$out/stderr" || return 1
    t1=$(date +%s%N)
    times+=($((t1 - t0)))
  done
  printf '%s\n' "${times[@]}" | sort -n | awk '{ t[NR] = $1 } END {
    m = NR % 2 ? t[(NR + 1) / 2] : (t[NR / 2] + t[NR / 2 + 1]) / 2; printf "%.4f\n", m / 1e9 }'
}

if command -v hyperfine >/dev/null; then
  hyperfine -N --warmup 1 --runs "$runs" --export-json "$out/h.json" \
    "${ours[*]}" "sh -c '${book[*]} >$out/book.ppm 2>/dev/null'" || exit 1
  python3 - "$out/h.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["results"]
for x in r:
    print(f"{x['command']}: median {x['median']:.4f} s")
print(f"book-ch7 / raycast: {r[1]['median'] / r[0]['median']:.1f}x")
PY
  exit 0
fi

book_s=$(median_seconds "${book[@]}") || { echo "book-ch7 failed:"; cat "$out/stderr"; exit 1; }
cp "$out/stdout" "$out/book.ppm"
echo "book-ch7 > book.ppm                               median of $runs: $book_s s ($(head -c 2 "$out/book.ppm"), $(wc -l <"$out/book.ppm") lines)"
if ours_s=$(median_seconds "${ours[@]}"); then
  echo "raycast --scene world --samples 100 -o aa.ppm    median of $runs: $ours_s s"
  awk -v b="$book_s" -v o="$ours_s" 'BEGIN { printf "book-ch7 / raycast: %.1fx\n", b / o }'
else
  echo "raycast --scene world --samples 100 -o aa.ppm failed:"
  sed 's/^/  /' "$out/stderr"
  exit 1
fi
