#pragma once
// bench_robots' rows of the 6-RUS robot (scene R6, docs/benchmarks.md).
#include "common/bench_csv.hpp"

namespace pcr::bench {

/// Cold FK (their README FK inputs, 0.5 kg), cold IK (their README IK target, massless) and warm IK
/// along their helix (200 points, 0.5 kg), time beside the error against a fine collocation mesh
/// (degree 6, 32 elements per rod) solved in the same run. Writes CSV rows and prints; returns 0, or 1
/// when a reference solve failed.
int bench_six_rus(BenchCsv& csv);

}  // namespace pcr::bench
