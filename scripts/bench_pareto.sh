#!/usr/bin/env bash
# Pareto summary of benchmark CSVs (format of bench_rods / bench_shooting): per scene and method, the
# fastest setting (median time per solve; for path scenes, *_path, the mean of column 9 when the CSV has
# it: the throughput along the path) whose error is at most 1e-3, 1e-6 and 1e-9, as a Markdown table.
# usage: scripts/bench_pareto.sh csv...
set -euo pipefail
awk -F, '
FNR == 1 { next }
$4 == "nan" || $4 == "-nan" || $4 == "inf" { next }
{
  t = ($1 ~ /_path$/ && NF >= 9) ? $9 : $5
  key = $1 SUBSEP $2
  if (!(key in seen)) { seen[key] = 1; order[++n] = key }
  for (k = 1; k <= 3; ++k) {
    target = 10 ^ (-3 * k)
    if ($4 + 0 <= target && (!((key, k) in best) || t + 0 < best[key, k])) {
      best[key, k] = t + 0; what[key, k] = sprintf("%s: %.2g s, %.1e", $3, t, $4)
    }
  }
}
END {
  print "| scene | method | error <= 1e-3 | error <= 1e-6 | error <= 1e-9 |"
  print "|---|---|---|---|---|"
  for (i = 1; i <= n; ++i) {
    split(order[i], part, SUBSEP)
    line = "| " part[1] " | " part[2]
    for (k = 1; k <= 3; ++k) line = line " | " (((order[i], k) in what) ? what[order[i], k] : "not reached")
    print line " |"
  }
}' "$@"
