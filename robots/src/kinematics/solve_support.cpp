#include "solve_support.hpp"

#include <sstream>

#include "pcr/robots/robot_stability.hpp"
#include "pcr/solve/free_jacobian.hpp"

namespace pcr::kinematics {

namespace {

// A solver that reports convergence at a non-finite point has failed.
void mark_non_finite(const VecX& x, SolveSummary& summary) {
  if (summary.converged() && !x.allFinite()) {
    summary.status = SolveStatus::Failed;
    summary.message = "non-finite solution";
  }
}

// Marks a converged solution failed when a rod is compressed to a point or inverted
// (admissible_axial_stretch; rod_solve.cpp checks single rods the same way). Returns whether the
// solution stays converged.
bool reject_inadmissible(RobotSolution& s) {
  if (!s.summary.converged()) return false;
  for (const RodResult& r : s.rods) {
    if (!admissible_axial_stretch(r.min_axial_stretch)) {
      std::ostringstream msg;
      msg << "inadmissible state: rod '" << r.name
          << "' has axial stretch v3 = 1 + eps3 = " << r.min_axial_stretch
          << " (compressed to a point or inverted; admissible: v3 > 0)"
          << (s.summary.message.empty() ? "" : "; " + s.summary.message);
      s.summary.status = SolveStatus::Failed;
      s.summary.message = msg.str();
      return false;
    }
  }
  return true;
}

}  // namespace

void account_for_round_off(const Problem& problem, const VecX& x, double tolerance, SolveSummary& summary) {
  if (!summary.converged() || !(summary.residual_max_abs > tolerance) || !x.allFinite()) return;
  const VecX xs = x.head(problem.num_variables());
  VecX c;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;
  problem.evaluate_residuals_and_jacobian(xs, c, J);
  const VecX r = c - c.cwiseMax(problem.row_lower()).cwiseMin(problem.row_upper());  // violation
  double bound = 0.0;
  std::ostringstream note;
  note << "|r|max = " << summary.residual_max_abs << " above the tolerance " << tolerance;
  if (residuals_within_round_off(J, xs, problem.variable_scales(), r, tolerance, bound)) {
    summary.residual_round_off = bound;
    note << ", within the round-off bound of each row (largest " << bound << ")";
    summary.message += "; converged to the round-off of the residuals: " + note.str();
    return;
  }
  summary.status = SolveStatus::Failed;
  summary.message =
      "residual above the tolerance and its round-off: " + note.str() + " (" + summary.message + ")";
}

void append_contact_warning(RobotSolution& s) {
  const std::string warning = contact_penetration_warning(s.contact_gaps);
  if (warning.empty()) return;
  s.summary.message += (s.summary.message.empty() ? "warning: " : "; warning: ") + warning;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

NewtonOptions newton_options(const KinematicsOptions& o) {
  NewtonOptions n;
  n.tolerance = o.tolerance;
  n.max_iterations = o.max_iterations;
  n.reuse_factorization = o.reuse_factorization;
  n.linear_solver = o.linear_solver;
  return n;
}

IpoptOptions ipopt_options(const KinematicsOptions& o) {
  IpoptOptions i;
  i.tol = o.tolerance;
  i.constraint_tolerance = o.tolerance;
  i.max_iterations = 3000;
  return i;
}

RobotSolution finish_solution(const RobotAssembly& assembly, const VecX& x, const VecX& x_fallback,
                              SolveSummary summary, Clock::time_point start,
                              const std::vector<std::vector<BasisDerivatives>>& sample_bases,
                              bool with_centerline, bool& accepted) {
  summary.wall_time_seconds = seconds_since(start);
  mark_non_finite(x, summary);
  RobotSolution out = read_solution(assembly, x.allFinite() ? x : x_fallback, sample_bases, with_centerline);
  out.summary = summary;
  append_contact_warning(out);
  accepted = reject_inadmissible(out);
  return out;
}

void monitor_stability(const Problem& fk, const VecX& x, int& last_sign, RobotSolution& out) {
  out.jacobian_sign = jacobian_determinant_sign(fk, x);
  if (out.jacobian_sign == 0) return;
  out.jacobian_sign_changed = last_sign != 0 && out.jacobian_sign != last_sign;
  last_sign = out.jacobian_sign;
}

void add_stability_verdict(const RobotAssembly& assembly, const VecX& x, RobotSolution& out) {
  out.stability_verdict = robot_stability(assembly, x.head(assembly.problem().num_variables()));
}

int definite_unstable_modes(const Stability& s) {
  return s.verdict == StabilityVerdict::Stable || s.verdict == StabilityVerdict::Unstable ? s.unstable_modes
                                                                                          : -1;
}

}  // namespace pcr::kinematics
