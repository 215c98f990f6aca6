// Robot FK / IK by shooting: see shooting_robot_solver.hpp for the unknowns, residuals and strategy.
#include "pcr/robots/shooting/shooting_robot_solver.hpp"

#include <Eigen/LU>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"

namespace pcr {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6x13 = Eigen::Matrix<double, 6, kRodStateSize>;

struct RodSetup {
  int rod = -1;
  int platform = -1;  ///< platform carrying the end link
  int input = -1;     ///< index of the fed-length input, or -1
  RodEndKind coupling = RodEndKind::Clamped;
  Pose base_frame;                    ///< world frame of the clamped start
  Pose end_offset;                    ///< end attachment frame in the platform frame
  RodModel model;                     ///< model.length = current length
  std::optional<RodOde> ode;          ///< rebuilt in place when the length changes (no allocation)
  std::vector<double> mesh_fraction;  ///< frozen Dormand-Prince steps, as fractions of L
  std::vector<double> mesh;
  RodStateWithTangents Y;  ///< tip state and d y(L) / d (n(0), m(0))
  RodStateVector dy_dL;    ///< f(L, y(L))
  RodTrajectory trajectory;
};

/// An external load carried by a platform, its point in the platform frame.
struct LoadSetup {
  int platform = -1;
  Vec3 point = Vec3::Zero();
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
};

struct State {
  std::vector<Vec3> n0, m0;
  std::vector<Pose> poses;
  VecX inputs;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

struct ShootingRobotSolver::Impl {
  std::shared_ptr<const RobotModel> model;
  ShootingRobotOptions options;
  std::vector<RodSetup> rods;
  std::vector<LoadSetup> loads;
  std::vector<std::vector<int>> rods_of_platform;
  double Ls = 1.0, Fs = 1.0, Ms = 1.0;  ///< length, force, moment scales
  bool ik_mode = false;
  bool frozen = false;
  bool has_warm = false;
  State warm;
  VecX row_scale;  ///< unscaled residual = scaled * row_scale
  /// LU of the last Newton Jacobian (scaled), for chord steps along warm-started sequences.
  Eigen::PartialPivLU<MatX> lu;
  bool lu_valid = false;
  void set_mode(bool ik) {
    if (ik != ik_mode) lu_valid = false;
    ik_mode = ik;
  }

  int num_rods() const { return static_cast<int>(rods.size()); }
  int num_platforms() const { return static_cast<int>(model->platforms().size()); }
  int num_unknowns() const {
    return 6 * num_rods() + (ik_mode ? static_cast<int>(model->inputs().size()) : 6 * num_platforms());
  }
  int num_residuals() const { return 6 * num_rods() + 6 * num_platforms(); }

