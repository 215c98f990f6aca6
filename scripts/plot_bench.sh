#!/usr/bin/env bash
# One log-log PNG per scene of error against median run time per solve, one series per method, from
# benchmark CSVs (scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations[,time_mean_s]; rows with
# a non-finite error — failed solves — are left out).
# usage: scripts/plot_bench.sh [csv...]   (default: every benchmarks/results/*.csv but all.csv, whose scenes
# and methods repeat those of the per-harness CSVs: scripts/bench_report.sh plots it)
# writes benchmarks/results/<scene>.png
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out_dir="$root/benchmarks/results"
if [ $# -gt 0 ]; then
  csvs=("$@")
else
  csvs=()
  for f in "$out_dir"/*.csv; do [ "$(basename "$f")" = all.csv ] || csvs+=("$f"); done
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Split into one data file per (scene, method): "time error".
awk -F, -v dir="$tmp" 'FNR > 1 && $4 + 0 > 0 && $4 != "nan" && $4 != "inf" {
  print $5, $4 > (dir "/" $1 "@" $2 ".dat")
}' "${csvs[@]}"
for scene in $(ls "$tmp" | sed 's/@.*//' | sort -u); do
  plot=""
  for f in "$tmp/$scene"@*.dat; do
    method=$(basename "$f" .dat | sed 's/.*@//')
    sort -g "$f" -o "$f"
    plot+="${plot:+, }'$f' using 1:2 with points title '$method'"
  done
  gnuplot <<GP
set terminal pngcairo size 900,650
set output '$out_dir/$scene.png'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'median run time per solve [s]'
set ylabel 'error [length units]'
set title '$scene: error vs run time (cold solves)' noenhanced
set key outside bottom center horizontal noenhanced
set grid
plot $plot
GP
  echo "wrote $out_dir/$scene.png"
done
