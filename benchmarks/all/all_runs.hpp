#pragma once
// bench_all: every method on every scene, one CSV (bench_all.cpp has the overview).
#include <chrono>
#include <string>
#include <vector>

#include "common/bench_csv.hpp"

namespace pcr::bench {

struct AllConfig {
  bool quick = false;               ///< reduced sweeps and repeats (smoke runs, ~1-2 min)
  std::vector<std::string> scenes;  ///< scene name prefixes to run ("R1", "R5a", "R5b_ik"); empty = all
  bool selected(const std::string& scene) const;
  /// Repeats of a timed single solve: full 0.2 s (at least once, at most 200), quick 0.03 s / 20.
  Repeats repeats() const;
};

/// Writes a CSV row and prints a progress line (elapsed time, row, status).
class Recorder {
 public:
  explicit Recorder(const std::string& csv_path);
  bool ok() const { return csv_.ok(); }
  const std::string& path() const { return csv_.path(); }
  void record(const std::string& scene, const std::string& method, const std::string& settings, double error,
              const Timing& timing, double iterations, const std::string& status);
  /// A progress line without a row (references, skipped parts).
  void note(const std::string& text);
  int rows() const { return rows_; }

 private:
  BenchCsv csv_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  int rows_ = 0;
};

/// R1, R2 (alpha = 10), R3, helical spring: collocation and shooting sweeps. False when a reference
/// failed (that scene's dependent rows are skipped).
bool run_rod_scenes(const AllConfig& config, Recorder& out);
/// R5a FK and IK (cold), R5b teleoperation path (warm IK): collocation and shooting sweeps.
bool run_robot_scenes(const AllConfig& config, Recorder& out);
/// contact_post_platform, contact_post_force: planar_post.urdf FK over the middle rod's mesh against a
/// fine-mesh (self-convergence) reference (all_contact.cpp).
bool run_contact_scenes(const AllConfig& config, Recorder& out);

}  // namespace pcr::bench
