#pragma once
// Private to the shooting robot solver: the robot's shooting map as a NonlinearSystem for the shared
// Newton loop (pcr/solve/newton_loop.hpp). Evaluating a point integrates every rod from its base state
// (with its six tangents for the Jacobian; d y(L)/dL = f(L, y(L)) for fed lengths; for a base frame moved
// by an unknown joint value, a second tangent pass on the same steps for its rotation), then the
// coupling rows of each rod, the balance rows of each platform and passive joint (unknown_layout.hpp).
// The rods' buffers hold the last integration, of the current or of the trial point.
#include <string>
#include <vector>

#include "pcr/robots/shooting/shooting_robot_solver.hpp"
#include "pcr/solve/dense_system.hpp"
#include "unknown_layout.hpp"

namespace pcr {
namespace shooting_robot {

class RobotShootingSystem : public DenseNonlinearSystem<Eigen::Dynamic> {
 public:
  RobotShootingSystem(RobotShootingModel& model, const ShootingRobotOptions& options);

  /// FK or IK unknowns; a change forgets the factorisation (its columns meant other unknowns).
  void set_mode(bool ik);
  const UnknownLayout& layout() const { return layout_; }
  /// The next solve starts at s, with adaptive integration (the mesh is frozen again when close).
  void start(const State& s);
  const State& state() const { return current_; }
  /// Makes the rods' buffers hold the integration of the current point; false if it failed.
  bool integrate_current();
  /// Unscaled residual = scaled * row_scale.
  const VecX& row_scale() const { return row_scale_; }
  /// ODE steps of the last integration, summed over the rods.
  int integration_steps() const;

  int size() const override { return layout_.num_unknowns(); }
  PointUpdate on_new_point(double r_max, VecX& r) override;
  std::string evaluation_failure() const override { return failure_; }

 protected:
  bool evaluate_at(const VecX* dx, VecX& r, MatX* J) override;
  void accept() override;

 private:
  /// An unknown joint value (passive joint, or joint input in IK): its column, joint and scale.
  struct JointColumn {
    int column, joint;
    double scale;
  };
  void find_joint_columns();
  bool integrate(const State& s, bool tangents);
  bool integrate_frame_rotation(RodSetup& r, const joint_end::FrameTangents& dy0_dframe);
  void residual(const State& s, VecX& r) const;
  void jacobian(const State& s, MatX& J);
  void add_passive_columns(const State& s, MatX& J) const;
  void add_joint_columns(const State& s, MatX& J) const;

  RobotShootingModel& model_;
  const ShootingRobotOptions& options_;
  IntegratorOptions integrator_;
  UnknownLayout layout_;
  VecX row_scale_;
  State current_, trial_;
  std::vector<JointColumn> joint_columns_;
  std::vector<char> frame_moves_;  // per rod: its base frame moves with an unknown joint value
  bool any_moving_base_ = false;   // some rod's base frame moves with a joint value (input or passive)
  std::vector<Eigen::Matrix<double, 6, kRodStateSize>> coupling_rates_, balance_rates_;  // D, E per rod
  bool rods_hold_current_ = false;
  bool frozen_ = false;
  std::string failure_;
};

}  // namespace shooting_robot
}  // namespace pcr
