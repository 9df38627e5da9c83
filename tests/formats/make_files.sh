#!/bin/sh
# The formats tests' files, written by the real tools into DIR (CTest's
# fixture formats.files): LAMMPS runs in.melt and in.tri, then
# write_peers.py writes the same frames with ASE and gsd; in.same's one
# frame, by same_frame.py, the same numbers in every format.
#   make_files.sh DIR
set -eu
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$1"
mkdir -p "$1"
dir=$(cd "$1" && pwd)
cd "$dir"
for input in in.melt in.tri in.same; do
  if ! lmp -in "$here/$input" -log none -screen none -nocite; then
    echo "lmp -in $input failed" >&2
    exit 1
  fi
done
/usr/bin/python3 "$here/write_peers.py" "$dir"
/usr/bin/python3 "$here/same_frame.py" "$dir"
gzip -kf same.lammpstrj
ls -l "$dir"
