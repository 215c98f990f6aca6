#!/usr/bin/env bash
# CTest smoke test of bench_all (label bench): the quick R1 sweep must write a CSV with the header, 8
# fields per row, positive times, and finite errors for the mixed Newton and both shooting methods, the
# best of each below 1e-8. Bound: the errors are against R1's exact arc and deterministic; the quick
# sweep's finest settings measured 7.1e-11 (mixed p=5 E=64), 8.7e-12 (RK4 N=640) and 8.1e-13
# (Dormand-Prince 1e-12), and the orders of the methods (docs/benchmarks.md "Convergence orders": mixed p=5 order 6, RK4 order 4) put
# them far below 1e-8 (p=5 E=16 alone gives 7.1e-7 and 4^6 less at E=64): 1e-8 leaves a margin of >100x
# while a wrong reference, sampling or solve shows as an error of the size of the discretisation or more.
# usage: smoke_test.sh BENCH_ALL CSV
set -euo pipefail
"$1" --quick --scenes R1 --out "$2" > "$2.log"
awk -F, '
NR == 1 {
  if ($0 != "scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations,time_mean_s") { print "bad header: " $0; bad = 1 }
  next
}
{
  rows++
  if (NF != 9) { print "row " NR ": " NF " fields"; bad = 1 }
  if ($1 != "R1_phi_2pi") { print "row " NR ": unexpected scene " $1; bad = 1 }
  if (!($5 + 0 > 0 && $6 + 0 > 0 && $7 + 0 >= $5 + 0)) { print "row " NR ": bad times"; bad = 1 }
  if ($2 == "collocation-mixed-newton" || $2 ~ /^shooting-/) {
    if ($4 == "nan" || $4 == "inf" || !($4 + 0 >= 0)) { print "row " NR ": error " $4 " for " $2 " " $3; bad = 1; next }
    if (!($2 in best) || $4 + 0 < best[$2]) best[$2] = $4 + 0
  }
}
END {
  split("collocation-mixed-newton shooting-rk4 shooting-dormand_prince", methods, " ")
  for (i = 1; i <= 3; ++i) {
    m = methods[i]
    if (!(m in best)) { print "no rows for " m; bad = 1 }
    else if (best[m] >= 1e-8) { print m ": best error " best[m] " >= 1e-8"; bad = 1 }
    else print m ": best error " best[m]
  }
  print rows " rows"
  exit bad
}' "$2"
