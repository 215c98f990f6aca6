// Pseudo-transient continuation to an equilibrium at fixed inputs (pseudo_transient_snap.hpp).
#include "pseudo_transient_snap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/solve/compressed_index.hpp"
#include "pcr/solve/grouped_lu.hpp"
#include "pcr/solve/newton_solver.hpp"

namespace pcr::kinematics {

namespace {

/// First pseudo-time step: the dampers (1/tau in the dimensionless rows) 10x a unit dimensionless
/// stiffness, so the first steps barely move from the start where the robot is soft.
constexpr double kFirstTau = 0.1;
/// Beyond this the dampers (1e-6 of a unit stiffness) no longer matter: the FK Newton solver finishes.
constexpr double kFinalTau = 1e6;
/// Pseudo-time steps (failed ones included) before giving up.
constexpr int kMaxSteps = 80;
/// Newton iterations per pseudo-time step, and their tolerance (intermediate states need not be exact;
/// the last solve is to the caller's tolerance).
constexpr int kStepIterations = 8;
constexpr double kStepTolerance = 1e-8;
/// Undamped residual below which the FK Newton solver is tried before tau reaches kFinalTau.
constexpr double kNearEquilibrium = 1e-6;
constexpr int kFinalIterations = 40;
/// After a failed pseudo-time step at tau_f the step grows back to at most kCeilingAfterFailure tau_f, a
/// cap that relaxes by kCeilingRelax per accepted step: without it the growth by 4 went straight back to
/// tau_f and failed there again (a random six_rus snap: 6 of its 24 failures in a row at the same tau,
/// 41 % of the damped motion's Newton iterations in failed steps over 10 such solves).
constexpr double kCeilingAfterFailure = 0.5;
constexpr double kCeilingRelax = 1.25;

using RowJacobian = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// One damped coordinate: a platform's position (3 rows, 3 columns), its rotation (3 rows; columns the
/// quaternion's 4) or a passive joint (1 row, 1 column); `scale` divides a length to make it
/// dimensionless.
struct Damper {
  enum class Kind { Position, Rotation, Joint } kind;
  int row, column;
  double scale;
};

/// The FK system with the dampers anchored at `anchor`, on the free columns.
class DampedSystem {
 public:
  DampedSystem(const RobotAssembly& a, double shift)
      : a_(a), row_lower_(a.problem().row_lower()), shift_(shift) {
    const Problem& p = a.problem();
    column_.assign(p.num_variables(), -1);
    std::vector<int> groups;  // variable group of each free column (-1: border)
    for (int v = 0; v < p.num_variable_blocks(); ++v) {
      if (p.variable_fixed(v)) continue;
      for (int k = 0; k < p.variable(v).size; ++k) {
        column_[p.variable(v).offset + k] = free_++;
        groups.push_back(p.variable(v).group);
      }
    }
    lu_.set_column_groups(std::move(groups));
    const double L0 = a.length_scale();
    for (int i = 0; i < static_cast<int>(a.model().platforms().size()); ++i) {
      if (p.variable_fixed(a.platform_variable(i)) || p.row_offset(a.platform_balance(i)) < 0) continue;
      const int row = p.row_offset(a.platform_balance(i)), col = p.variable(a.platform_variable(i)).offset;
      dampers_.push_back({Damper::Kind::Position, row, col, L0});
      dampers_.push_back({Damper::Kind::Rotation, row + 3, col + 3, 1.0});
    }
    const std::vector<int>& joints = a.model().passive_joints();
    for (int i = 0; i < static_cast<int>(joints.size()); ++i) {
      if (p.variable_fixed(a.passive_joint_variable(i)) || p.row_offset(a.passive_joint_balance(i)) < 0)
        continue;
      const bool prismatic = a.model().joints()[joints[i]].type == JointType::Prismatic;
      dampers_.push_back({Damper::Kind::Joint, p.row_offset(a.passive_joint_balance(i)),
                          p.variable(a.passive_joint_variable(i)).offset, prismatic ? L0 : 1.0});
    }
    if (shift_ > 0.0) list_shifted_columns();
  }

