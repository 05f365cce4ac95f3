#!/usr/bin/env bash
# Instructions (callgrind) and time per derivative of an N-link chain, by one
# or more algorithms, compiled once from tools/probes/chain_derivative.cpp at
# the Release flags against this tree's headers:
#   tools/chain_counts.sh N runtime|typed|planar default,articulated,other [CXXFLAGS...]
# (also articulated_unrolled and articulated_shared: the articulated body with
# its per-link steps forced into one form; and jacobian: the exact Jacobian,
# jacobian(), in place of a derivative)
# Prints one line per algorithm, "chain <axes> N=<n> <algorithm>
# instructions=<i> ns=<t>": t is the median of 3 runs of 3·10⁵ calls, i the
# difference between runs of 2000 and 1000 calls, so that start-up does not
# count. CHAIN_TIME_ONLY=1 skips callgrind (instructions=-).
set -euo pipefail
n=${1:?N}; axes=${2:?axes}; algs=${3:?algorithm}; shift 3
here=$(cd "$(dirname "$0")/.." && pwd)
exe=$(mktemp)
trap 'rm -f "$exe"' EXIT
eigen=$(pkg-config --cflags eigen3 2>/dev/null || echo -I/usr/include/eigen3)
jac=; [[ ,$algs, == *,jacobian,* ]] && jac=-DPROBE_JACOBIAN
g++ -std=c++20 -O3 -DNDEBUG "$@" $jac -DPROBE_N="$n" -DPROBE_AXES="$axes" -I"$here/include" $eigen \
  "$here/tools/probes/chain_derivative.cpp" -o "$exe"
for alg in ${algs//,/ }; do
  count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$exe" "$1" "$alg" 2>&1 | awk '/Collected/ { print $4 }'; }
  if [[ ${CHAIN_TIME_ONLY:-0} == 1 ]]; then instr=-; else instr=$(( ($(count 2000) - $(count 1000)) / 1000 )); fi
  ts=()
  for r in 1 2 3; do
    t0=$(date +%s%N); "$exe" 300000 "$alg" > /dev/null; t1=$(date +%s%N)
    ts+=($(( (t1 - t0) / 300000 )))
  done
  echo "chain $axes N=$n $alg instructions=$instr ns=$(printf '%s\n' "${ts[@]}" | sort -n | sed -n 2p)"
done
