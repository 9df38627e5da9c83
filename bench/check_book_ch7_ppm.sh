#!/bin/sh
# CTest's check of book-ch7 (BookCh7.WritesTheBooksPpm): it runs to the end and
# writes the book's picture as the book does, a 400x225 P3 PPM ("P3", "400
# 225", "255", then one "r g b" line a pixel), every value in 0..255, the sky
# (blue the largest channel) in the top-left pixel and the ground (green the
# largest) in the bottom-right one: the book's rows run top first.
#   usage: check_book_ch7_ppm.sh path/to/book-ch7
out=$(mktemp) || exit 1
trap 'rm -f "$out"' EXIT
"$1" >"$out" 2>/dev/null || { echo "book-ch7 failed"; exit 1; }
awk '
  NR == 1 { if ($0 != "P3") { print "line 1: " $0; bad = 1 } next }
  NR == 2 { if ($0 != "400 225") { print "line 2: " $0; bad = 1 } next }
  NR == 3 { if ($0 != "255") { print "line 3: " $0; bad = 1 } next }
  {
    if (NF != 3 || $0 !~ /^[0-9]+ [0-9]+ [0-9]+$/ || $1 > 255 || $2 > 255 || $3 > 255) {
      if (!bad) print "line " NR ": " $0
      bad = 1
    }
    px++
    if (px == 1 && !($3 > $1 && $3 > $2)) { print "top-left pixel is not sky: " $0; bad = 1 }
    last = $0; lr = $1; lg = $2; lb = $3
  }
  END {
    if (px != 400 * 225) { print px " pixels, not 90000"; bad = 1 }
    if (!(lg > lr && lg > lb)) { print "bottom-right pixel is not ground: " last; bad = 1 }
    exit bad
  }' "$out"
