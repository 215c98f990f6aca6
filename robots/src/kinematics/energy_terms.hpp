#pragma once
// The terms of the total potential energy (energy_model.hpp) and its constraint rows, as Problem blocks
// (internal header of pcr::robots). Gradients and Jacobians by forward-mode dual numbers (pcr/math/dual.hpp)
// on a few local quantities, chained to the unknowns by hand.
#include <memory>
#include <vector>

#include "energy_hessian.hpp"
#include "pcr/robots/robot_model.hpp"
#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/obstacle.hpp"
#include "pcr/solve/residual_block.hpp"

namespace pcr::kinematics {

/// The energy of one rod over its control points [P, Q] (Ritz form on its knots), divided by
/// energy_scale: int_0^L 1/2 (v - v*)^T K_SE (v - v*) + 1/2 (u - u*)^T K_BT (u - u*) - f . p ds with
/// s = L u, v = R^T p_s, u = 2 vec(conj(q) q_s) / |q|^2, f the distributed dead force (gravity included),
/// minus the work F . p of the dead forces on free ends.
class RodEnergyTerm : public ObjectiveTerm {
 public:
  RodEnergyTerm(const CollocationRod& rod, double length, std::vector<VariableId> points,
                double energy_scale);
  double evaluate(const double* const* values, double* const* gradients) const override;
  int expected_variable_size(int) const override { return 7; }
  /// Per quadrature node: the exact Hessian of the strain energy density in [p_s, q, q_s] (second-order
  /// forward mode, hyper_dual.hpp), chained to the node's control points.
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const* values, double* hessian) const override;
  /// The section force n and moment m (world frame) of the constitutive law, and the position p, at u.
  void section(const double* const* values, double u, Vec3& p, Vec3& n, Vec3& m) const;

 private:
  struct Node {
    double u, weight;  // weight: the quadrature weight in s (ds = L du)
    int first;         // first active basis function
    MatX basis;        // 2 x (degree + 1): N and dN/ds
    Vec3 eps0, kappa0;
  };
  const CollocationRod& rod_;
  double length_, scale_;
  std::vector<Node> nodes_;
  Node node_at(double u, double weight) const;
};

/// A platform's weight and the dead forces on the links it carries, divided by energy_scale:
/// -sum_k F_k . (x + R(Q) r_k), r_k in the platform frame, over [x (3), Q (4)].
class PlatformLoadTerm : public ObjectiveTerm {
 public:
  PlatformLoadTerm(VariableId platform, std::vector<Vec3> forces, std::vector<Vec3> points,
                   double energy_scale);
  double evaluate(const double* const* values, double* const* gradients) const override;
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const* values, double* hessian) const override {
    gradient_difference_hessian(*this, sizes_, values, hessian);
  }

 private:
  std::vector<Vec3> forces_, points_;
  double scale_;
  std::vector<int> sizes_{7};
};

/// The passive joints' springs 1/2 k (q - rest)^2 and the weights and dead forces on the links they
/// move, -F . X(q), divided by energy_scale, over all passive joint values (RobotModel::passive_joints()
/// order). joint_values: the joint-value vector at the inputs (passive entries overwritten).
class PassiveJointTerm : public ObjectiveTerm {
 public:
  PassiveJointTerm(const RobotModel& model, VecX joint_values, std::vector<VariableId> passive,
                   double energy_scale);
  double evaluate(const double* const* values, double* const* gradients) const override;
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const* values, double* hessian) const override {
    gradient_difference_hessian(*this, sizes_, values, hessian);
  }

 private:
  struct PointForce {
    int link;
    Vec3 point, force;  // point in the link frame, force in the world frame
  };
  const RobotModel& model_;
  VecX joint_values_;
  std::vector<PointForce> forces_;
  double scale_;
  std::vector<int> sizes_;
};

/// |Q|^2 - 1 = 0 for the quaternion at component 3 of a block [P or x (3), Q (4)].
class UnitQuaternionRow : public ResidualBlock {
 public:
  explicit UnitQuaternionRow(VariableId block);
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override;
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const* values, const double* weights, double* hessian) const override;
};

/// The kinematic part of a rod end's coupling (RobotModel RodAttachment, rod_model.hpp RodEndKind): the
/// end's position at the attachment's (3 rows, / length_scale), and clamped: R_a^T R = I (3 rows, the
/// skew part), collar: d3 along R_a e3 (2), revolute: R a = R_a a (2), universal: R_a a normal to R b
/// (1), spherical: nothing more. Variables: the end control point, then the platform carrying the link
/// (if any), then the passive joints moving it. joint_values as PassiveJointTerm;
/// platform_from_attachment: the attachment in the platform frame (platform links only).
class CouplingRows : public ResidualBlock {
 public:
  CouplingRows(const RobotModel& model, const RodAttachment& attachment, VecX joint_values,
               const Pose& platform_from_attachment, std::vector<VariableId> variables, int platform_count,
               std::vector<int> passive_joints, double length_scale);
  static int rows_of(RodEndKind kind);
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override;
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const* values, const double* weights, double* hessian) const override {
    jacobian_difference_hessian(*this, sizes_, values, weights, hessian);
  }

 private:
  const RobotModel& model_;
  RodAttachment attachment_;
  VecX joint_values_;
  Pose platform_from_attachment_;
  bool on_platform_;
  std::vector<int> passive_joints_;  // joint indices
  double length_scale_;
  std::vector<int> sizes_;
};

/// Frictionless contact as constraints of the energy (a workless reaction: the obstacles add no potential):
/// the gap g_k(p(u)) (obstacle.hpp, contact radius r) of the centerline point p(u) = sum_a N_a(u) P_a to
/// each obstacle k, divided by length_scale, bounded below by 0. One row per obstacle, over the control
/// points [P, Q] whose basis functions do not vanish at u (basis: their N_a(u)). The collocation's contact
/// rows hold at its midpoints (rod_contact.hpp), and so do these. Jacobian N_a nu_k^T / length_scale;
/// Hessian of sum_k w_k g_k: sum_k w_k N_a N_b (d nu_k / d p) / length_scale in the P-P blocks.
class ObstacleGapRows : public ResidualBlock {
 public:
  ObstacleGapRows(std::vector<Obstacle> obstacles, double radius, VecX basis, std::vector<VariableId> points,
                  double length_scale);
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override;
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const* values, const double* weights, double* hessian) const override;

 private:
  std::vector<Obstacle> obstacles_;
  double radius_;
  VecX basis_;
  double length_scale_;
  Vec3 centerline(const double* const* values) const;
};

}  // namespace pcr::kinematics
