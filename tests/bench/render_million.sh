#!/usr/bin/env bash
# Issue 27's whole-process target for big meshes: a 1,000,000-triangle body (the torus of
# bench_mass_properties, binary STL) rendered by `tumble render` into a 120-frame MP4 at
# 1280x720 with the demo's arrows, herpolhode and overlay, FXAA on. Prints the best of ROUNDS
# processes (default 3) for the whole command and for its start-up alone (`--frames 0:1`:
# reading, checks, mass properties, upload and the level of detail the first frame needs),
# and the whole process's frames a second (target >= 30).
# Usage: tests/bench/render_million.sh [BUILD_DIR] [ROUNDS]   (default: build 3)
set -euo pipefail
. "$(dirname "$0")/whole_process.sh"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mesh="${TMPDIR:-/tmp}/tumble_bench_torus_1m.stl"
[ -f "$mesh" ] || "$bench" --benchmark_filter='^BM_AssimpReadStl/' >/dev/null
[ -f "$mesh" ] || { echo "render_million.sh: $mesh was not written" >&2; exit 1; }
cat >"$dir/million.json" <<JSON
{
  "name": "a million triangles",
  "duration": 4.0,
  "dt": 0.001,
  "integrator": "rk4",
  "bodies": [{"name": "torus", "mesh": "$mesh", "density": 1000,
              "angular_velocity": [0.3, 2.0, 0.1]}],
  "render": {"size": [1280, 720], "fps": 30,
             "camera": {"mode": "fixed", "azimuth": -20, "elevation": 20, "fov": 40},
             "show": {"angular_velocity": true, "angular_momentum": true, "herpolhode": true,
                      "overlay": true}}
}
JSON

whole="" start_up=""
for _ in $(seq "$rounds"); do
  whole=$(best "$whole" "$(run_ms "$tumble" render "$dir/million.json" -o "$dir/out.mp4" -q --frames 0:120)")
  start_up=$(best "$start_up" "$(run_ms "$tumble" render "$dir/million.json" -o "$dir/one.mp4" -q --frames 0:1)")
done
awk -v w="$whole" -v s="$start_up" 'BEGIN {
  printf "120 frames, whole process (best)   %6.0f ms\n", w
  printf "start-up alone, --frames 0:1 (best) %6.0f ms\n", s
  printf "whole process: %.1f frames/s (target >= 30)\n", 120000 / w
}'
