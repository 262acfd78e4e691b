#!/usr/bin/env bash
# Issue 27's render-side ratios on the default demo (assets/scenes/t_handle_flip.json, 481 frames
# at 1280x720, FXAA and overlay): in each of ROUNDS rounds, run in turn,
#  - ffmpeg alone, encoding the exact stream the MP4 sink pipes, with the sink's own arguments
#    (both dumped once through a PATH shim `ffmpeg` that saves its arguments and `cat > FILE`);
#  - `tumble render` end to end into an MP4;
#  - the render side alone: the same command with ffmpeg replaced by `cat > /dev/null`;
# and, given OTHER_BUILD_DIR, the last two for that build too (an earlier commit's binaries).
# Prints wall and CPU (user + system, children included) for each, and per round the ratio of
# end to end to ffmpeg alone (target <= 1.5) and of the other build's render-side CPU to this
# one's (target >= 2.5 against the build before issue 27's work).
# Usage: tests/bench/render_demo_ratios.sh [BUILD_DIR] [ROUNDS] [OTHER_BUILD_DIR]  (build 3)
set -euo pipefail
build=${1:-build}
rounds=${2:-3}
other=${3:-}
scene="$(dirname "$0")/../../assets/scenes/t_handle_flip.json"
for tool in "$build/app/tumble" ${other:+"$other/app/tumble"}; do
  [ -x "$tool" ] || { echo "render_demo_ratios.sh: $tool not found (build first)" >&2; exit 1; }
done
command -v ffmpeg >/dev/null || { echo "render_demo_ratios.sh: ffmpeg not found" >&2; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir "$dir/dump" "$dir/sink"
printf '#!/bin/sh\nprintf "%%s\\0" "$@" > "%s"\nexec cat > "%s"\n' "$dir/arguments" \
  "$dir/frames.rgba" >"$dir/dump/ffmpeg"
printf '#!/bin/sh\nexec cat > /dev/null\n' >"$dir/sink/ffmpeg"
chmod +x "$dir/dump/ffmpeg" "$dir/sink/ffmpeg"
PATH="$dir/dump:$PATH" "$build/app/tumble" render "$scene" -o "$dir/dump.mp4" -q

# Runs "$@" under /usr/bin/time; prints "wall cpu" in seconds.
timed() {
  /usr/bin/time -f '%e %U %S' -o "$dir/time" "$@" >/dev/null 2>&1
  awk '{printf "%.2f %.2f\n", $1, $2 + $3}' "$dir/time"
}
# The runs, as commands /usr/bin/time can start. ffmpeg alone: the sink's arguments, its last
# (the output file) replaced, reading the dumped frames.
mapfile -d '' -t arguments <"$dir/arguments"
arguments[-1]="$dir/alone.mp4"
alone=(sh -c 'exec ffmpeg "$@" < "'"$dir/frames.rgba"'"' ffmpeg "${arguments[@]}")
render() { timed "$1/app/tumble" render "$scene" -o "$dir/out.mp4" -q; }
render_side() { timed env PATH="$dir/sink:$PATH" "$1/app/tumble" render "$scene" -o "$dir/out.mp4" -q; }

printf '%-5s %-26s %8s %8s\n' round run wall_s cpu_s
for round in $(seq "$rounds"); do
  read -r alone_wall alone_cpu < <(timed "${alone[@]}")
  read -r end_wall end_cpu < <(render "$build")
  read -r side_wall side_cpu < <(render_side "$build")
  printf '%-5s %-26s %8s %8s\n' "$round" "ffmpeg alone" "$alone_wall" "$alone_cpu" \
    "$round" "end to end" "$end_wall" "$end_cpu" "$round" "render side" "$side_wall" "$side_cpu"
  line="end to end / ffmpeg alone $(awk -v a="$end_wall" -v b="$alone_wall" 'BEGIN{printf "%.2f", a/b}')"
  if [ -n "$other" ]; then
    read -r o_end_wall o_end_cpu < <(render "$other")
    read -r o_side_wall o_side_cpu < <(render_side "$other")
    printf '%-5s %-26s %8s %8s\n' "$round" "other: end to end" "$o_end_wall" "$o_end_cpu" \
      "$round" "other: render side" "$o_side_wall" "$o_side_cpu"
    line="$line; other's render-side CPU / this one's $(awk -v a="$o_side_cpu" -v b="$side_cpu" 'BEGIN{printf "%.2f", a/b}')"
    line="$line; other's end to end / ffmpeg alone $(awk -v a="$o_end_wall" -v b="$alone_wall" 'BEGIN{printf "%.2f", a/b}')"
  fi
  echo "      $line"
done
