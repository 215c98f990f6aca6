#pragma once
// Robots with universal / revolute rod ends and passive joints, built in code (RobotModel constructor)
// for the shooting reference's tests (test_shooting_joints.cpp).
#include <memory>

#include "pcr/robots/robot_model.hpp"

namespace pcr {
namespace test_robots {

/// 6-RUS-like robot (the geometry of the 6-RUS of Rodrigues et al., ARK 2024, as described for pcr's
/// six_rus model): six motors (revolute about their frame's x, default 0.39497946 rad) turn cranks of
/// 0.23164 m; at each crank tip a universal joint (first axis along the crank, the crank frame's y;
/// second axis e3 x a = -d1) holds a pre-curved titanium rod (radius 2 mm, 0.53 m, stress-free
/// curvature 1/0.3 m about d1) whose other end is a spherical joint on a 0.5 kg platform (initial pose
/// (0, 0, 0.5)); gravity -9.81 e3.
/// passive_universals: each universal joint replaced by two passive joints (continuous about the crank
/// y, then revolute about -x of the first joint's link, at the crank tip) carrying a massless link to
/// which the rod is clamped: the same mechanics (rod frame R_crank R_y(q1) R_-x(q2), no moment about
/// either axis).
std::shared_ptr<const RobotModel> six_rus_like(bool passive_universals);

/// Planar three-rod robot (the geometry of models/planar_three_rod.urdf: rods in the x-z plane,
/// lengths actuated), steel rods of radius 1 mm, every rod pinned at both ends about y (normal to the
/// plane): at the start by a passive revolute joint about y carrying a massless link to which the rod is
/// clamped, at the end by a revolute coupling. massless_rods: density 0 (the rods are then two-force
/// members, straight).
std::shared_ptr<const RobotModel> planar_pinned(bool massless_rods);

/// Tripod: three steel rods (radius 1.5 mm) from base points at radius 0.12 m (angles 90, 210, 330 deg)
/// up to platform points at radius 0.06 m (platform 0.3 kg at height 0.3 m, centre of mass 0.02 m off
/// along x), each pinned at its start about the tangential direction (the start frame's x axis; z along
/// the rod) and clamped to the platform. passive_starts: the pins as passive revolute joints about that
/// axis carrying massless links to which the rods are clamped (the same mechanics).
std::shared_ptr<const RobotModel> tripod_pinned(bool passive_starts);

/// A rod base on a passive spring joint: the link "arm" (0.2 kg at (0, 0.05, 0)) hangs on the passive
/// joint "spring" at the origin; a steel rod (0.2 m, along +y) is clamped to the arm at its origin and
/// to a 0.5 kg platform (centre of mass 0.03 m beyond the rod end along the rod). Revolute: about x,
/// stiffness 10 N m/rad, rest 0.6 rad, a stiff rod (radius 10 mm, 0.503 kg); prismatic: along z,
/// 2000 N/m, rest 0.01 m, radius 3 mm.
std::shared_ptr<const RobotModel> spring_hinge(JointType type);

}  // namespace test_robots
}  // namespace pcr
