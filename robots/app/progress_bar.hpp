#pragma once
// A progress bar on stderr for the long commands (path, workspace): drawn only when stderr is a terminal,
// redrawn in place ("\r"), at most every 0.1 s; ended by a newline.
#include <chrono>
#include <cstdint>
#include <ostream>
#include <string>

namespace pcr_app {

class ProgressBar {
 public:
  /// enabled = false draws nothing (e.g. stderr is not a terminal: stderr_is_terminal()).
  ProgressBar(std::ostream& out, std::string label, std::int64_t total, bool enabled);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  /// Redraws with `done` of total (skipped within 0.1 s of the last drawing unless done == total).
  void update(std::int64_t done, std::int64_t failed = 0);
  /// Draws the final state and ends the line (once; the destructor calls it).
  void finish();

 private:
  std::ostream& out_;
  std::string label_;
  std::int64_t total_, done_ = 0, failed_ = 0;
  bool enabled_, finished_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
  void draw();
};

bool stderr_is_terminal();

}  // namespace pcr_app
