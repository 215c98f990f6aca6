#pragma once
// Writers of a solved robot (forward or inverse kinematics result). SI units in files (m, rad, N,
// N m); the human-readable table uses mm and degrees. A file that cannot be written throws InputError
// naming its path. Formats: docs/results_format.md.
#include <ostream>
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr {

/// Short table: summary line, inputs, platform poses (mm, rpy deg, quaternion), per rod length,
/// axial force and base force norm.
void write_solution_table(std::ostream& out, const RobotModel& model, const RobotSolution& solution);

/// JSON object with model, status, inputs, platforms, rods, summary (and targets when given), see
/// docs/results_format.md. Non-finite numbers are written as null; returns how many there were.
int write_solution_json(std::ostream& out, const RobotModel& model, const RobotSolution& solution,
                        const std::vector<LinkTarget>& targets = {});

/// File name of a rod's centerline CSV: "rod_<name>.csv", characters other than [A-Za-z0-9._-]
/// replaced by '_'.
std::string rod_csv_file_name(const std::string& rod_name);

/// DIR/platforms.csv, DIR/inputs.csv and one DIR/rod_<name>.csv (s,x,y,z) per rod; creates DIR.
/// Non-finite numbers are written as empty fields.
void write_solution_csv(const std::string& directory, const RobotModel& model, const RobotSolution& solution);

/// Legacy ASCII VTK POLYDATA: one polyline per rod (centerline), then the outlines of the base and the
/// platforms (robot_outline.hpp) as polygons (closed outlines) or polylines (collinear points); cell data
/// "part" = rod index, -1 for the base outline, -2 - p for platform p. Throws InputError if a coordinate is
/// not finite.
void write_solution_vtk(const std::string& path, const RobotModel& model, const RobotSolution& solution);

}  // namespace pcr
