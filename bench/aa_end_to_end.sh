#!/usr/bin/env bash
# Whole-process timings of the antialiased picture (src/scene/README.md, "Antialiasing (ch.
# 7)"): `raycast --scene world --samples 100` at 400x225 on all cores against
# the book's own ch. 7 program (build/bin/book-ch7: one thread, double, virtual
# hittable_list, 100 samples a pixel, P3 on standard output). Each command is
# run RUNS times (after one warm-up); the medians and their ratio are printed,
# with the CPU. hyperfine is used when installed, else python3's perf_counter
# (runs interleaved), else a plain shell loop. Not run by CI or the tests.
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

# Without hyperfine: python3 times each run with perf_counter around the
# process (a shell loop's `date` calls add milliseconds of their own), the two
# commands interleaved run by run so that both see the same noise.
if command -v python3 >/dev/null; then
  python3 - "$runs" "$out" "${ours[@]}" -- "${book[@]}" <<'PY' || exit 1
import statistics, subprocess, sys, time
runs, out = int(sys.argv[1]), sys.argv[2]
split = sys.argv.index("--")
ours, book = sys.argv[3:split], sys.argv[split + 1:]
def once(cmd, stdout):
    t = time.perf_counter()
    r = subprocess.run(cmd, stdout=stdout, stderr=subprocess.PIPE)
    dt = time.perf_counter() - t
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed: {r.stderr.decode(errors='replace').strip()}")
    return dt
with open(f"{out}/book.ppm", "wb") as f:  # warm-up, and the check that both run
    once(book, f)
once(ours, subprocess.DEVNULL)
t_ours, t_book = [], []
for _ in range(runs):
    t_ours.append(once(ours, subprocess.DEVNULL))
    with open(f"{out}/book.ppm", "wb") as f:
        t_book.append(once(book, f))
mo, mb = statistics.median(t_ours), statistics.median(t_book)
print(f"book-ch7 > book.ppm                               median of {runs}: {mb:.4f} s")
print(f"raycast --scene world --samples 100 -o aa.ppm    median of {runs}: {mo:.4f} s (fastest {min(t_ours):.4f})")
print(f"book-ch7 / raycast: {mb / mo:.1f}x")
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
