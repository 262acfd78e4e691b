# Sourced by the whole-process ratio scripts of tests/bench/, which take [BUILD_DIR] [ROUNDS]:
# sets build, rounds, tumble and bench (bench_mass_properties, which writes the 1M-triangle
# torus), and stops when either is not built.
build=${1:-build}
rounds=${2:-3}
tumble="$build/app/tumble"
bench="$build/tests/bench_mass_properties"
for tool in "$tumble" "$bench"; do
  [ -x "$tool" ] || { echo "$(basename "$0"): $tool not found (build first)" >&2; exit 1; }
done

# One process's wall time in milliseconds (its output thrown away).
run_ms() {
  local start end
  start=$(date +%s%N)
  "$@" >/dev/null
  end=$(date +%s%N)
  echo $(((end - start) / 1000000))
}

# The lesser of two times, the first possibly empty (no run yet): best "$best" "$t".
best() {
  if [ -z "$1" ] || [ "$2" -lt "$1" ]; then echo "$2"; else echo "$1"; fi
}
