#!/usr/bin/env bash
# Instruction counts per derivative evaluation of every variant in
# benchmarks/effects.cpp, with valgrind's callgrind (repeatable, unlike time):
#   tools/effect_counts.sh [build/benchmarks/effects] > counts.txt
# Prints "<scene>/<effect>/<variant> <instructions per call>".
set -euo pipefail
exe=${1:-build/benchmarks/effects}
n=20000
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for v in $("$exe" --list); do
  valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect='*evaluate_n*' "$exe" --count "$v" "$n" \
    2>&1 | awk -v v="$v" -v n="$n" '/Collected/ { printf "%s %.0f\n", v, $4 / n }'
done