  /// g = R(x) - (1/tau) D (q(x) - q(anchor)); with matrix: M = dg/dx on the free columns. False if not
  /// finite.
  bool evaluate(const VecX& x, const VecX& anchor, double inv_tau, VecX& g, bool with_matrix) {
    VecX c;
    std::vector<Eigen::Triplet<double>> entries;  // the dampers' and the shift's entries
    RowJacobian& J = jacobian_;                   // kept: its pattern is not built again at every evaluation
    if (with_matrix) {
      a_.problem().evaluate_residuals_and_jacobian(x, c, J);
      ++jacobians_;
      if (J.rows() != free_) return false;  // not square
      entries.reserve(16 * dampers_.size() + shifted_.size());
    } else {
      a_.problem().evaluate_residuals(x, c);
    }
    g = c - row_lower_;
    for (const Damper& d : dampers_) add_damper(d, x, anchor, inv_tau, g, with_matrix ? &entries : nullptr);
    for (int k : shifted_) {  // the diagonal shift (shift / tau) D, D = I on the free index
      const int i = column_[k];
      g[i] -= shift_ * inv_tau * (x[k] - anchor[k]);
      if (with_matrix) entries.emplace_back(i, i, -shift_ * inv_tau);
    }
    if (!g.allFinite()) return false;
    if (!with_matrix) return true;
    // M = J_free + the dampers' and the shift's entries, written into the kept pattern (build_pattern).
    // J keeps its pattern while the problem's structure does (Problem::evaluate_residuals_and_jacobian).
    const std::uint64_t version = a_.problem().structure_version();
    if (pattern_version_ != version || slot_.size() != static_cast<size_t>(J.nonZeros())) {
      build_pattern(J, entries);
      pattern_version_ = version;
    }
    double* values = M_.valuePtr();
    std::fill(values, values + M_.nonZeros(), 0.0);
    const double* jv = J.valuePtr();
    for (size_t k = 0; k < slot_.size(); ++k)
      if (slot_[k] >= 0) values[slot_[k]] += jv[k];
    for (const Eigen::Triplet<double>& t : entries) {
      const int slot = slot_of(t.row(), t.col());
      if (slot < 0) return false;  // not in the pattern: cannot happen (the same entries every time)
      values[slot] += t.value();
    }
    return Eigen::Map<const VecX>(values, M_.nonZeros()).allFinite();
  }
  /// The structured LU of the FK Newton systems (the dampers and the shift keep the rods' bands and the
  /// border), the sparse LU where it has no such structure or a block is singular (grouped_lu.hpp).
  bool factorize() { return lu_.factorize(M_); }
  VecX solve(const VecX& rhs) const { return lu_.solve(rhs); }
  /// x + alpha dx on the free columns.
  VecX moved(const VecX& x, const VecX& dx, double alpha) const {
    VecX out = x;
    for (size_t k = 0; k < column_.size(); ++k)
      if (column_[k] >= 0) out[static_cast<int>(k)] += alpha * dx[column_[k]];
    return out;
  }
  int jacobians() const { return jacobians_; }

