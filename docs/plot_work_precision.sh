#!/usr/bin/env bash
# Draws one log-log work-precision diagram per scene with gnuplot, from the CSV
# that build/benchmarks/work_precision --csv writes: the error at the final
# time against the median wall time per simulated second, one curve per
# stepper (flange's solid, peer simulators' dashed).
#
#   docs/plot_work_precision.sh [CSV] [OUTDIR]     (defaults: docs/work_precision.csv, docs)
#
# Writes OUTDIR/work_precision_<scene>.png. tools/install-deps.sh --plots
# installs gnuplot.
set -euo pipefail
csv=${1:-docs/work_precision.csv}
out=${2:-docs}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for scene in $(awk -F, 'NR > 1 { print $1 }' "$csv" | sort -u); do
  # One data file per stepper, in the order the CSV first names them.
  awk -F, -v s="$scene" -v d="$tmp" '
    NR > 1 && $1 == s {
      if (!($2 in idx)) { idx[$2] = ++n; names[n] = $2 }
      print $5, $6 > (d "/" s "." idx[$2])
    }
    END { for (i = 1; i <= n; ++i) print names[i] > (d "/" s ".names") }' "$csv"
  plots=()
  i=0
  while IFS= read -r name; do
    i=$((i + 1))
    dash=1
    [[ $name == *:* ]] && dash=2   # "mujoco: RK4", "simbody: …"
    plots+=("'$tmp/$scene.$i' using 1:2 with linespoints lw 2 dt $dash pt $(((i - 1) % 13 + 1)) ps 1.1 title '${name//\'/}'")
  done < "$tmp/$scene.names"
  cmd=$(IFS=,; echo "${plots[*]}")
  gnuplot <<GP
set terminal pngcairo size 1000,700 font "DejaVu Sans,10" noenhanced
set output "$out/work_precision_$scene.png"
set title "$scene: what accuracy costs (error at the final time against median time per simulated second)"
set logscale xy
set format x "1e%T"
set format y "1e%T"
set xlabel "error at T (max over states of |x - x_ref| / (1 + |x_ref|))"
set ylabel "wall time per simulated second [s]"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key outside right top
set xrange [*:1] reverse
plot $cmd
GP
  echo "wrote $out/work_precision_$scene.png"
done
