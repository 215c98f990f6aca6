// The robot's shooting map for the shared Newton loop (see robot_shooting_system.hpp).
#include "robot_shooting_system.hpp"

#include <algorithm>

#include "coupling_residuals.hpp"
#include "pcr/math/so3.hpp"

namespace pcr {
namespace shooting_robot {

namespace {
using Mat6x13 = Eigen::Matrix<double, 6, kRodStateSize>;

bool contains(const std::vector<int>& v, int x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}
}  // namespace

RobotShootingSystem::RobotShootingSystem(RobotShootingModel& model, const ShootingRobotOptions& options)
    : model_(model), options_(options) {
  integrator_.method = options.integrator;
  integrator_.rk4_steps = options.rk4_steps;
  integrator_.relative_tolerance = options.integration_relative_tolerance;
  integrator_.absolute_tolerance = options.integration_absolute_tolerance;
  layout_ = UnknownLayout(model, false);
  row_scale_.resize(layout_.num_residuals());
  for (const ResidualRows& rows : layout_.residuals()) {
    if (rows.kind == ResidualKind::RodCoupling) {
      const RodSetup& rod = model.rods[rows.index];
      row_scale_.segment<6>(rows.offset) = coupling_of(rod.coupling).row_scale(rod.end_axes, model);
    } else if (rows.kind == ResidualKind::PlatformBalance) {
      row_scale_.segment<6>(rows.offset) << Vec3::Constant(model.Fs), Vec3::Constant(model.Ms);
    } else {
      row_scale_[rows.offset] = model.passive[rows.index].row_scale;
    }
  }
  for (const RodSetup& rod : model.rods) any_moving_base_ = any_moving_base_ || !rod.base_joints.empty();
  coupling_rates_.resize(model.num_rods());
  balance_rates_.resize(model.num_rods());
  find_joint_columns();
}

void RobotShootingSystem::set_mode(bool ik) {
  if (ik == layout_.ik()) return;
  layout_ = UnknownLayout(model_, ik);
  find_joint_columns();
  forget_factorization();
}

// The unknown joint values of the layout and the rods whose base frames they move.
void RobotShootingSystem::find_joint_columns() {
  const RobotModel& m = *model_.model;
  joint_columns_.clear();
  for (const UnknownBlock& b : layout_.unknowns()) {
    if (b.kind == UnknownKind::PassiveJoint) {
      const PassiveSetup& p = model_.passive[b.index];
      joint_columns_.push_back({b.offset, p.joint, p.unknown_scale});
    } else if (b.kind == UnknownKind::InputValue &&
               m.inputs()[b.index].kind == ActuationInput::Kind::JointValue) {
      joint_columns_.push_back({b.offset, m.inputs()[b.index].index, model_.input_scale[b.index]});
    }
  }
  frame_moves_.assign(model_.num_rods(), 0);
  for (int i = 0; i < model_.num_rods(); ++i)
    for (const JointColumn& c : joint_columns_)
      if (contains(model_.rods[i].base_joints, c.joint)) frame_moves_[i] = 1;
}

void RobotShootingSystem::start(const State& s) {
  current_ = s;
  frozen_ = false;
  rods_hold_current_ = false;
}

int RobotShootingSystem::integration_steps() const {
  if (options_.integrator == IntegratorMethod::RK4) return options_.rk4_steps * model_.num_rods();
  int steps = 0;
  for (const RodSetup& rod : model_.rods) steps += std::max(0, static_cast<int>(rod.trajectory.s.size()) - 1);
  return steps;
}

bool RobotShootingSystem::integrate(const State& s, bool tangents) {
  const bool on_mesh = frozen_ && options_.integrator == IntegratorMethod::DormandPrince;
  const VecX q = any_moving_base_ ? model_.joint_values(s) : VecX();
  joint_end::FrameTangents dy0_dframe;
  for (int i = 0; i < model_.num_rods(); ++i) {
    RodSetup& r = model_.rods[i];
    r.set_length(model_.length_of(r, s));
    const double L = r.model.length;
    if (!(L > 0.0)) {
      failure_ = "rod '" + r.model.name + "' has length <= 0";
      return false;
    }
    const bool frame_rates = tangents && frame_moves_[i];
    model_.base_state(i, model_.base_frame(i, q, s), s.base[i], r.y0, tangents ? &r.dy0_dz : nullptr,
                      frame_rates ? &dy0_dframe : nullptr);
    r.Y.col(0) = r.y0;
    if (on_mesh) {
      r.mesh.resize(r.mesh_fraction.size());
      for (size_t j = 0; j < r.mesh.size(); ++j) r.mesh[j] = r.mesh_fraction[j] * L;
    }
    r.trajectory.clear();
    IntegrationReport report;
    if (tangents) {
      r.Y.rightCols<kRodTangentCount>() = r.dy0_dz;
      report = on_mesh ? integrate_rod_on_mesh(*r.ode, r.mesh, r.Y, options_.integrator, &r.trajectory)
                       : integrate_rod(*r.ode, 0.0, L, r.Y, integrator_, &r.trajectory);
    } else {
      RodStateVector y = r.y0;
      report = on_mesh ? integrate_rod_on_mesh(*r.ode, r.mesh, y, options_.integrator, &r.trajectory)
                       : integrate_rod(*r.ode, 0.0, L, y, integrator_, &r.trajectory);
      r.Y.col(0) = y;
    }
    if (!report.success || !r.Y.allFinite()) {
      failure_ = "rod '" + r.model.name + "': " + (report.success ? "non-finite state" : report.message);
      return false;
    }
    // d y(L) / dL for a fed rod.
    if (tangents && r.input >= 0) r.ode->derivative(L, RodStateVector(r.Y.col(0)), r.dy_dL);
    if (frame_rates && !integrate_frame_rotation(r, dy0_dframe)) return false;
  }
  return true;
}

// d y(L) / d(world rotation of the base frame): its three directions integrated as tangents on the
// steps of the state's integration (the exact derivative of the same discrete map). A translation of
// the base frame translates the whole rod (the ODE does not depend on p), so it needs no integration.
bool RobotShootingSystem::integrate_frame_rotation(RodSetup& r, const joint_end::FrameTangents& dy0_dframe) {
  RodStateWithTangents Z = RodStateWithTangents::Zero();
  Z.col(0) = r.y0;
  Z.middleCols<3>(1) = dy0_dframe;
  const IntegrationReport report = integrate_rod_on_mesh(*r.ode, r.trajectory.s, Z, options_.integrator);
  if (!report.success || !Z.allFinite()) {
    failure_ =
        "rod '" + r.model.name + "': base frame tangents " + (report.success ? "not finite" : report.message);
    return false;
  }
  r.dyL_dframe = Z.middleCols<3>(1);
  return true;
}

void RobotShootingSystem::residual(const State& s, VecX& r) const {
  r.resize(layout_.num_residuals());
  for (const ResidualRows& rows : layout_.residuals()) {
    if (rows.kind == ResidualKind::RodCoupling) {
      const RodSetup& rod = model_.rods[rows.index];
      r.segment<6>(rows.offset) =
          coupling_of(rod.coupling)
              .residual(rod.Y.col(0), s.poses[rod.platform] * rod.end_offset, rod.end_axes, model_);
    } else if (rows.kind == ResidualKind::PlatformBalance) {
      r.segment<6>(rows.offset) = platform_balance(model_, rows.index, s.poses[rows.index]);
    }
  }
  if (model_.num_passive() == 0) return;
  // Passive joints: from the base states of s (not of the last integration: the Jacobian's central
  // differences move the joint values with the tip states held).
  const VecX q = model_.joint_values(s);
  std::vector<RodStateVector> y0(model_.num_rods());
  for (int i = 0; i < model_.num_rods(); ++i)
    model_.base_state(i, model_.base_frame(i, q, s), s.base[i], y0[i]);
  for (int p = 0; p < model_.num_passive(); ++p)
    r[layout_.row(ResidualKind::PassiveBalance, p)] = passive_balance(model_, p, q, s, y0);
}

// J = dr/dz: rod columns through the tangents (and d y(L)/dL of fed lengths), the algebraic coupling
// rows by central differences in y(L), the balance rows exactly; platform pose and joint value columns
// by central differences of the algebraic rows (tip states held), plus, for joint values, the motion
// of the base frames they carry through the rods (add_joint_columns); passive rows in the rod columns
// exactly (add_passive_columns).
void RobotShootingSystem::jacobian(const State& s, MatX& J) {
  const double Ls = model_.Ls, Fs = model_.Fs, Ms = model_.Ms;
  J.setZero(layout_.num_residuals(), layout_.num_unknowns());
  RodStateVector h_state;
  h_state << Vec3::Constant(Ls), Quat::Constant(1.0), Vec3::Constant(Fs), Vec3::Constant(Ms);
  h_state *= 1e-6;  // central differences: truncation ~(1e-6)^2, round-off ~1e-16 / 1e-6
  for (int i = 0; i < model_.num_rods(); ++i) {
    const RodSetup& rod = model_.rods[i];
    const int k = rod.platform;
    const RodStateVector y = rod.Y.col(0);
    const Pose T = s.poses[k] * rod.end_offset;
    const Coupling& coupling = coupling_of(rod.coupling);
    Mat6x13& D = coupling_rates_[i];  // d(coupling rows)/dy(L)
    for (int c = 0; c < kRodStateSize; ++c) {
      RodStateVector yp = y, ym = y;
      yp[c] += h_state[c];
      ym[c] -= h_state[c];
      D.col(c) =
          (coupling.residual(yp, T, rod.end_axes, model_) - coupling.residual(ym, T, rod.end_axes, model_)) /
          (2 * h_state[c]);
    }
    // d(balance)/dy(L): -n, -(m + (p - x) x n), exact.
    Mat6x13& E = balance_rates_[i];
    E.setZero();
    const Vec3 n = y.segment<3>(RodStateIndex::n), arm = y.segment<3>(RodStateIndex::p) - s.poses[k].position;
    E.block<3, 3>(0, RodStateIndex::n) = -Mat3::Identity() / Fs;
    E.block<3, 3>(3, RodStateIndex::p) = hat(n) / Ms;
    E.block<3, 3>(3, RodStateIndex::n) = -hat(arm) / Ms;
    E.block<3, 3>(3, RodStateIndex::m) = -Mat3::Identity() / Ms;
    const Eigen::Matrix<double, kRodStateSize, 6> tangents =
        rod.Y.rightCols<kRodTangentCount>() * rod.unknown_scale.asDiagonal();
    const int rows_rod = layout_.row(ResidualKind::RodCoupling, i);
    const int rows_platform = layout_.row(ResidualKind::PlatformBalance, k);
    const int col = layout_.column(UnknownKind::RodBase, i);
    J.block<6, 6>(rows_rod, col) = D * tangents;
    J.block<6, 6>(rows_platform, col) = E * tangents;
    const int input_col = layout_.column(UnknownKind::InputValue, rod.input);
    if (input_col >= 0) {
      J.block<6, 1>(rows_rod, input_col) += D * rod.dy_dL * Ls;
      J.block<6, 1>(rows_platform, input_col) += E * rod.dy_dL * Ls;
    }
  }
  VecX rp, rm, dz = VecX::Zero(layout_.num_unknowns());
  State sp, sm;
  for (const UnknownBlock& b : layout_.unknowns()) {
    const bool joint_value = b.kind == UnknownKind::PassiveJoint ||
                             (b.kind == UnknownKind::InputValue && model_.num_passive() > 0 &&
                              model_.model->inputs()[b.index].kind == ActuationInput::Kind::JointValue);
    if (b.kind != UnknownKind::PlatformPose && !joint_value) continue;
    for (int c = 0; c < b.size; ++c) {
      const double h = 1e-6;
      dz[b.offset + c] = h;
      layout_.retract(model_, s, dz, sp);
      layout_.retract(model_, s, -dz, sm);
      dz[b.offset + c] = 0.0;
      residual(sp, rp);
      residual(sm, rm);
      J.col(b.offset + c) = (rp - rm) / (2 * h);
    }
  }
  add_passive_columns(s, J);
  add_joint_columns(s, J);
}

// Passive balance rows in the rod base columns: dQ/dy(0) dy(0)/dz, exact.
void RobotShootingSystem::add_passive_columns(const State& s, MatX& J) const {
  if (model_.num_passive() == 0) return;
  const VecX q = model_.joint_values(s);
  for (int p = 0; p < model_.num_passive(); ++p) {
    const PassiveSetup& setup = model_.passive[p];
    Vec3 w, o;
    joint_axis(model_, setup.joint, q, s, w, o);
    const int row = layout_.row(ResidualKind::PassiveBalance, p);
    for (int i : setup.rods) {
      const RodSetup& rod = model_.rods[i];
      J.block<1, 6>(row, layout_.column(UnknownKind::RodBase, i)) +=
          passive_force_gradient(setup, w, o, rod.y0) * rod.dy0_dz * rod.unknown_scale.asDiagonal() /
          setup.row_scale;
    }
  }
}

// A joint value moves the base frames beyond it: y(L) moves by the frame's translation v (the whole rod
// translates) and by dy(L)/d(frame rotation) omega (integrate_frame_rotation).
void RobotShootingSystem::add_joint_columns(const State& s, MatX& J) const {
  if (joint_columns_.empty()) return;
  const VecX q = model_.joint_values(s);
  for (const JointColumn& c : joint_columns_) {
    for (int i = 0; i < model_.num_rods(); ++i) {
      const RodSetup& rod = model_.rods[i];
      if (!contains(rod.base_joints, c.joint)) continue;
      Vec3 velocity, omega;
      model_.base_frame_rate(i, c.joint, q, s, velocity, omega);
      RodStateVector dy = rod.dyL_dframe * omega;
      dy.segment<3>(RodStateIndex::p) += velocity;
      J.block<6, 1>(layout_.row(ResidualKind::RodCoupling, i), c.column) += coupling_rates_[i] * dy * c.scale;
      J.block<6, 1>(layout_.row(ResidualKind::PlatformBalance, rod.platform), c.column) +=
          balance_rates_[i] * dy * c.scale;
    }
  }
}

bool RobotShootingSystem::evaluate_at(const VecX* dx, VecX& r, MatX* J) {
  if (dx) layout_.retract(model_, current_, *dx, trial_);
  const State& s = dx ? trial_ : current_;
  rods_hold_current_ = false;
  if (!integrate(s, J != nullptr)) return false;
  rods_hold_current_ = dx == nullptr;
  residual(s, r);
  if (!r.allFinite()) {
    failure_ = "non-finite residual";
    return false;
  }
  if (!J) return true;
  jacobian(s, *J);
  if (J->allFinite()) return true;
  failure_ = "non-finite Jacobian";
  return false;
}

void RobotShootingSystem::accept() {
  std::swap(current_, trial_);
  rods_hold_current_ = true;
}

bool RobotShootingSystem::integrate_current() {
  if (rods_hold_current_) return true;
  rods_hold_current_ = integrate(current_, false);
  return rods_hold_current_;
}

// Dormand-Prince: freeze every rod's current (adaptive) steps once the residual is small, and
// re-evaluate the current point on them.
NonlinearSystem::PointUpdate RobotShootingSystem::on_new_point(double r_max, VecX& r) {
  if (options_.integrator != IntegratorMethod::DormandPrince || frozen_ ||
      !(r_max < options_.freeze_mesh_below))
    return PointUpdate::Unchanged;
  if (!integrate_current()) return PointUpdate::Failed;
  for (RodSetup& rod : model_.rods) {
    rod.mesh_fraction = rod.trajectory.s;
    for (double& x : rod.mesh_fraction) x /= rod.model.length;
    rod.mesh_fraction.back() = 1.0;
  }
  frozen_ = true;
  return reevaluate_current(r) ? PointUpdate::Changed : PointUpdate::Failed;
}

}  // namespace shooting_robot
}  // namespace pcr
