#pragma once
// Fields of the CSV writers: numbers with 17 significant digits (a double reads back exactly), empty
// when not finite; text quoted as RFC 4180 asks.
#include <cmath>
#include <cstdio>
#include <string>

#include "pcr/robots/pose.hpp"
#include "pcr/rods/stability/stability.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr::io_detail {

inline std::string csv_number(double value) {
  if (!std::isfinite(value)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

/// "text" with every " doubled.
inline std::string csv_quote(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// ",x,y,z,qw,qx,qy,qz" of a pose.
inline std::string csv_pose(const Pose& pose) {
  std::string out;
  for (int k = 0; k < 3; ++k) out += "," + csv_number(pose.position[k]);
  for (int k = 0; k < 4; ++k) out += "," + csv_number(pose.orientation[k]);
  return out;
}

/// ",NAME.x,NAME.y,...,NAME.qz"
inline std::string csv_pose_header(const std::string& name) {
  std::string out;
  for (const char* c : {"x", "y", "z", "qw", "qx", "qy", "qz"}) out += "," + name + "." + c;
  return out;
}

/// The columns of a solve's summary (csv_summary) and of its stability verdict (csv_stability).
inline constexpr const char* kCsvSummaryHeader =
    "status,iterations,residual_max_abs,wall_time_seconds,message";
inline constexpr const char* kCsvStabilityHeader =
    "stability,unstable_modes,stability_margin,stability_reason";

/// "status,iterations,residual_max_abs,wall_time_seconds,"message"" of a solve.
inline std::string csv_summary(const SolveSummary& s) {
  return std::string(to_string(s.status)) + ',' + std::to_string(s.iterations) + ',' +
         csv_number(s.residual_max_abs) + ',' + csv_number(s.wall_time_seconds) + ',' + csv_quote(s.message);
}

/// "verdict,unstable_modes,margin,"reason"": the count and margin empty where nothing was counted
/// (not checked, unknown).
inline std::string csv_stability(const Stability& v) {
  const bool counted = is_counted(v);
  return std::string(to_string(v.verdict)) + ',' + (counted ? std::to_string(v.unstable_modes) : "") + ',' +
         (counted ? csv_number(v.margin) : "") + ',' + csv_quote(v.reason);
}

}  // namespace pcr::io_detail
