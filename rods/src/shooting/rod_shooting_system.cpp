// One rod's shooting map for the shared Newton loop (see rod_shooting_system.hpp).
#include "rod_shooting_system.hpp"

#include "pcr/solve/newton_loop.hpp"

namespace pcr {
namespace shooting {

RodShootingSystem::RodShootingSystem(const RodModel& model, const IntegratorOptions& integrator,
                                     const RodStateVector& y0, double freeze_mesh_below)
    : DenseNonlinearSystem<6>(1e-14),  // below: Levenberg-Marquardt instead of the Newton step
      model_(model),
      ode_(model),
      integrator_(integrator),
      scale_(residual_scale(model.tip, ode_)),
      unknown_scale_(unknown_scale(model.base, ode_)),
      freeze_mesh_below_(freeze_mesh_below),
      y_(y0),
      trial_y_(y0) {}

void RodShootingSystem::evaluate(const RodStateVector& y0, bool with_jacobian, Evaluation& e) const {
  e.ok = false;
  e.message.clear();
  e.jacobian.setZero();
  IntegrationReport report;
  const bool on_mesh = frozen_ && integrator_.method == IntegratorMethod::DormandPrince;
  RodTrajectory trajectory;
  RodTrajectory* record =
      (!on_mesh && integrator_.method == IntegratorMethod::DormandPrince) ? &trajectory : nullptr;
  RodStateVector tip;
  if (with_jacobian) {
    // The ends are written for the section's n, m; the ODE integrates a drawn rod's N, M (rod_ode.hpp).
    RodStateWithTangents Y;
    base_tangents(model_.base, y0, Y);
    ode_.to_effective(Y);
    report = on_mesh ? integrate_rod_on_mesh(ode_, mesh_, Y, integrator_.method)
                     : integrate_rod(ode_, 0.0, model_.length, Y, integrator_, record);
    ode_.to_section(Y);
    tip = Y.col(0);
    if (report.success && Y.allFinite())
      e.jacobian = scale_.cwiseInverse().asDiagonal() * tip_residual_jacobian(model_.tip, Y);
  } else {
    tip = y0;
    ode_.to_effective(tip);
    report = on_mesh ? integrate_rod_on_mesh(ode_, mesh_, tip, integrator_.method)
                     : integrate_rod(ode_, 0.0, model_.length, tip, integrator_, record);
    ode_.to_section(tip);
  }
  e.mesh = std::move(trajectory.s);
  e.steps = report.steps;
  if (!report.success || !tip.allFinite()) {
    e.message = report.success ? "non-finite tip state" : report.message;
    return;
  }
  e.residual = tip_residual(model_.tip, tip).cwiseQuotient(scale_);
  e.ok = e.residual.allFinite() && e.jacobian.allFinite();
  if (!e.ok) e.message = "non-finite residual";
}

bool RodShootingSystem::evaluate_at(const VecX* dx, VecX& r, Mat6* J) {
  if (dx) {
    trial_y_ = y_;
    retract_base(model_.base, Vec6(*dx), trial_y_);
  }
  Evaluation& e = dx ? trial_ : current_;
  evaluate(dx ? trial_y_ : y_, J != nullptr, e);
  if (!e.ok) {
    failure_ = e.message;
    return false;
  }
  r = e.residual;
  if (J) *J = e.jacobian;
  return true;
}

void RodShootingSystem::accept() {
  y_ = trial_y_;
  std::swap(current_, trial_);
}

// Dormand-Prince: once close to the root, the step sequence is frozen so that the shooting map is
// smooth and Newton converges to round-off. The mesh was chosen adaptively for an iterate within
// freeze_mesh_below of the root, so it suits the answer as well as a fresh adaptive one would (a fresh
// one differs at the level of the integration tolerance, by discrete step events).
NonlinearSystem::PointUpdate RodShootingSystem::on_new_point(double r_max, VecX&) {
  if (integrator_.method == IntegratorMethod::DormandPrince && !frozen_ && r_max <= freeze_mesh_below_ &&
      !current_.mesh.empty()) {
    mesh_ = current_.mesh;  // the current point was integrated adaptively on exactly this mesh
    frozen_ = true;
  }
  return PointUpdate::Unchanged;
}

// Trust-region-like cap: the largest change of an unknown in units of its scale.
double RodShootingSystem::step_size(const VecX& dx) const {
  return Vec6(dx).cwiseQuotient(unknown_scale_).cwiseAbs().maxCoeff();
}

NewtonOutcome solve_newton(const RodModel& model, const IntegratorOptions& integrator, RodStateVector& y0,
                           const ShootingOptions& o) {
  NewtonLoopOptions l;
  l.tolerance = o.tolerance;
  l.max_iterations = o.max_iterations;
  l.min_step = 1.0 / 16;
  l.max_step = o.max_step;
  l.levenberg_marquardt = o.levenberg_marquardt;
  l.stall_window = o.stall_window;
  l.stall_ratio = o.stall_ratio;
  RodShootingSystem system(model, integrator, y0, o.freeze_mesh_below);
  NewtonLoop loop(l);
  const NewtonLoopResult result = loop.run(system, {o.max_iterations}, false);
  y0 = system.base_state();
  NewtonOutcome out;
  out.status = result.status;
  out.iterations = result.iterations;
  out.jacobian_evaluations = result.jacobian_evaluations;
  out.message = result.message;
  out.mesh = system.frozen_mesh();
  return out;
}

}  // namespace shooting
}  // namespace pcr
