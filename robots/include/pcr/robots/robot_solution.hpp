#pragma once
// The result of a robot solve, by collocation (kinematics.hpp) or by shooting
// (shooting/shooting_robot_solver.hpp): inputs, platform poses, per rod its end wrenches and centerline,
// and the solve's summary. World frame throughout.
#include <string>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/robots/pose.hpp"
#include "pcr/rods/rod_contact.hpp"
#include "pcr/rods/stability/stability.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {

struct RodResult {
  std::string name;
  double length = 0.0;
  /// n(0), m(0): the wrench the rod exerts on its start link (world frame, moment about the end point).
  Vec3 base_force = Vec3::Zero(), base_moment = Vec3::Zero();
  /// n(L), m(L): the wrench the end link exerts on the rod.
  Vec3 tip_force = Vec3::Zero(), tip_moment = Vec3::Zero();
  /// Axial force at the feed point n(0) . d3(0) (positive in tension): minus the actuator's push.
  double axial_force = 0.0;
  /// Points of the centerline, base first and tip last (the tip position is centerline.back()).
  /// Collocation: KinematicsOptions::centerline_points equally spaced points; shooting: the points of the
  /// integrator's steps.
  std::vector<Vec3> centerline;
  /// Smallest axial stretch v3 = 1 + eps3 (d3 . p' over the unstretched rate, 1 = unstretched) at the
  /// ends and the centerline points. A solve whose rods reach v3 <= 1e-6 (a rod compressed to a point
  /// or inverted, inadmissible however small its residual) is reported as failed.
  double min_axial_stretch = 1.0;
};

struct RobotSolution {
  SolveSummary summary;
  VecX inputs;                  ///< in the model's input order
  std::vector<Pose> platforms;  ///< in the model's platform order
  std::vector<RodResult> rods;
  VecX passive_joints;  ///< passive joint values [m or rad], in RobotModel::passive_joints() order
  /// Collocation only: per rod with obstacles (rod order) one entry per obstacle it may touch, with its
  /// contact intervals and forces (docs/contact.md).
  std::vector<ObstacleContact> contacts;
  /// Collocation only: per rod with obstacles its smallest gap sampled densely along the rod (8 points per
  /// collocation cell) over all its obstacles. A rod that penetrates by more than the tolerance
  /// (kPenetrationTolerance times its contact radius) puts a warning into summary.message (the solve's
  /// status is kept: the discrete equations are solved, the mesh does not resolve the contact).
  std::vector<RodContactGap> contact_gaps;
  /// Collocation only: with KinematicsOptions::check_stability: sign of det J, J = dR/dx of
  /// the FK system (inputs fixed at the solution's) over its free unknowns at the solution: +1 or -1; 0 when
  /// not checked, not converged or singular.
  int jacobian_sign = 0;
  /// jacobian_sign differs from that of the previous converged, checked solve of this solver: det J
  /// vanishes where equilibria pass a fold or a bifurcation (buckling), so an odd number of them lies
  /// between the two equilibria, and for conservative loads (dead loads, gravity) this one has an odd
  /// number of unstable modes more or fewer than the previous one. Along a path that starts at a stable
  /// equilibrium the first change means: unstable (e.g. a rod fed past its buckling length stays straight
  /// by symmetry). No change does not prove stability (an even number of crossings, or a double mode
  /// such as a round rod's buckling in both bending planes at once, keeps the sign).
  bool jacobian_sign_changed = false;
  /// Collocation only, with KinematicsOptions::stability_verdict: stable / unstable (with the number of
  /// unstable modes) / critical / unknown, from the second variation of the energy (robot_stability.hpp;
  /// FK: at its inputs; IK: the FK system at the solution's inputs). NotChecked otherwise.
  Stability stability_verdict;
};

}  // namespace pcr
