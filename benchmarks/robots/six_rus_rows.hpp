#pragma once
// bench_robots' rows of the 6-RUS robot (scene R6, docs/benchmarks.md).
#include "common/bench_csv.hpp"

namespace pcr::bench {

/// Cold FK (their README FK inputs, 0.5 kg), cold IK (their README IK target, massless) and warm IK
/// along their helix (200 points, 0.5 kg), by collocation at several meshes and by shooting (RK4 N=40,
/// Dormand-Prince 1e-6..1e-10), time beside the error against the shooting reference (Dormand-Prince
/// 1e-12) solved in the same run. Writes CSV rows and prints; returns 0, or 1 when a reference failed.
int bench_six_rus(BenchCsv& csv);

}  // namespace pcr::bench
