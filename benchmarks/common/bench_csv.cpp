#include "common/bench_csv.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace pcr::bench {

Timing summarise(std::vector<double> seconds) {
  if (seconds.empty()) return {};
  std::sort(seconds.begin(), seconds.end());
  const size_t n = seconds.size();
  const double median = n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
  double total = 0.0;
  for (double s : seconds) total += s;
  return {median, seconds.front(), seconds.back(), total / static_cast<double>(n)};
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Timing time_repeated(const std::function<void()>& solve, const Repeats& repeats) {
  std::vector<double> times;
  double total = 0.0;
  while ((static_cast<int>(times.size()) < repeats.min_count || total < repeats.min_seconds) &&
         static_cast<int>(times.size()) < repeats.max_count) {
    const auto t0 = std::chrono::steady_clock::now();
    solve();
    times.push_back(seconds_since(t0));
    total += times.back();
  }
  return summarise(std::move(times));
}

BenchCsv::BenchCsv(const std::string& path) : path_(path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ignored;  // a failure shows as !ok() below
  if (!parent.empty()) std::filesystem::create_directories(parent, ignored);
  out_.open(path);
  if (out_)
    out_ << "scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations,time_mean_s\n" << std::flush;
}

void BenchCsv::row(const std::string& scene, const std::string& method, const std::string& settings,
                   double error, const Timing& timing, double iterations) {
  out_ << scene << ',' << method << ',' << settings << ',';
  if (std::isfinite(error))
    out_ << error;
  else
    out_ << "nan";  // one spelling for every failure (no "-nan", "inf")
  out_ << ',' << timing.median << ',' << timing.min << ',' << timing.max << ',' << iterations << ','
       << timing.mean << '\n'
       << std::flush;
}

}  // namespace pcr::bench