 private:
  /// Position: -(1/tau) (x - x_a) / L0 on the force rows. Rotation: -(1/tau) theta on the moment rows,
  /// theta = 2 vec(Q (x) conj(Q_a)) the world-frame rotation from the anchor's orientation (to first
  /// order; the moment rows pair with world rotations, robot_blocks.hpp). Joint: -(1/tau) (q - q_a) /
  /// scale. Each the force of a viscous damper (opposing the motion; R holds the net force).
  void add_damper(const Damper& d, const VecX& x, const VecX& anchor, double inv_tau, VecX& g,
                  std::vector<Eigen::Triplet<double>>* entries) const {
    if (d.kind != Damper::Kind::Rotation) {
      const int n = d.kind == Damper::Kind::Position ? 3 : 1;
      for (int i = 0; i < n; ++i) {
        g[d.row + i] -= inv_tau * (x[d.column + i] - anchor[d.column + i]) / d.scale;
        if (entries) entries->emplace_back(d.row + i, column_[d.column + i], -inv_tau / d.scale);
      }
      return;
    }
    const Quat Q = x.segment<4>(d.column), conj_anchor = quat_conjugate(anchor.segment<4>(d.column));
    const Vec3 theta = 2.0 * quat_multiply(Q, conj_anchor).tail<3>();
    g.segment<3>(d.row) -= inv_tau * theta;
    if (!entries) return;
    const double pw = conj_anchor[0];  // conj(Q_a) = [pw, pv]
    const Vec3 pv = conj_anchor.tail<3>();
    // d theta / d(qw, qv) = 2 [pv, pw I - hat(pv)].
    const Mat3 dv = pw * Mat3::Identity() - hat(pv);
    for (int i = 0; i < 3; ++i) {
      entries->emplace_back(d.row + i, column_[d.column], -inv_tau * 2.0 * pv[i]);
      for (int k = 0; k < 3; ++k)
        entries->emplace_back(d.row + i, column_[d.column + 1 + k], -inv_tau * 2.0 * dv(i, k));
    }
  }

  /// M's pattern: J's free columns and the damper and shift entries (at the same places at every
  /// evaluation); the slot of each of J's entries in it.
  void build_pattern(const RowJacobian& J, const std::vector<Eigen::Triplet<double>>& damping) {
    std::vector<Eigen::Triplet<double>> pattern;
    pattern.reserve(J.nonZeros() + damping.size());
    for (int r = 0; r < J.outerSize(); ++r)
      for (RowJacobian::InnerIterator it(J, r); it; ++it)
        if (column_[it.col()] >= 0) pattern.emplace_back(r, column_[it.col()], 0.0);
    for (const Eigen::Triplet<double>& t : damping) pattern.emplace_back(t.row(), t.col(), 0.0);
    M_.resize(free_, free_);
    M_.setFromTriplets(pattern.begin(), pattern.end());
    M_.makeCompressed();
    slot_.assign(J.nonZeros(), -1);
    for (int r = 0; r < J.outerSize(); ++r)
      for (Eigen::Index e = J.outerIndexPtr()[r]; e < J.outerIndexPtr()[r + 1]; ++e)
        if (column_[J.innerIndexPtr()[e]] >= 0) slot_[e] = slot_of(r, column_[J.innerIndexPtr()[e]]);
  }
  /// The index of entry (row, col) of M in its value array, -1 when M has no such entry.
  int slot_of(int row, int col) const {
    return compressed_index(M_.outerIndexPtr(), M_.innerIndexPtr(), col, row);
  }

  /// The free columns without a damper (the rods' unknowns, contact variables, ...).
  void list_shifted_columns() {
    std::vector<bool> damped(column_.size(), false);
    for (const Damper& d : dampers_) {
      const int n = d.kind == Damper::Kind::Position ? 3 : d.kind == Damper::Kind::Rotation ? 4 : 1;
      for (int i = 0; i < n; ++i) damped[d.column + i] = true;
    }
    for (size_t k = 0; k < column_.size(); ++k)
      if (column_[k] >= 0 && !damped[k]) shifted_.push_back(static_cast<int>(k));
  }

