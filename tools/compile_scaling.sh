#!/usr/bin/env bash
# Compile time and compiler memory of a spatial chain of N links (run-time
# axes) as N grows: the derivative only (benchmarks/compile_scaling/chain.cpp.in),
# g++ at the Release flags. For each N it compiles the unit twice: with
# -fsyntax-only (the front end: parsing, template instantiation and the
# constexpr scene analysis) and in full (the optimiser and code generation),
# and prints
#
#   compile chain_spatial N=<n> seconds=<s> max_rss_mb=<m> front_end_seconds=<s>
#
# (From 10 links on, such a chain takes the articulated-body algorithm:
# dynamics/algorithm.hpp.)
#
# Writes build/compile_scaling.csv, and docs/compile_scaling.svg when gnuplot
# is installed (tools/install-deps.sh --plots).
#
#   tools/compile_scaling.sh [N ...]     (default: 8 16 32 64 128)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(8 16 32 64 128)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
flags=(-std=c++20 -O3 -DNDEBUG -I"$root/include" -I/usr/include/eigen3)
csv="$root/build/compile_scaling.csv"
mkdir -p "$root/build"
echo "n,seconds,max_rss_mb,front_end_seconds" >"$csv"
for n in "${sizes[@]}"; do
  src="$work/chain$n.cpp"
  sed -e "s/@N@/$n/g" -e "s/@FULL@/0/" "$root/benchmarks/compile_scaling/chain.cpp.in" >"$src"
  fe=$( { /usr/bin/time -f "%e" g++ "${flags[@]}" -fsyntax-only "$src" ; } 2>&1 | tail -1)
  read -r secs rss < <( { /usr/bin/time -f "%e %M" g++ "${flags[@]}" -c "$src" -o "$work/chain$n.o" ; } 2>&1 | tail -1)
  mb=$((rss / 1024))
  echo "compile chain_spatial N=$n seconds=$secs max_rss_mb=$mb front_end_seconds=$fe"
  echo "$n,$secs,$mb,$fe" >>"$csv"
done
if command -v gnuplot >/dev/null; then
  gnuplot <<EOT
set terminal svg size 640,400 font "sans,12"
set output "$root/docs/compile_scaling.svg"
set datafile separator ","
set logscale xy
set xlabel "links N (spatial chain, run-time axes)"
set ylabel "seconds (g++ 12 -O3)"
set y2label "compiler memory, MB"
set y2tics
set logscale y2
set key top left
set grid
plot "$csv" skip 1 using 1:2 with linespoints title "compile time", \
     "$csv" skip 1 using 1:4 with linespoints title "front end only", \
     "$csv" skip 1 using 1:3 axes x1y2 with linespoints title "memory (right)"
EOT
  echo "wrote docs/compile_scaling.svg"
fi
