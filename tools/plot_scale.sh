#!/usr/bin/env bash
# The scale benchmark's log–log plot: ns per derivative against N, flange and
# MuJoCo, one colour per scene, the fitted exponents (the "fit" lines) in the
# legend. Reads benchmarks/scale's output and writes docs/scale.svg:
#   build/benchmarks/scale > /tmp/scale.txt && tools/plot_scale.sh /tmp/scale.txt
set -euo pipefail
in=${1:?the scale benchmark output}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenes=(chain_planar chain_spatial chain_spatial_typed tree_legged)
titles=("planar chain" "spatial chain, run-time axes" "spatial chain, typed axes" "floating tree")
for s in "${scenes[@]}"; do
  awk -v s="$s" '$1 == "scale" && $2 == s {
      n = $3; sub("N=", "", n); f = $4; sub("flange_ns=", "", f); m = $5; sub("mujoco_ns=", "", m)
      print n, f, m }' "$in" >"$work/$s.dat"
done
fit() {  # scene, which (flange|mujoco) → exponent
  awk -v s="$1" -v w="$2_exponent=" '$1 == "fit" && $2 == s { for (i = 3; i <= NF; ++i) if (index($i, w) == 1) { sub(w, "", $i); print $i } }' "$in"
}
plot=""
for i in "${!scenes[@]}"; do
  s=${scenes[$i]}; t=${titles[$i]}; c=$((i + 1))
  plot+="\"$work/$s.dat\" using 1:2 with linespoints lc $c pt 7 title \"flange: $t (exponent $(fit "$s" flange))\", "
  plot+="\"$work/$s.dat\" using 1:3 with linespoints lc $c dt 2 pt 6 title \"MuJoCo: $t (exponent $(fit "$s" mujoco))\", "
done
gnuplot <<EOT
set terminal svg size 760,560 font "sans,11"
set output "$root/docs/scale.svg"
set logscale xy 2
set xlabel "links or joints N"
set ylabel "ns per derivative (mj_forward for MuJoCo)"
set key bottom right font "sans,9"
set termoption noenhanced
set grid
set format y "%g"
plot ${plot%, }
EOT
echo "wrote docs/scale.svg"
