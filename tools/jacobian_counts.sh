#!/usr/bin/env bash
# Instructions (callgrind) per jacobian() and per derivative of the Jacobian
# benchmark's small scenes, compiled once from tools/probes/small_jacobians.cpp
# at the Release flags against this tree's headers:
#   tools/jacobian_counts.sh [scene ...] [-- CXXFLAGS...]
# (scenes: chain_any_1 chain_typed_2 gantry_crane spatial_arm free_body
# tree_legged_1 tree_legged_2 tree_legged_4 fourbar; all of them by default). Prints one line per
# scene, "jacobian <scene> jacobian_instructions=<j>
# derivative_instructions=<d> ratio=<j/d>": each count the difference between
# runs of 2000 and 1000 calls over 1000, so that start-up does not count.
# Instructions are not time (one leg on a floating base is 3.7 derivatives
# in instructions and 4.7 in time: docs/performance.md, "The Jacobian"), but
# they do not move with the machine or with where the code lies.
set -euo pipefail
scenes=()
while [[ $# -gt 0 && $1 != -- ]]; do scenes+=("$1"); shift; done
[[ ${1:-} == -- ]] && shift
[[ ${#scenes[@]} -eq 0 ]] && scenes=(chain_any_1 chain_typed_2 gantry_crane spatial_arm free_body tree_legged_1 tree_legged_2 tree_legged_4 fourbar)
here=$(cd "$(dirname "$0")/.." && pwd)
exe=$(mktemp)
trap 'rm -f "$exe"' EXIT
eigen=$(pkg-config --cflags eigen3 2>/dev/null || echo -I/usr/include/eigen3)
g++ -std=c++20 -O3 -DNDEBUG "$@" -I"$here/include" $eigen "$here/tools/probes/small_jacobians.cpp" -o "$exe"
# Valgrind 3.19 does not know every AVX instruction g++ emits in the passes'
# AVX2 build (the spatial arm's, two legs', four legs'): where it stops, say
# so and go on to the next scene (-- -DFLANGE_NO_AVX2 counts the portable
# build instead).
count() {
  local n
  n=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$exe" "$@" 2>&1 | awk '/Unrecognised instruction/ { bad = 1 } /Collected/ { c = $4 } END { if (!bad) print c }')
  [[ -n $n ]] || { echo "jacobian_counts.sh: valgrind could not run $* to the end (an instruction it does not know?); try -- -DFLANGE_NO_AVX2" >&2; exit 1; }
  echo "$n"
}
for s in "${scenes[@]}"; do
  if ! j2=$(count "$s" 2000) || ! j1=$(count "$s" 1000); then
    echo "jacobian $s skipped: valgrind could not run its Jacobian (-- -DFLANGE_NO_AVX2 counts the portable build)"
    continue
  fi
  d2=$(count "$s" 2000 d); d1=$(count "$s" 1000 d)
  j=$(( (j2 - j1) / 1000 )); d=$(( (d2 - d1) / 1000 ))
  echo "jacobian $s jacobian_instructions=$j derivative_instructions=$d ratio=$(awk -v j="$j" -v d="$d" 'BEGIN { printf "%.2f", j / d }')"
done
