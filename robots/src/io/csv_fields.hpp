#pragma once
// Fields of the CSV writers: numbers with 17 significant digits (a double reads back exactly), empty
// when not finite; text quoted as RFC 4180 asks.
#include <cmath>
#include <cstdio>
#include <string>

#include "pcr/robots/pose.hpp"

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

}  // namespace pcr::io_detail
