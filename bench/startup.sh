#!/usr/bin/env bash
# Whole-command timings of the CLI ("leave out what the job does not
# need"): a PPM must not load OpenImageIO at all, and a PNG must cost no more
# than a bare program that links OpenImageIO and writes the same file.
#   usage: bench/startup.sh [build-dir]     (needs hyperfine: apt-get install hyperfine)
set -euo pipefail
build=${1:-build}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
hyperfine -N --warmup 5 --runs 50 \
  "$build/bin/raycast -o $out/sky.ppm" \
  "$build/bin/raycast -o - --quiet"
hyperfine -N --warmup 3 --runs 40 \
  "$build/bin/oiio-png-baseline $out/baseline.png" \
  "$build/bin/raycast -o $out/sky.png"
cmp "$out/baseline.png" "$out/sky.png" && echo "sky.png is byte-identical to the baseline's"