  void setup();
  State cold_state(const VecX& inputs, const std::vector<Pose>& poses) const;
  void set_length(RodSetup& r, double L) {
    if (r.ode && r.model.length == L) return;
    r.model.length = L;
    r.ode.emplace(r.model);
  }
  bool integrate(const State& s, bool tangents);
  Vec6 tip_residual(const RodSetup& r, const RodStateVector& y, const Pose& platform) const;
  Vec6 balance(int k, const Pose& pose) const;
  void residual(const State& s, VecX& r) const;
  bool evaluate(const State& s, bool jacobian, VecX& r, MatX& J);
  State retract(const State& s, const VecX& dz) const;
  /// Newton from s; warm_start allows chord steps with the last factorised Jacobian.
  ShootingRobotResult solve(State s, bool warm_start = false);
  /// Solves at move(start, t) for t = 1/n, 2/n, ..., 1, each from the previous solution, with n = 4,
  /// 8, ..., 64 until every step converges; iterations and time of all attempts are summed.
  ShootingRobotResult continuation(const State& start, const std::function<void(State&, double)>& move,
                                   ShootingRobotResult failed);
  ShootingRobotResult result(const State& s) const;
};

void ShootingRobotSolver::Impl::setup() {
  const RobotModel& m = *model;
  for (const ActuationInput& in : m.inputs())
    require(in.kind == ActuationInput::Kind::RodLength, "ShootingRobotSolver: input '", in.name,
            "' is a joint value; joint-driven bases are not supported by the shooting solver");
  const VecX joints = m.default_joint_values();
  const std::vector<Pose> poses0 = m.initial_platform_poses();
  rods_of_platform.assign(m.platforms().size(), {});
  Ls = 0.0;
  double stiff_force = 0.0;
  for (int i = 0; i < static_cast<int>(m.rods().size()); ++i) {
    const RodElement& e = m.rods()[i];
    require(e.start.link >= 0 && m.carrying_platform(e.start.link) < 0, "ShootingRobotSolver: rod '", e.name,
            "' starts on a link carried by a platform (two-stage robots are not supported by the shooting "
            "solver)");
    require(e.start.coupling == RodEndKind::Clamped, "ShootingRobotSolver: rod '", e.name, "' has a ",
            to_string(e.start.coupling), " start; the shooting solver needs a clamped start");
    require(e.end.link >= 0 && m.carrying_platform(e.end.link) >= 0, "ShootingRobotSolver: rod '", e.name,
            "' does not end on a platform-carried link (not supported by the shooting solver)");
    require(e.end.coupling != RodEndKind::Free, "ShootingRobotSolver: rod '", e.name,
            "' has a free end (not supported by the shooting solver)");
    RodSetup r;
    r.rod = i;
    r.platform = m.carrying_platform(e.end.link);
    r.coupling = e.end.coupling;
    r.model = e.rod;
    for (int j = 0; j < static_cast<int>(m.inputs().size()); ++j)
      if (m.inputs()[j].index == i) r.input = j;
    r.base_frame = m.attachment_pose(e.start, joints, poses0);
    r.end_offset = poses0[r.platform].inverse() * m.attachment_pose(e.end, joints, poses0);
    set_length(r, e.rod.length);
    const double L = r.input >= 0 ? std::max(e.length_upper, e.rod.length) : e.rod.length;
    Ls = std::max(Ls, L);
    stiff_force =
        std::max(stiff_force, e.rod.bending_torsion_stiffness.maxCoeff() / (e.rod.length * e.rod.length));
    rods_of_platform[r.platform].push_back(i);
    rods.push_back(std::move(r));
  }
  for (int k = 0; k < num_platforms(); ++k)
    require(!rods_of_platform[k].empty(), "ShootingRobotSolver: platform '", m.platforms()[k].name,
            "' is held by no rod");
  double applied = 0.0;
  for (const Platform& p : m.platforms()) applied += p.mass * m.gravity().norm();
  for (const RodSetup& r : rods) applied += r.model.distributed_force().norm() * r.model.length;
  for (const ExternalLoad& l : m.loads()) {
    const int k = l.link >= 0 ? m.carrying_platform(l.link) : -1;
    if (k < 0) continue;  // carried by the ground
    LoadSetup s;
    s.platform = k;
    s.point =
        poses0[k].inverse().transform_point(m.link_pose(l.link, joints, poses0).transform_point(l.point));
    s.force = l.force;
    s.torque = l.torque;
    applied += l.force.norm() + l.torque.norm() / Ls;
    loads.push_back(s);
  }
  Fs = std::max(stiff_force, applied);
  Ms = Fs * Ls;
}

State ShootingRobotSolver::Impl::cold_state(const VecX& inputs, const std::vector<Pose>& poses) const {
  // Unbent rods sharing their platform's load equally: n(L) = (m g + F_ext) / N, n(0) = n(L) + f L.
  State s;
  s.inputs = inputs;
  s.poses = poses;
  std::vector<Vec3> share(num_platforms(), Vec3::Zero());
  for (int k = 0; k < num_platforms(); ++k) share[k] = model->platforms()[k].mass * model->gravity();
  for (const LoadSetup& l : loads) share[l.platform] += l.force;
  for (const RodSetup& r : rods) {
    const double L = r.input >= 0 ? inputs[r.input] : r.model.length;
    s.n0.push_back(share[r.platform] / static_cast<double>(rods_of_platform[r.platform].size()) +
                   r.model.distributed_force() * L);
    s.m0.push_back(Vec3::Zero());
  }
  return s;
}

bool ShootingRobotSolver::Impl::integrate(const State& s, bool tangents) {
  IntegratorOptions io;
  io.method = options.integrator;
  io.rk4_steps = options.rk4_steps;
  io.rel_tol = options.rel_tol;
  io.abs_tol = options.abs_tol;
  for (int i = 0; i < num_rods(); ++i) {
    RodSetup& r = rods[i];
    set_length(r, r.input >= 0 ? s.inputs[r.input] : r.model.length);
    const double L = r.model.length;
    if (!(L > 0.0)) return false;
    r.Y.setZero();
    r.Y.col(0).segment<3>(RodStateIndex::p) = r.base_frame.position;
    r.Y.col(0).segment<4>(RodStateIndex::q) = r.base_frame.orientation;
    r.Y.col(0).segment<3>(RodStateIndex::n) = s.n0[i];
    r.Y.col(0).segment<3>(RodStateIndex::m) = s.m0[i];
    IntegrationReport report;
    const bool on_mesh = frozen && options.integrator == IntegratorMethod::DormandPrince;
    if (on_mesh) {
      r.mesh.resize(r.mesh_fraction.size());
      for (size_t j = 0; j < r.mesh.size(); ++j) r.mesh[j] = r.mesh_fraction[j] * L;
    } else {
      r.trajectory.clear();
    }
    if (tangents) {
      for (int j = 0; j < 3; ++j) {
        r.Y(RodStateIndex::n + j, 1 + j) = 1.0;
        r.Y(RodStateIndex::m + j, 4 + j) = 1.0;
      }
      report = on_mesh ? integrate_rod_on_mesh(*r.ode, r.mesh, r.Y, options.integrator)
                       : integrate_rod(*r.ode, 0.0, L, r.Y, io, &r.trajectory);
    } else {
      RodStateVector y = r.Y.col(0);
      report = on_mesh ? integrate_rod_on_mesh(*r.ode, r.mesh, y, options.integrator)
                       : integrate_rod(*r.ode, 0.0, L, y, io, &r.trajectory);
      r.Y.col(0) = y;
    }
    if (!report.success || !r.Y.allFinite()) return false;
    if (tangents && r.input >= 0) {
      const RodStateVector y = r.Y.col(0);
      r.ode->derivative(L, y, r.dy_dL);  // d y(L) / dL for a rod fed through its clamped base
    }
  }
  return true;
}

Vec6 ShootingRobotSolver::Impl::tip_residual(const RodSetup& r, const RodStateVector& y,
                                             const Pose& platform) const {
  const Pose T = platform * r.end_offset;
  const Quat q = y.segment<4>(RodStateIndex::q).normalized();
  Vec6 res;
  res.head<3>() = (y.segment<3>(RodStateIndex::p) - T.position) / Ls;
  switch (r.coupling) {
    case RodEndKind::Clamped: {
      // q_e = conj(q_T) (x) q with w >= 0: 2 vec(q_e) = sin(theta/2) axis, zero only at R = R_T.
      Quat qe = quat_multiply(quat_conjugate(T.orientation.normalized()), q);
      if (qe[0] < 0) qe = -qe;
      res.tail<3>() = 2.0 * qe.tail<3>();
      break;
    }
    case RodEndKind::Collar: {
      // d3 along the collar axis: the components of R_T^T d3 normal to it; free torsion: m(L) . d3 = 0.
      const Vec3 d3 = rotation_matrix(q).col(2);
      const Vec3 b = T.rotation().transpose() * d3;
      res[3] = b[0];
      res[4] = b[1];
      res[5] = y.segment<3>(RodStateIndex::m).dot(d3) / Ms;
      break;
    }
    default:  // spherical: no moment transmitted
      res.tail<3>() = y.segment<3>(RodStateIndex::m) / Ms;
  }
  return res;
}

Vec6 ShootingRobotSolver::Impl::balance(int k, const Pose& pose) const {
  // F_ext + m g - sum n(L) = 0 and the moments about the platform origin x (DESIGN.md §3).
  const Platform& p = model->platforms()[k];
  const Mat3 R = pose.rotation();
  const Vec3 weight = p.mass * model->gravity();
  Vec3 F = weight, M = (R * p.center_of_mass).cross(weight);
  for (const LoadSetup& l : loads)
    if (l.platform == k) {
      F += l.force;
      M += l.torque + (R * l.point).cross(l.force);
    }
  for (int i : rods_of_platform[k]) {
    const RodStateVector& y = rods[i].Y.col(0);
    const Vec3 n = y.segment<3>(RodStateIndex::n);
    F -= n;
    M -= y.segment<3>(RodStateIndex::m) + (y.segment<3>(RodStateIndex::p) - pose.position).cross(n);
  }
  Vec6 b;
  b << F / Fs, M / Ms;
  return b;
}

void ShootingRobotSolver::Impl::residual(const State& s, VecX& r) const {
  r.resize(num_residuals());
  for (int i = 0; i < num_rods(); ++i)
    r.segment<6>(6 * i) = tip_residual(rods[i], rods[i].Y.col(0), s.poses[rods[i].platform]);
  for (int k = 0; k < num_platforms(); ++k) r.segment<6>(6 * num_rods() + 6 * k) = balance(k, s.poses[k]);
}

bool ShootingRobotSolver::Impl::evaluate(const State& s, bool jacobian, VecX& r, MatX& J) {
  if (!integrate(s, jacobian)) return false;
  residual(s, r);
  if (!r.allFinite()) return false;
  if (!jacobian) return true;
  const int nr = num_rods(), rows0 = 6 * nr;
  J.setZero(num_residuals(), num_unknowns());
  Eigen::Matrix<double, 6, 6> unknown_scale = Eigen::Matrix<double, 6, 6>::Zero();
  unknown_scale.diagonal() << Fs, Fs, Fs, Ms, Ms, Ms;
  RodStateVector h_state;
  h_state << Vec3::Constant(Ls), Quat::Constant(1.0), Vec3::Constant(Fs), Vec3::Constant(Ms);
  h_state *= 1e-6;  // central differences: truncation ~(1e-6)^2, round-off ~1e-16 / 1e-6
  for (int i = 0; i < nr; ++i) {
    const RodSetup& rod = rods[i];
    const int k = rod.platform;
    const RodStateVector y = rod.Y.col(0);
    // d(tip residual)/dy(L) by central differences of the algebraic function.
    Mat6x13 D;
    for (int c = 0; c < kRodStateSize; ++c) {
      RodStateVector yp = y, ym = y;
      yp[c] += h_state[c];
      ym[c] -= h_state[c];
      D.col(c) = (tip_residual(rod, yp, s.poses[k]) - tip_residual(rod, ym, s.poses[k])) / (2 * h_state[c]);
    }
    // d(balance)/dy(L): -n, -(m + (p - x) x n), exact.
    Mat6x13 E = Mat6x13::Zero();
    const Vec3 n = y.segment<3>(RodStateIndex::n), arm = y.segment<3>(RodStateIndex::p) - s.poses[k].position;
    E.block<3, 3>(0, RodStateIndex::n) = -Mat3::Identity() / Fs;
    E.block<3, 3>(3, RodStateIndex::p) = hat(n) / Ms;
    E.block<3, 3>(3, RodStateIndex::n) = -hat(arm) / Ms;
    E.block<3, 3>(3, RodStateIndex::m) = -Mat3::Identity() / Ms;
    const auto tangents = rod.Y.rightCols<kRodTangentCount>();
    J.block<6, 6>(6 * i, 6 * i) = D * tangents * unknown_scale;
    J.block<6, 6>(rows0 + 6 * k, 6 * i) = E * tangents * unknown_scale;
    if (ik_mode && rod.input >= 0) {
      const int col = rows0 + rod.input;
      J.block<6, 1>(6 * i, col) += D * rod.dy_dL * Ls;
      J.block<6, 1>(rows0 + 6 * k, col) += E * rod.dy_dL * Ls;
    }
  }
  if (!ik_mode) {
    // Platform pose columns: central differences of the algebraic tip and balance residuals.
    VecX rp, rm;
    for (int k = 0; k < num_platforms(); ++k)
      for (int c = 0; c < 6; ++c) {
        const double h = 1e-6;
        VecX dz = VecX::Zero(num_unknowns());
        State sp = s, sm = s;
        dz[rows0 + 6 * k + c] = h;
        sp = retract(s, dz);
        sm = retract(s, -dz);
        residual(sp, rp);
        residual(sm, rm);
        J.col(rows0 + 6 * k + c) = (rp - rm) / (2 * h);
      }
  }
  return J.allFinite();
}

State ShootingRobotSolver::Impl::retract(const State& s, const VecX& dz) const {
  State t = s;
  const int nr = num_rods(), c0 = 6 * nr;
  for (int i = 0; i < nr; ++i) {
    t.n0[i] += Fs * dz.segment<3>(6 * i);
    t.m0[i] += Ms * dz.segment<3>(6 * i + 3);
  }
  if (ik_mode) {
    t.inputs += Ls * dz.segment(c0, t.inputs.size());
  } else {
    for (int k = 0; k < num_platforms(); ++k) {
      t.poses[k].position += Ls * dz.segment<3>(c0 + 6 * k);
      // World rotation vector increment: R <- exp(hat(dtheta)) R.
      t.poses[k].orientation =
          quat_multiply(quat_from_rotation_vector(dz.segment<3>(c0 + 6 * k + 3)), s.poses[k].orientation)
              .normalized();
    }
  }
  return t;
}

ShootingRobotResult ShootingRobotSolver::Impl::solve(State s, bool warm_start) {
  const auto t0 = std::chrono::steady_clock::now();
  ShootingSummary summary;
  summary.solver = std::string("shooting (") + to_string(options.integrator) + ")";
  frozen = false;
  VecX r, r_trial;
  MatX J, J_trial;
  const bool dp = options.integrator == IntegratorMethod::DormandPrince;
  std::vector<double> history;
  // Chord steps (the Jacobian of an earlier solution, state-only integrations, ~5x cheaper) while
  // they reduce the residual by half; Newton with a fresh Jacobian from the first one that does not.
  bool chord = warm_start && lu_valid && options.reuse_jacobian;
  bool have_J = !chord;
  if (!evaluate(s, have_J, r, J)) {
    summary.status = SolveStatus::Failed;
    summary.message = "integration failed at the initial guess";
  } else {
    summary.status = SolveStatus::MaxIterations;
    summary.message = "no convergence in " + std::to_string(options.max_iterations) + " iterations";
    for (int it = 0;; ++it) {
      if (dp && !frozen && r.lpNorm<Eigen::Infinity>() < options.freeze_mesh_below) {
        // Freeze every rod's current (adaptive) steps: the last evaluation was of s.
        for (RodSetup& rod : rods) {
          rod.mesh_fraction = rod.trajectory.s;
          for (double& x : rod.mesh_fraction) x /= rod.model.length;
          rod.mesh_fraction.back() = 1.0;
        }
        frozen = true;
        if (!evaluate(s, have_J, r, J)) {
          summary.status = SolveStatus::Failed;
          summary.message = "integration failed on the frozen mesh";
          break;
        }
      }
      if (r.lpNorm<Eigen::Infinity>() <= options.residual_tolerance) {
        summary.status = SolveStatus::Converged;
        summary.message.clear();
        break;
      }
      if (it >= options.max_iterations) break;
      // Stalled (e.g. on the way to another equilibrium branch): less than 10 % progress over 10
      // iterations; the caller then falls back to continuation.
      history.push_back(r.norm());
      const size_t window = static_cast<size_t>(std::max(options.stall_window, 0));
      if (window > 0 && history.size() > window &&
          history.back() > 0.9 * history[history.size() - 1 - window]) {
        summary.status = SolveStatus::Failed;
        summary.message =
            "stalled: residual fell by less than 10 % over " + std::to_string(window) + " iterations";
        break;
      }
      summary.iterations = it + 1;
      if (chord) {
        VecX dz = lu.solve(-r);
        const double big = dz.lpNorm<Eigen::Infinity>();
        if (big > options.max_step) dz *= options.max_step / big;
        const State trial = retract(s, dz);
        if (dz.allFinite() && evaluate(trial, false, r_trial, J_trial) && r_trial.norm() < 0.5 * r.norm()) {
          s = trial;
          r.swap(r_trial);
          continue;
        }
        chord = false;
      }
      if (!have_J && !evaluate(s, true, r, J)) {
        summary.status = SolveStatus::Failed;
        summary.message = "integration failed";
        break;
      }
      have_J = true;
      lu.compute(J);
      lu_valid = true;
      VecX dz = lu.solve(-r);
      bool accepted = false;
      if (dz.allFinite()) {
        const double big = dz.lpNorm<Eigen::Infinity>();
        if (big > options.max_step) dz *= options.max_step / big;
        for (double alpha = 1.0; alpha > 1e-3 && !accepted; alpha *= 0.5) {
          const State trial = retract(s, alpha * dz);
          if (evaluate(trial, true, r_trial, J_trial) && r_trial.norm() < (1.0 - 1e-4 * alpha) * r.norm()) {
            s = trial;
            accepted = true;
          }
        }
      }
      if (!accepted && options.levenberg_marquardt) {
        // Levenberg-Marquardt: (J^T J + mu diag(J^T J)) dz = -J^T r with mu increasing until descent.
        const MatX JtJ = J.transpose() * J;
        const VecX g = J.transpose() * r;
        for (double mu = 1e-4; mu < 1e8 && !accepted; mu *= 10.0) {
          MatX A = JtJ;
          A.diagonal() += mu * (JtJ.diagonal().array() + 1e-12).matrix();
          VecX step = A.partialPivLu().solve(-g);
          if (!step.allFinite()) continue;
          const double big = step.lpNorm<Eigen::Infinity>();
          if (big > options.max_step) step *= options.max_step / big;
          const State trial = retract(s, step);
          if (evaluate(trial, true, r_trial, J_trial) && r_trial.norm() < r.norm()) {
            s = trial;
            accepted = true;
          }
        }
      }
      if (!accepted) {
        summary.status = SolveStatus::Failed;
        summary.message = "stalled: no step reduces the residual";
        // Restore the state of s in the rods (the last evaluation was a rejected trial).
        evaluate(s, false, r, J);
        break;
      }
      r.swap(r_trial);
      J.swap(J_trial);
    }
  }
  summary.residual_scaled_max_abs = r.size() ? r.lpNorm<Eigen::Infinity>() : 0.0;
  summary.residual_max_abs = r.size() ? r.cwiseProduct(row_scale).lpNorm<Eigen::Infinity>() : 0.0;
  for (const RodSetup& rod : rods)
    summary.integration_steps +=
        std::max(0, static_cast<int>(frozen ? rod.mesh.size() : rod.trajectory.s.size()) - 1);
  if (options.integrator == IntegratorMethod::RK4) summary.integration_steps = options.rk4_steps * num_rods();
  summary.wall_time_seconds = seconds_since(t0);
  if (!r.allFinite()) {
    summary.residual_max_abs = summary.residual_scaled_max_abs = 0.0;
    summary.status = SolveStatus::Failed;
  }
  ShootingRobotResult out = result(s);
  out.summary = summary;
  if (summary.converged()) {
    warm = s;
    has_warm = true;
  }
  return out;
}

ShootingRobotResult ShootingRobotSolver::Impl::continuation(const State& start,
                                                            const std::function<void(State&, double)>& move,
                                                            ShootingRobotResult failed) {
  int iterations = failed.summary.iterations;
  double time = failed.summary.wall_time_seconds;
  for (int n = 4; n <= 64; n *= 2) {
    State s = start;
    ShootingRobotResult out;
    bool ok = true;
    for (int j = 1; j <= n && ok; ++j) {
      move(s, static_cast<double>(j) / n);
      out = solve(s, true);
      iterations += out.summary.iterations;
      time += out.summary.wall_time_seconds;
      ok = out.summary.converged();
      if (ok) s = warm;
    }
    if (ok) {
      out.summary.iterations = iterations;
      out.summary.wall_time_seconds = time;
      out.summary.load_steps = n;
      out.summary.message = "continuation in " + std::to_string(n) + " steps";
      return out;
    }
  }
  failed.summary.iterations = iterations;
  failed.summary.wall_time_seconds = time;
  failed.summary.message += "; continuation failed";
  return failed;
}

ShootingRobotResult ShootingRobotSolver::Impl::result(const State& s) const {
  ShootingRobotResult out;
  out.inputs = s.inputs;
  out.platforms = s.poses;
  for (int i = 0; i < num_rods(); ++i) {
    const RodSetup& r = rods[i];
    const RodStateVector y = r.Y.col(0);
    ShootingRodResult rr;
    rr.name = model->rods()[r.rod].name;
    rr.length = r.model.length;
    rr.base_force = s.n0[i];
    rr.base_moment = s.m0[i];
    rr.tip_position = y.segment<3>(RodStateIndex::p);
    rr.tip_rotation = rotation_matrix(y.segment<4>(RodStateIndex::q));
    rr.tip_force = y.segment<3>(RodStateIndex::n);
    rr.tip_moment = y.segment<3>(RodStateIndex::m);
    out.rods.push_back(rr);
  }
  return out;
}

ShootingRobotSolver::ShootingRobotSolver(std::shared_ptr<const RobotModel> model,
                                         const ShootingRobotOptions& options)
    : impl_(std::make_unique<Impl>()) {
  require(model != nullptr, "ShootingRobotSolver: model is null");
  require(options.rk4_steps > 0, "ShootingRobotOptions.rk4_steps = ", options.rk4_steps, " must be > 0");
  require(options.rel_tol > 0 && options.abs_tol > 0, "ShootingRobotOptions: rel_tol = ", options.rel_tol,
          ", abs_tol = ", options.abs_tol, " must be > 0");
  require(options.residual_tolerance > 0,
          "ShootingRobotOptions.residual_tolerance = ", options.residual_tolerance, " must be > 0");
  require(options.max_iterations >= 0, "ShootingRobotOptions.max_iterations = ", options.max_iterations,
          " must be >= 0");
  require(options.max_step > 0, "ShootingRobotOptions.max_step = ", options.max_step, " must be > 0");
  impl_->model = std::move(model);
  impl_->options = options;
  impl_->setup();
  const int nr = impl_->num_rods();
  impl_->row_scale.resize(impl_->num_residuals());
  for (int i = 0; i < nr; ++i) {
    const bool moment = impl_->rods[i].coupling == RodEndKind::Spherical;
    impl_->row_scale.segment<6>(6 * i) << Vec3::Constant(impl_->Ls), Vec3::Constant(moment ? impl_->Ms : 1.0);
    if (impl_->rods[i].coupling == RodEndKind::Collar) impl_->row_scale[6 * i + 5] = impl_->Ms;
  }
  for (int k = 0; k < impl_->num_platforms(); ++k)
    impl_->row_scale.segment<6>(6 * nr + 6 * k) << Vec3::Constant(impl_->Fs), Vec3::Constant(impl_->Ms);
}

ShootingRobotSolver::~ShootingRobotSolver() = default;
ShootingRobotSolver::ShootingRobotSolver(ShootingRobotSolver&&) noexcept = default;
ShootingRobotSolver& ShootingRobotSolver::operator=(ShootingRobotSolver&&) noexcept = default;

const RobotModel& ShootingRobotSolver::model() const {
  return *impl_->model;
}
const ShootingRobotOptions& ShootingRobotSolver::options() const {
  return impl_->options;
}
void ShootingRobotSolver::reset() {
  impl_->has_warm = false;
}

ShootingRobotResult ShootingRobotSolver::fk(const VecX& inputs) {
  const RobotModel& m = *impl_->model;
  require(inputs.size() == static_cast<int>(m.inputs().size()), "ShootingRobotSolver::fk: ", inputs.size(),
          " inputs given, the model has ", m.inputs().size());
  for (int j = 0; j < inputs.size(); ++j)
    require(std::isfinite(inputs[j]) && inputs[j] >= m.inputs()[j].lower && inputs[j] <= m.inputs()[j].upper,
            "ShootingRobotSolver::fk: input '", m.inputs()[j].name, "' = ", inputs[j], " outside [",
            m.inputs()[j].lower, ", ", m.inputs()[j].upper, "]");
  impl_->set_mode(false);
  ShootingSummary first;  // a cold start goes through the default inputs (the URDF's initial pose fits them)
  const VecX u0 = m.default_input_values();
  if (!impl_->has_warm && inputs != u0) {
    first = impl_->solve(impl_->cold_state(u0, m.initial_platform_poses())).summary;
    if (!first.converged()) {
      ShootingRobotResult failed = impl_->solve(impl_->cold_state(inputs, m.initial_platform_poses()));
      failed.summary.iterations += first.iterations;
      failed.summary.wall_time_seconds += first.wall_time_seconds;
      return failed;
    }
  }
  State s = impl_->has_warm ? impl_->warm : impl_->cold_state(inputs, m.initial_platform_poses());
  s.inputs = inputs;
  ShootingRobotResult out = impl_->solve(s, impl_->has_warm);
  out.summary.iterations += first.iterations;
  out.summary.wall_time_seconds += first.wall_time_seconds;
  if (out.summary.converged()) return out;
  // Continuation in the inputs from the last solution (or from a cold solve at the default inputs).
  if (!impl_->has_warm) {
    const ShootingRobotResult at_default = impl_->solve(impl_->cold_state(u0, m.initial_platform_poses()));
    out.summary.iterations += at_default.summary.iterations;
    out.summary.wall_time_seconds += at_default.summary.wall_time_seconds;
    if (!at_default.summary.converged()) return out;
  }
  const State start = impl_->warm;
  return impl_->continuation(
      start, [&](State& st, double t) { st.inputs = start.inputs + t * (inputs - start.inputs); }, out);
}

ShootingRobotResult ShootingRobotSolver::ik(const std::vector<Pose>& targets) {
  const RobotModel& m = *impl_->model;
  require(static_cast<int>(targets.size()) == impl_->num_platforms(),
          "ShootingRobotSolver::ik: ", targets.size(), " targets given, the model has ",
          impl_->num_platforms(), " platforms");
  require(m.inputs().size() == 6 * targets.size(), "ShootingRobotSolver::ik: model '", m.name(), "' has ",
          m.inputs().size(), " inputs; the shooting IK needs 6 per platform (a square system)");
  std::vector<Pose> poses = targets;
  for (Pose& p : poses) {
    require(p.position.allFinite() && p.orientation.allFinite() && p.orientation.norm() > 0,
            "ShootingRobotSolver::ik: target pose is not finite or has a zero quaternion");
    p.orientation.normalize();
  }
  impl_->set_mode(true);
  State s = impl_->has_warm ? impl_->warm : impl_->cold_state(m.default_input_values(), poses);
  s.poses = poses;
  ShootingRobotResult out = impl_->solve(s, impl_->has_warm);
  if (!out.summary.converged()) {
    // Continuation in the targets from the last solution's poses (or the FK solution at the default
    // inputs): positions linear, rotations along the geodesic R(t) = exp(t log(R_1 R_0^T)) R_0.
    bool have_start = impl_->has_warm;
    if (!have_start) {
      const ShootingRobotResult at_default = fk(m.default_input_values());
      out.summary.iterations += at_default.summary.iterations;
      out.summary.wall_time_seconds += at_default.summary.wall_time_seconds;
      have_start = at_default.summary.converged();
      impl_->set_mode(true);
    }
    if (have_start) {
      const State start = impl_->warm;
      out = impl_->continuation(
          start,
          [&](State& st, double t) {
            for (size_t k = 0; k < poses.size(); ++k) {
              const Pose& a = start.poses[k];
              st.poses[k].position = a.position + t * (poses[k].position - a.position);
              const Vec3 w = so3_log(poses[k].rotation() * a.rotation().transpose());
              st.poses[k].orientation =
                  quat_multiply(quat_from_rotation_vector(t * w), a.orientation).normalized();
            }
          },
          out);
    }
  }
  if (out.summary.converged())
    for (int j = 0; j < out.inputs.size(); ++j)
      if (out.inputs[j] < m.inputs()[j].lower || out.inputs[j] > m.inputs()[j].upper)
        out.summary.message +=
            "input '" + m.inputs()[j].name + "' = " + std::to_string(out.inputs[j]) + " outside its bounds; ";
  return out;
}

}  // namespace pcr
