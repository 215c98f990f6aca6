#pragma once
// Obstacles and contact forces of a solved robot for pictures (VTK, gnuplot; docs/results_format.md):
// the obstacles at the solution's link poses as coarse surfaces, lines and vertices, and the contact
// forces on the rods' centerline points. World frame, SI units.
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr {

/// An obstacle drawn: points [m] and cells indexing them.
struct ObstacleMesh {
  std::string name;
  int obstacle = -1;                       ///< index in RobotModel::obstacles()
  std::vector<Vec3> points;                ///< world frame [m]
  std::vector<std::vector<int>> polygons;  ///< closed facets (triangles, quads, end discs)
  std::vector<std::vector<int>> lines;     ///< open polylines (edges)
  std::vector<int> vertices;               ///< single points (point obstacles)
};

/// The model's obstacles in the world frame at the solution's inputs, passive joint values and platform
/// poses (an obstacle on a link moves with it), in RobotModel::obstacles() order.
std::vector<Obstacle> world_obstacles(const RobotModel& model, const RobotSolution& solution);

/// One mesh per obstacle of the model. Bounded shapes are drawn whole: a sphere as 12 x 6 facets, a
/// capsule as a tube of 12 quads with a sphere at each end, a roller as a tube with its two end discs.
/// Unbounded shapes are cut around the rods' centerline point nearest to them, with the robot's size d
/// (the diagonal of the rods' bounding box, at least 1 mm): a half-space as the square of side d on its
/// plane centred at the foot of that point, an infinite cylinder as a tube and an infinite edge as a line
/// of length d centred at its foot on the axis. A finite edge is its segment, a point a vertex.
std::vector<ObstacleMesh> obstacle_meshes(const RobotModel& model, const RobotSolution& solution);

/// The contact forces of a solution on the rods' centerline points (RodResult::centerline).
struct ContactForceSamples {
  /// Per rod (solution.rods order), per centerline point: the resultants of the distributed contact's
  /// collocation cells whose midpoint is nearest to the point (each cell's resultant goes to one point,
  /// so the sum over a rod is the rod's distributed contact force) [N].
  std::vector<std::vector<Vec3>> nodal;
  /// Per rod, per centerline point: the distributed force density of the cell whose midpoint is nearest
  /// to the point, summed over the obstacles [N/m].
  std::vector<std::vector<Vec3>> density;
  /// Concentrated forces (sharp obstacles, contact="point") that are active: where they act (the
  /// centerline interpolated at the contact section) [m], the force on the rod [N], the rod's index.
  std::vector<Vec3> points, forces;
  std::vector<int> rods;
};
/// Throws InputError when a contact names a rod that the solution does not have.
ContactForceSamples contact_force_samples(const RobotSolution& solution);

}  // namespace pcr
