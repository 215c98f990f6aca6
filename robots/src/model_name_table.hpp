#pragma once
// Checks shared by the parts of RobotModel's construction (robot_model.cpp, robot_model_tables.cpp).
#include <cmath>
#include <map>
#include <string>

#include "pcr/core/error.hpp"

namespace pcr::model_checks {

inline bool finite(double v) {
  return std::isfinite(v);
}

/// Adds name -> index, rejecting empty and duplicate names.
inline void add_name(std::map<std::string, int>& table, const std::string& kind, const std::string& name,
                     int index) {
  require(!name.empty(), kind, " #", index, " has an empty name");
  require(table.emplace(name, index).second, "duplicate ", kind, " name '", name, "'");
}

}  // namespace pcr::model_checks
