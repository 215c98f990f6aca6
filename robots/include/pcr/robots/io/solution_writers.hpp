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

class JsonWriter;

/// The reached world pose of a named link (e.g. a tool link carried by a platform).
struct LinkPose {
  std::string link;
  Pose pose;
};

/// Parts of a report that the writers cannot compute from a RobotSolution alone; each is written only
/// when not empty.
struct SolutionExtras {
  std::vector<LinkPose> links;  ///< links to report besides the platforms
  /// d(platform poses)/d(inputs), ForwardKinematics::input_jacobian(): 6 rows per platform
  /// [dx, dy, dz (m), dtheta_x, dtheta_y, dtheta_z (rad, world frame)], one column per input.
  MatX input_jacobian;
  /// Per platform d(pose)/d(wrench at its origin), ForwardKinematics::compliance(): 6 x 6, columns
  /// force (N) then torque (N m), rows as input_jacobian's; world frame.
  std::vector<MatX> compliance;
};

/// Joint values of a solution: the inputs' (joint_values_of_inputs), and the passive joints' values
/// when the solution carries them (RobotSolution::passive_joints of the model's size).
VecX joint_values_of_solution(const RobotModel& model, const RobotSolution& solution);

/// World poses of the named links in the solution (throws InputError naming an unknown link).
std::vector<LinkPose> link_poses(const RobotModel& model, const RobotSolution& solution,
                                 const std::vector<std::string>& links);

/// Short table: summary line, inputs, platform poses (mm, rpy deg, quaternion), per rod length,
/// axial force and base force norm.
void write_solution_table(std::ostream& out, const RobotModel& model, const RobotSolution& solution);

/// JSON object with model, status, inputs, platforms, rods, summary (and targets when given), see
/// docs/results_format.md. Non-finite numbers are written as null; returns how many there were.
int write_solution_json(std::ostream& out, const RobotModel& model, const RobotSolution& solution,
                        const std::vector<LinkTarget>& targets = {});
/// The same with `links`, `input_jacobian` and `compliance` from extras, and in each target the reached
/// pose of its link and the distance to it.
int write_solution_json(std::ostream& out, const RobotModel& model, const RobotSolution& solution,
                        const std::vector<LinkTarget>& targets, const SolutionExtras& extras);
/// The object of write_solution_json without `non_finite_values`, as the next value of `json` (e.g. one
/// point of a path).
void write_solution_object(JsonWriter& json, const RobotModel& model, const RobotSolution& solution,
                           const std::vector<LinkTarget>& targets, const SolutionExtras& extras);

/// "links:" table of link poses (mm, rpy deg, quaternion), as the platforms' rows of the solution table.
void write_link_table(std::ostream& out, const std::vector<LinkPose>& links);

/// File name of a rod's centerline CSV: "rod_<name>.csv", characters other than [A-Za-z0-9._-]
/// replaced by '_'.
std::string rod_csv_file_name(const std::string& rod_name);

/// DIR/summary.csv (the solve's status, iterations, residual, time, message and stability verdict),
/// DIR/platforms.csv, DIR/inputs.csv and one DIR/rod_<name>.csv (s,x,y,z) per rod; creates DIR.
/// Non-finite numbers are written as empty fields.
void write_solution_csv(const std::string& directory, const RobotModel& model, const RobotSolution& solution);

/// Legacy ASCII VTK POLYDATA: one polyline per rod (centerline), then the outlines of the base and the
/// platforms (robot_outline.hpp) as polygons (closed outlines) or polylines (collinear points); cell data
/// "part" = rod index, -1 for the base outline, -2 - p for platform p. Throws InputError if a coordinate is
/// not finite.
void write_solution_vtk(const std::string& path, const RobotModel& model, const RobotSolution& solution);

}  // namespace pcr
