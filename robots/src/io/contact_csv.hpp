#pragma once
// The obstacles and the contact forces as CSV files of write_solution_csv (internal header of
// pcr::robots; docs/results_format.md, "CSV").
#include <filesystem>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr::io_detail {

/// DIR/obstacles.csv (each obstacle's geometry in the world frame at the solution's link poses) and
/// DIR/contacts.csv (per rod, obstacle and collocation cell, or concentrated contact: arc length,
/// density or force magnitude, gap, force vector). Nothing when the model has no obstacles.
void write_contact_csv(const std::filesystem::path& dir, const RobotModel& model,
                       const RobotSolution& solution);

}  // namespace pcr::io_detail
