#!/usr/bin/env bash
# Start-up of the `tumble` command as a whole process: 100 runs of `tumble inspect` on a
# 12-triangle unit cube, as binary STL (tumble's own reader) and as OBJ (assimp's), and of
# `tumble --help`. Prints the time per run and the largest peak memory of a run.
# Usage: tests/bench/startup.sh [BUILD_DIR]   (default: build)
set -euo pipefail
build=${1:-build}
tumble="$build/app/tumble"
[ -x "$tumble" ] || { echo "startup.sh: $tumble not found (build first)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "startup.sh: needs /usr/bin/time (apt-get install time)" >&2; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# The cube: 8 corners, 12 outward triangles.
corners=("0 0 0" "1 0 0" "1 1 0" "0 1 0" "0 0 1" "1 0 1" "1 1 1" "0 1 1")
faces=("0 2 1" "0 3 2" "4 5 6" "4 6 7" "0 1 5" "0 5 4" "1 2 6" "1 6 5" "2 3 7" "2 7 6" "3 0 4" "3 4 7")
{
  printf 'v %s\n' "${corners[@]}"
  for f in "${faces[@]}"; do set -- $f; echo "f $(($1 + 1)) $(($2 + 1)) $(($3 + 1))"; done
} > "$dir/cube.obj"
# Binary STL: 80-byte header, little-endian count, then per triangle a normal, three corners
# (float32) and two attribute bytes. The floats used are 0 (00000000) and 1 (0000803f).
float() { [ "$1" = 1 ] && printf '\x00\x00\x80\x3f' || printf '\x00\x00\x00\x00'; }
{
  head -c 80 /dev/zero
  printf '\x0c\x00\x00\x00'
  for f in "${faces[@]}"; do
    for _ in 1 2 3; do float 0; done
    for i in $f; do for c in ${corners[$i]}; do float "$c"; done; done
    printf '\x00\x00'
  done
} > "$dir/cube.stl"

measure() {
  local label=$1; shift
  local report
  report=$( { /usr/bin/time -f "%e %M" bash -c 'for i in $(seq 100); do "$@" >/dev/null; done' _ "$@"; } 2>&1 )
  read -r seconds kib <<< "$report"
  awk -v l="$label" -v s="$seconds" -v k="$kib" \
    'BEGIN { printf "%-34s %6.1f ms a run, peak %5.1f MiB\n", l, s * 10, k / 1024 }'
}
measure "inspect cube.stl (tumble's reader)" "$tumble" inspect "$dir/cube.stl"
measure "inspect cube.obj (assimp)" "$tumble" inspect "$dir/cube.obj"
# The same with the worker's heap in 4 KiB pages only (the worker advises huge pages for malloc's
# large blocks unless GLIBC_TUNABLES is set): what the tunable saves.
measure "inspect cube.obj (no huge pages)" env GLIBC_TUNABLES=glibc.malloc.hugetlb=0 \
  "$tumble" inspect "$dir/cube.obj"
measure "--help" "$tumble" --help
