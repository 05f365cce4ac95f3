#!/usr/bin/env bash
# The large-scene test (tests/large_scenes_test.cpp) at a size CI does not
# build: by default a spatial chain of 128 links and a floating tree of four
# 15-link legs (60 joints, 66 rates). Compiles the unit with the flags the
# test build gives it (-O1, warnings on), links it with the allocation
# counter, runs it, and prints
#
#   compile large_scenes chain=<n> legs=<k> seconds=<s> max_rss_mb=<m>
#
# followed by Catch2's summary (LARGE_SCENES_TEST_ARGS are passed to the test:
# "-s" prints every check with its measured error). The test itself checks
# the articulated body against Newton–Euler inverse dynamics (≤ 1e-12) and
# Newton–Euler with the mass matrix (within that reference's ε/rcond(M)) on
# both scenes, and RK4 steps of the chain without the heap.
#
#   tools/large_scenes.sh [chain links] [leg links] [extra compiler flags...]
#   (default: 128 15)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
chain=${1:-128}
legs=${2:-15}
shift $(($# < 2 ? $# : 2))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
flags=(-std=c++20 -O1 -DNDEBUG -Wall -Wextra -Wpedantic -I"$root/include" -I"$root/tests" -I/usr/include/eigen3
       -DFLANGE_LARGE_CHAIN="$chain" -DFLANGE_LARGE_LEGS="$legs" "$@")
g++ -std=c++20 -O2 -c "$root/tests/main.cpp" -o "$work/main.o" &
g++ -std=c++20 -O2 -I"$root/include" -I/usr/include/eigen3 -c "$root/tests/allocation_counter.cpp" -o "$work/alloc.o"
wait
read -r secs rss < <( { /usr/bin/time -f "%e %M" g++ "${flags[@]}" -c "$root/tests/large_scenes_test.cpp" \
                          -o "$work/large.o" ; } 2>&1 | tail -1)
echo "compile large_scenes chain=$chain legs=$legs seconds=$secs max_rss_mb=$((rss / 1024))"
g++ "$work/main.o" "$work/alloc.o" "$work/large.o" -o "$work/large_scenes" \
  -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=aligned_alloc,--wrap=posix_memalign
"$work/large_scenes" ${LARGE_SCENES_TEST_ARGS:-}
