#include "progress_bar.hpp"

#include <unistd.h>

#include <cstdio>

namespace pcr_app {
namespace {

constexpr int kWidth = 30;  // characters of the bar

std::string clock_time(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buffer;
}

}  // namespace

bool stderr_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

ProgressBar::ProgressBar(std::ostream& out, std::string label, std::int64_t total, bool enabled)
    : out_(out),
      label_(std::move(label)),
      total_(total),
      enabled_(enabled && total > 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() {
  finish();
}

void ProgressBar::update(std::int64_t done, std::int64_t failed) {
  done_ = done;
  failed_ = failed;
  if (!enabled_ || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  draw();
}

void ProgressBar::finish() {
  if (!enabled_ || finished_) return;
  draw();
  out_ << "\n";
  out_.flush();
  finished_ = true;
}

void ProgressBar::draw() {
  const double fraction = static_cast<double>(done_) / static_cast<double>(total_);
  const int filled = static_cast<int>(fraction * kWidth);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string bar(static_cast<size_t>(filled), '#');
  bar.resize(kWidth, '.');
  out_ << "\r" << label_ << " [" << bar << "] " << done_ << "/" << total_;
  if (failed_ > 0) out_ << " (" << failed_ << " failed)";
  out_ << " " << clock_time(elapsed);
  if (done_ > 0 && done_ < total_) out_ << ", " << clock_time(elapsed * (1.0 / fraction - 1.0)) << " left";
  out_ << "   ";  // clears the rest of a longer previous line
  out_.flush();
}

}  // namespace pcr_app
