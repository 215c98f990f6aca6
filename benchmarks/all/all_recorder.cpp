#include <cstdio>

#include "all/all_runs.hpp"

namespace pcr::bench {

bool AllConfig::selected(const std::string& scene) const {
  if (scenes.empty()) return true;
  for (const std::string& prefix : scenes)
    if (scene.compare(0, prefix.size(), prefix) == 0) return true;
  return false;
}

Repeats AllConfig::repeats() const {
  return quick ? Repeats{1, 20, 0.03} : Repeats{1, 200, 0.2};
}

Recorder::Recorder(const std::string& csv_path) : csv_(csv_path) {}

void Recorder::record(const std::string& scene, const std::string& method, const std::string& settings,
                      double error, const Timing& timing, double iterations, const std::string& status) {
  csv_.row(scene, method, settings, error, timing, iterations);
  ++rows_;
  std::printf("[%6.1f s] %-12s %-26s %-12s error %9.2e  median %10.4f ms  mean %10.4f ms  it %6.1f  %s\n",
              seconds_since(start_), scene.c_str(), method.c_str(), settings.c_str(), error,
              1e3 * timing.median, 1e3 * timing.mean, iterations, status.c_str());
  std::fflush(stdout);
}

void Recorder::note(const std::string& text) {
  std::printf("[%6.1f s] %s\n", seconds_since(start_), text.c_str());
  std::fflush(stdout);
}

}  // namespace pcr::bench
