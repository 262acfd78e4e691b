#!/usr/bin/env bash
# Issue 27's targets as whole processes, side by side in one run: `tumble inspect` of the
# 1,000,000-triangle torus (binary STL) with the overlap checks, the same with
# --skip-overlap-checks, and assimp's bare read of the file (BM_AssimpReadStl of
# bench_mass_properties, which also writes the file: its best of 3 repetitions in one process).
# tumble's figures are the best of ROUNDS processes each (default 3), run in turns.
# Prints each time and the two ratios (targets: checks/read <= 1.5, checks/skipped <= 1.3).
# Usage: tests/bench/inspect_overlap_ratios.sh [BUILD_DIR] [ROUNDS]   (default: build 3)
set -euo pipefail
. "$(dirname "$0")/whole_process.sh"
file="${TMPDIR:-/tmp}/tumble_bench_torus_1m.stl"

# assimp's read, in milliseconds: the least of the repetitions' real times.
read_ms=$("$bench" --benchmark_filter='^BM_AssimpReadStl/' --benchmark_repetitions=3 \
  --benchmark_format=csv 2>/dev/null |
  awk -F, '$1 ~ /^"BM_AssimpReadStl[\/"]/ && $1 !~ /_(mean|median|stddev|cv)/ {
             t = $3 + 0; if (best == "" || t < best) best = t }
           END { print best }')
[ -f "$file" ] || { echo "inspect_overlap_ratios.sh: $file was not written" >&2; exit 1; }

checks="" skipped=""
for _ in $(seq "$rounds"); do
  checks=$(best "$checks" "$(run_ms "$tumble" inspect "$file")")
  skipped=$(best "$skipped" "$(run_ms "$tumble" inspect --skip-overlap-checks "$file")")
done
awk -v r="$read_ms" -v c="$checks" -v s="$skipped" 'BEGIN {
  printf "assimp bare read (best of 3 in one process)  %7.0f ms\n", r
  printf "tumble inspect, checks on (best process)       %7.0f ms\n", c
  printf "tumble inspect --skip-overlap-checks (best)    %7.0f ms\n", s
  printf "checks on / assimp read    %.2fx (target <= 1.5x)\n", c / r
  printf "checks on / checks skipped %.2fx (target <= 1.3x)\n", c / s
}'
