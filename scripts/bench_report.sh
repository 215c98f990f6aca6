#!/usr/bin/env bash
# Report of a bench_all CSV (scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations,
# time_mean_s; rows with error nan — failed solves — are left out). Time per solve: the median, except
# on path scenes (*_path: different warm-started solves along a path) the mean, i.e. the throughput:
#  - OUT_DIR/<scene>.png: error (log) against run time per solve (log), every setting as a point
#    and each method's Pareto front (the settings that no faster setting of the method beats in error)
#    as a line;
#  - Markdown on stdout and in OUT_DIR/report.md: per scene and method the fastest setting reaching
#    error <= 1e-3, 1e-6, 1e-9 (scripts/bench_pareto.sh), then per scene and error level the fastest
#    collocation and the fastest shooting setting of the same run and their time ratio.
# usage: scripts/bench_report.sh [CSV = benchmarks/results/all.csv] [OUT_DIR = benchmarks/results/all]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
csv=${1:-"$root/benchmarks/results/all.csv"}
out_dir=${2:-"$root/benchmarks/results/all"}
mkdir -p "$out_dir"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# One data file per (scene, method): "time error", and its Pareto front.
awk -F, -v dir="$tmp" 'FNR > 1 && $4 + 0 > 0 && $4 != "nan" && $4 != "-nan" && $4 != "inf" {
  print (($1 ~ /_path$/ && NF >= 9) ? $9 : $5), $4 > (dir "/" $1 "@" $2 ".dat")
}' "$csv"
for scene in $(ls "$tmp" | grep '\.dat$' | sed 's/@.*//' | sort -u); do
  plot=""
  index=1
  for f in "$tmp/$scene"@*.dat; do
    method=$(basename "$f" .dat | sed 's/.*@//')
    sort -g -k1,1 "$f" -o "$f"
    awk 'NR == 1 || $2 + 0 < best { print; best = $2 + 0 }' "$f" > "${f%.dat}.front"
    plot+="${plot:+, }'$f' using 1:2 with points pt 7 ps 0.6 lc $index notitle"
    plot+=", '${f%.dat}.front' using 1:2 with linespoints pt 7 ps 0.9 lw 2 lc $index title '$method'"
    index=$((index + 1))
  done
  gnuplot <<GP
set terminal pngcairo size 1000,700
set output '$out_dir/$scene.png'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel '$( [[ $scene == *_path ]] && echo "mean" || echo "median") run time per solve [s]'
set ylabel 'error [length units; m for R5]'
set title '$scene: error vs run time, lines = Pareto front of each method' noenhanced
set key outside bottom center horizontal noenhanced
set grid
plot $plot
GP
  echo "wrote $out_dir/$scene.png" >&2
done

{
  echo "Fastest setting of each method reaching the error (settings: time per solve, error; median, on *_path scenes mean):"
  echo
  bash "$root/scripts/bench_pareto.sh" "$csv"
  echo
  echo "Fastest collocation against fastest shooting setting reaching the error, same run:"
  echo
  awk -F, '
  FNR == 1 { next }
  $4 == "nan" || $4 == "-nan" || $4 == "inf" { next }
  {
    if (!($1 in seen)) { seen[$1] = 1; order[++n] = $1 }
    t = ($1 ~ /_path$/ && NF >= 9) ? $9 : $5
    family = ($2 ~ /^collocation/) ? "c" : (($2 ~ /^shooting/) ? "s" : "")
    if (family == "") next
    for (k = 1; k <= 3; ++k) {
      key = $1 SUBSEP family SUBSEP k
      if ($4 + 0 <= 10 ^ (-3 * k) && (!(key in best) || t + 0 < best[key])) {
        best[key] = t + 0; what[key] = sprintf("%s %s: %.3g ms, %.1e", $2, $3, 1e3 * t, $4)
      }
    }
  }
  END {
    print "| scene | error <= | fastest collocation | fastest shooting | time ratio collocation / shooting |"
    print "|---|---|---|---|---|"
    for (i = 1; i <= n; ++i) {
      for (k = 1; k <= 3; ++k) {
        c = order[i] SUBSEP "c" SUBSEP k; s = order[i] SUBSEP "s" SUBSEP k
        ratio = ((c in best) && (s in best)) ? sprintf("%.3g", best[c] / best[s]) : "-"
        printf "| %s | 1e-%d | %s | %s | %s |\n", order[i], 3 * k, (c in what) ? what[c] : "not reached",
               (s in what) ? what[s] : "not reached", ratio
      }
    }
  }' "$csv"
} | tee "$out_dir/report.md"
