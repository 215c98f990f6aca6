#pragma once
// Outlines for pictures of a solved robot: for the base and for each platform, the polygon through
// the rod attachment points it carries (world frame), ordered by angle around their centroid in
// their best-fit plane (or along their line when they are collinear).
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr {

struct Outline {
  std::string name;          ///< "base" or the platform's link name
  int platform = -1;         ///< platform index, -1 for the base (links fixed to the world)
  std::vector<Vec3> points;  ///< distinct attachment points in polygon order (world frame) [m]
  /// A polygon (>= 3 points, not all on one line); otherwise the points form an open polyline
  /// ordered along their line.
  bool closed = false;
};

/// Joint values (model's joint-value vector) for the given inputs (model input order); passive joints
/// at their defaults.
VecX joint_values_of_inputs(const RobotModel& model, const VecX& inputs);

/// The base outline first, then one per platform, from the solution's inputs and platform poses.
/// Outlines with no attached rod end are omitted. Points closer than 1e-9 m are merged.
std::vector<Outline> robot_outlines(const RobotModel& model, const RobotSolution& solution);

}  // namespace pcr
