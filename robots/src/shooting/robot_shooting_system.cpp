// The robot's shooting map for the shared Newton loop (see robot_shooting_system.hpp).
#include "robot_shooting_system.hpp"

#include "coupling_residuals.hpp"
#include "pcr/math/so3.hpp"

namespace pcr {
namespace shooting_robot {

namespace {
using Mat6x13 = Eigen::Matrix<double, 6, kRodStateSize>;
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
    if (rows.kind == ResidualKind::RodCoupling)
      row_scale_.segment<6>(rows.offset) = coupling_of(model.rods[rows.index].coupling).row_scale(model);
    else
      row_scale_.segment<6>(rows.offset) << Vec3::Constant(model.Fs), Vec3::Constant(model.Ms);
  }
}

void RobotShootingSystem::set_mode(bool ik) {
  if (ik == layout_.ik()) return;
  layout_ = UnknownLayout(model_, ik);
  forget_factorization();
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
  for (int i = 0; i < model_.num_rods(); ++i) {
    RodSetup& r = model_.rods[i];
    r.set_length(model_.length_of(r, s));
    const double L = r.model.length;
    if (!(L > 0.0)) {
      failure_ = "rod '" + r.model.name + "' has length <= 0";
      return false;
    }
    r.Y.setZero();
    r.Y.col(0) << r.base_frame.position, r.base_frame.orientation, s.n0[i], s.m0[i];
    if (on_mesh) {
      r.mesh.resize(r.mesh_fraction.size());
      for (size_t j = 0; j < r.mesh.size(); ++j) r.mesh[j] = r.mesh_fraction[j] * L;
    }
    r.trajectory.clear();
    IntegrationReport report;
    if (tangents) {
      for (int j = 0; j < 3; ++j) {
        r.Y(RodStateIndex::n + j, 1 + j) = 1.0;
        r.Y(RodStateIndex::m + j, 4 + j) = 1.0;
      }
      report = on_mesh ? integrate_rod_on_mesh(*r.ode, r.mesh, r.Y, options_.integrator, &r.trajectory)
                       : integrate_rod(*r.ode, 0.0, L, r.Y, integrator_, &r.trajectory);
    } else {
      RodStateVector y = r.Y.col(0);
      report = on_mesh ? integrate_rod_on_mesh(*r.ode, r.mesh, y, options_.integrator, &r.trajectory)
                       : integrate_rod(*r.ode, 0.0, L, y, integrator_, &r.trajectory);
      r.Y.col(0) = y;
    }
    if (!report.success || !r.Y.allFinite()) {
      failure_ = "rod '" + r.model.name + "': " + (report.success ? "non-finite state" : report.message);
      return false;
    }
    // d y(L) / dL for a rod fed through its clamped base.
    if (tangents && r.input >= 0) r.ode->derivative(L, RodStateVector(r.Y.col(0)), r.dy_dL);
  }
  return true;
}

void RobotShootingSystem::residual(const State& s, VecX& r) const {
  r.resize(layout_.num_residuals());
  for (const ResidualRows& rows : layout_.residuals()) {
    if (rows.kind == ResidualKind::RodCoupling) {
      const RodSetup& rod = model_.rods[rows.index];
      r.segment<6>(rows.offset) =
          coupling_of(rod.coupling).residual(rod.Y.col(0), s.poses[rod.platform] * rod.end_offset, model_);
    } else {
      r.segment<6>(rows.offset) = platform_balance(model_, rows.index, s.poses[rows.index]);
    }
  }
}

// J = dr/dz: rod columns through the tangents (and d y(L)/dL of fed lengths), the algebraic coupling
// rows by central differences in y(L), the balance rows exactly; platform pose columns (FK) by central
// differences of the algebraic rows (the rods' states do not depend on the poses).
void RobotShootingSystem::jacobian(const State& s, MatX& J) {
  const double Ls = model_.Ls, Fs = model_.Fs, Ms = model_.Ms;
  J.setZero(layout_.num_residuals(), layout_.num_unknowns());
  Eigen::Matrix<double, 6, 6> unknown_scale = Eigen::Matrix<double, 6, 6>::Zero();
  unknown_scale.diagonal() << Fs, Fs, Fs, Ms, Ms, Ms;
  RodStateVector h_state;
  h_state << Vec3::Constant(Ls), Quat::Constant(1.0), Vec3::Constant(Fs), Vec3::Constant(Ms);
  h_state *= 1e-6;  // central differences: truncation ~(1e-6)^2, round-off ~1e-16 / 1e-6
  for (int i = 0; i < model_.num_rods(); ++i) {
    const RodSetup& rod = model_.rods[i];
    const int k = rod.platform;
    const RodStateVector y = rod.Y.col(0);
    const Pose T = s.poses[k] * rod.end_offset;
    const Coupling& coupling = coupling_of(rod.coupling);
    Mat6x13 D;  // d(coupling rows)/dy(L)
    for (int c = 0; c < kRodStateSize; ++c) {
      RodStateVector yp = y, ym = y;
      yp[c] += h_state[c];
      ym[c] -= h_state[c];
      D.col(c) = (coupling.residual(yp, T, model_) - coupling.residual(ym, T, model_)) / (2 * h_state[c]);
    }
    // d(balance)/dy(L): -n, -(m + (p - x) x n), exact.
    Mat6x13 E = Mat6x13::Zero();
    const Vec3 n = y.segment<3>(RodStateIndex::n), arm = y.segment<3>(RodStateIndex::p) - s.poses[k].position;
    E.block<3, 3>(0, RodStateIndex::n) = -Mat3::Identity() / Fs;
    E.block<3, 3>(3, RodStateIndex::p) = hat(n) / Ms;
    E.block<3, 3>(3, RodStateIndex::n) = -hat(arm) / Ms;
    E.block<3, 3>(3, RodStateIndex::m) = -Mat3::Identity() / Ms;
    const auto tangents = rod.Y.rightCols<kRodTangentCount>();
    const int rows_rod = layout_.row(ResidualKind::RodCoupling, i);
    const int rows_platform = layout_.row(ResidualKind::PlatformBalance, k);
    const int col = layout_.column(UnknownKind::RodBaseWrench, i);
    J.block<6, 6>(rows_rod, col) = D * tangents * unknown_scale;
    J.block<6, 6>(rows_platform, col) = E * tangents * unknown_scale;
    const int input_col = layout_.column(UnknownKind::InputValue, rod.input);
    if (input_col >= 0) {
      J.block<6, 1>(rows_rod, input_col) += D * rod.dy_dL * Ls;
      J.block<6, 1>(rows_platform, input_col) += E * rod.dy_dL * Ls;
    }
  }
  VecX rp, rm, dz = VecX::Zero(layout_.num_unknowns());
  State sp, sm;
  for (const UnknownBlock& b : layout_.unknowns()) {
    if (b.kind != UnknownKind::PlatformPose) continue;
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
