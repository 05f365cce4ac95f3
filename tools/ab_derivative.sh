#!/usr/bin/env bash
# Time the derivatives of the paper's arm, the crane and the four-bar (a
# loop) of another commit (side a) against this tree's (side b) in one
# program, in turns, so that the machine's drift falls on both alike:
#   tools/ab_derivative.sh REV [CXXFLAGS...]
# Both sides are compiled from tools/probes/ab_scenes.cpp at the Release
# flags, REV's headers in namespace flange_a and this tree's in flange_b
# (Google Benchmark is linked because handwritten.hpp includes it). The
# hand-written closed forms are timed the same way: where they have not
# changed, their two columns are one code twice and their ratio is the noise.
# Prints, per scene and loop (throughput, latency), one line
#   ab <scene> <loop> a_ns=<x> b_ns=<y> ratio=<y/x> (first quartile; medians ...)
set -euo pipefail
rev=${1:?commit to compare with}; shift
here=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'git -C "$here" worktree remove --force "$work/a" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
git -C "$here" worktree add --detach "$work/a" "$rev" >/dev/null  # its errors stay visible
eigen=$(pkg-config --cflags eigen3 2>/dev/null || echo -I/usr/include/eigen3)
flags=(-std=c++20 -O3 -DNDEBUG "$@")
side() {  # side NAME ROOT
  g++ "${flags[@]}" -Dflange=flange_"$1" -DAB_SIDE="$1" -I"$2/include" -I"$2/benchmarks" $eigen \
    -c "$here/tools/probes/ab_scenes.cpp" -o "$work/$1.o"
}
side a "$work/a" &
side b "$here"
wait
g++ "${flags[@]}" -c "$here/tools/probes/ab_driver.cpp" -o "$work/driver.o"
g++ "$work/driver.o" "$work/a.o" "$work/b.o" -o "$work/ab" -lbenchmark -lpthread
"$work/ab"
