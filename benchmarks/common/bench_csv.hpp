#pragma once
// What every run-time-vs-error harness shares: the timing of repeated solves (median, min, max, mean
// wall time) and the CSV they all write, one row per (scene, method, settings):
//   scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations,time_mean_s
// The mean is the throughput figure of a path of different solves (R5b: total time / solves; a few
// solves with a fresh factorisation cost several times the median one); the median that of repeats of
// one solve.
// (error nan = failed solve; scripts/plot_bench.sh, bench_pareto.sh and bench_report.sh skip those rows).
#include <chrono>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace pcr::bench {

struct Timing {
  double median = 0.0, min = 0.0, max = 0.0, mean = 0.0;  ///< seconds
};

/// Median (mean of the two middle values for an even count), min, max and mean; zeros when empty.
Timing summarise(std::vector<double> seconds);

/// Wall seconds since t0.
double seconds_since(std::chrono::steady_clock::time_point t0);

/// How often a timed solve repeats: at least min_count times and min_seconds in total, at most
/// max_count times (max_count wins).
struct Repeats {
  int min_count = 1;
  int max_count = 200;
  double min_seconds = 0.2;
};

/// Times each call of `solve` (steady clock), repeated as `repeats` says.
Timing time_repeated(const std::function<void()>& solve, const Repeats& repeats);

/// A harness's CSV: parent folders created and the header written on opening; every row is flushed,
/// so an interrupted run keeps what it measured.
class BenchCsv {
 public:
  explicit BenchCsv(const std::string& path);
  /// False when the file could not be opened (the harness reports it and exits).
  bool ok() const { return static_cast<bool>(out_); }
  const std::string& path() const { return path_; }
  void row(const std::string& scene, const std::string& method, const std::string& settings, double error,
           const Timing& timing, double iterations);

 private:
  std::string path_;
  std::ofstream out_;
};

}  // namespace pcr::bench