  const RobotAssembly& a_;
  VecX row_lower_;
  double shift_;
  std::vector<int> shifted_;  // global columns that get the diagonal shift
  std::vector<int> column_;   // free index of each global column, -1 when fixed
  int free_ = 0;
  std::vector<Damper> dampers_;
  RowJacobian jacobian_;  // J of the last evaluation (its pattern kept)
  Eigen::SparseMatrix<double> M_;
  std::uint64_t pattern_version_ = 0;  // the problem's structure_version() M's pattern was built for
  std::vector<int> slot_;              // per entry of J: its value's index in M, -1 for a fixed column
  GroupedLu lu_;
  int jacobians_ = 0;
};

/// One implicit Euler step: Newton with a backtracking line search on |g|_2 from the anchor. False when
/// it does not converge within kStepIterations.
bool pseudo_time_step(DampedSystem& s, const VecX& anchor, double inv_tau, VecX& x, int& iterations) {
  x = anchor;
  VecX g, trial_g;
  if (!s.evaluate(x, anchor, inv_tau, g, true)) return false;
  for (int it = 0; it < kStepIterations; ++it) {
    if (g.cwiseAbs().maxCoeff() <= kStepTolerance) return true;
    if (!s.factorize()) return false;
    const VecX dx = s.solve(-g);
    if (!dx.allFinite()) return false;
    ++iterations;
    double alpha = 1.0;
    VecX trial;
    for (;; alpha *= 0.5) {
      if (alpha < 1e-3) return false;
      trial = s.moved(x, dx, alpha);
      if (s.evaluate(trial, anchor, inv_tau, trial_g, false) &&
          trial_g.norm() <= (1.0 - 1e-4 * alpha) * g.norm())
        break;
    }
    x = trial;
    if (!s.evaluate(x, anchor, inv_tau, g, true)) return false;
  }
  return g.cwiseAbs().maxCoeff() <= kStepTolerance;
}

/// The FK Newton solver from x (undamped, the full tolerance).
bool finish(const RobotAssembly& a, double tolerance, VecX& x, PseudoTransientResult& out) {
  NewtonOptions o;
  o.tolerance = tolerance;
  NewtonSolver newton(a.problem(), o);
  VecX xs = x;
  const SolveSummary s = newton.solve(xs, kFinalIterations);
  out.iterations += s.iterations;
  out.jacobian_evaluations += s.jacobian_evaluations;
  if (!s.converged() || !xs.allFinite()) return false;
  x = xs;
  return true;
}

}  // namespace

PseudoTransientResult pseudo_transient_equilibrium(const RobotAssembly& assembly, const VecX& start,
                                                   double tolerance, double shift) {
  PseudoTransientResult out;
  out.x = start;
  DampedSystem system(assembly, shift);
  double tau = kFirstTau;
  double ceiling = std::numeric_limits<double>::infinity();  // tau's cap since the last failed step
  VecX g, next;
  for (int attempt = 0; attempt < kMaxSteps; ++attempt) {
    int iterations = 0;
    const bool ok = pseudo_time_step(system, out.x, 1.0 / tau, next, iterations);
    out.iterations += iterations;
    if (!ok) {
      ceiling = kCeilingAfterFailure * tau;
      tau *= 0.25;  // too long a pseudo-time step: the motion turned faster than Newton follows
      if (tau < 1e-6 * kFirstTau) {
        out.stopped = "pseudo-time step below " + std::to_string(tau);
        break;
      }
      continue;
    }
    out.x = next;
    ++out.steps;
    system.evaluate(out.x, out.x, 0.0, g, false);  // the undamped residual
    const bool near = g.cwiseAbs().maxCoeff() <= kNearEquilibrium;
    if ((near || tau >= kFinalTau) && finish(assembly, tolerance, out.x, out)) {
      out.converged = true;
      break;
    }
    if (tau >= kFinalTau) {
      out.stopped = "no convergence of the undamped system after the pseudo-time reached its end";
      break;
    }
    // Geometric growth while the steps are easy (Kelley & Keyes' SER rule, here by Newton's count).
    tau = std::min(ceiling, tau * (iterations <= 2 ? 4.0 : iterations <= 4 ? 2.0 : 1.0));
    ceiling *= kCeilingRelax;
  }
  if (!out.converged && out.stopped.empty()) out.stopped = "pseudo-time step budget used up";
  out.jacobian_evaluations += system.jacobians();
  return out;
}

}  // namespace pcr::kinematics
