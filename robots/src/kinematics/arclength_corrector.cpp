// Pseudo-arclength corrector on the FK system (arclength_corrector.hpp).
#include "arclength_corrector.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "pcr/solve/compressed_index.hpp"

namespace pcr::kinematics {

ArcCorrector::ArcCorrector(const RobotAssembly& assembly, const VecX& u_a, const VecX& u_b, double tolerance)
    : assembly_(assembly), u_a_(u_a), u_b_(u_b), tolerance_(tolerance) {
  const Problem& problem = assembly.problem();
  std::vector<int> groups;  // variable group of each free column, -1 for lambda (border)
  for (int v = 0; v < problem.num_variable_blocks(); ++v) {
    if (problem.variable_fixed(v)) continue;
    const VariableBlock& b = problem.variable(v);
    for (int k = 0; k < b.size; ++k) {
      free_.push_back(b.offset + k);
      groups.push_back(b.group);
    }
  }
  groups.push_back(-1);  // lambda: a border column
  lu_.set_column_groups(std::move(groups));
  for (int i = 0; i < static_cast<int>(u_a.size()); ++i)
    inputs_.push_back(problem.variable(assembly.input_variable(i)).offset);
  row_lower_ = problem.row_lower();
  weights_ = VecX::Ones(static_cast<int>(free_.size()) + 1);
}

VecX ArcCorrector::free_vector(const VecX& x, double lambda) const {
  const int n = static_cast<int>(free_.size());
  VecX y(n + 1);
  for (int i = 0; i < n; ++i) y[i] = x[free_[i]];
  y[n] = lambda;
  return y;
}

void ArcCorrector::write_state(const VecX& y, VecX& x) const {
  x = x_template_;
  for (size_t i = 0; i < free_.size(); ++i) x[free_[i]] = y[static_cast<int>(i)];
  assembly_.set_inputs(x, inputs_at(y[y.size() - 1]));
}

double ArcCorrector::weighted_dot(const VecX& a, const VecX& b) const {
  return (a.array() * weights_.array() * b.array()).sum();
}

bool ArcCorrector::evaluate(const VecX& y, const VecX& normal, VecX& residual) {
  const Problem& problem = assembly_.problem();
  VecX x, c;
  write_state(y, x);
  RowJacobian& J = jacobian_;  // kept: its pattern is not built again at every evaluation
  problem.evaluate_residuals_and_jacobian(x, c, J);
  ++jacobians_;
  residual = c - row_lower_;
  if (!residual.allFinite()) return false;
  // J keeps its pattern while the problem's structure does (Problem::evaluate_residuals_and_jacobian).
  if (pattern_version_ != problem.structure_version() || slot_.size() != static_cast<size_t>(J.nonZeros())) {
    build_pattern(J);
    pattern_version_ = problem.structure_version();
  }
  // The values into the kept pattern: each entry of J onto its slot (a free column's, or an input
  // column's onto its row's lambda slot times du_i: R_lambda = R_u du), then the hyperplane row.
  double* values = matrix_.valuePtr();
  std::fill(values, values + matrix_.nonZeros(), 0.0);
  const double* entries = J.valuePtr();
  for (size_t k = 0; k < slot_.size(); ++k)
    if (slot_[k] >= 0) values[slot_[k]] += factor_[k] * entries[k];
  for (size_t j = 0; j < normal_slot_.size(); ++j) values[normal_slot_[j]] = normal[j] * weights_[j];
  return Eigen::Map<const VecX>(values, matrix_.nonZeros()).allFinite();
}

void ArcCorrector::build_pattern(const RowJacobian& J) {
  const Problem& problem = assembly_.problem();
  const int n = static_cast<int>(free_.size());
  // Column map: free index, or -(input + 2) for an input column, -1 for other fixed ones.
  std::vector<int> column(problem.num_variables(), -1);
  for (int i = 0; i < n; ++i) column[free_[i]] = i;
  for (size_t i = 0; i < inputs_.size(); ++i) column[inputs_[i]] = -static_cast<int>(i) - 2;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(J.nonZeros() + 2 * (n + 1));
  for (int r = 0; r < J.outerSize(); ++r) {
    bool touches_input = false;
    for (RowJacobian::InnerIterator it(J, r); it; ++it) {
      const int k = column[it.col()];
      if (k >= 0) entries.emplace_back(r, k, 0.0);
      touches_input = touches_input || k <= -2;
    }
    if (touches_input) entries.emplace_back(r, n, 0.0);
  }
  for (int j = 0; j <= n; ++j) entries.emplace_back(n, j, 0.0);
  matrix_.resize(n + 1, n + 1);
  matrix_.setFromTriplets(entries.begin(), entries.end());
  matrix_.makeCompressed();
  // The slot of entry (row, col) in the column-major storage (every entry looked up is in the pattern).
  const auto slot_of = [this](int row, int col) {
    return compressed_index(matrix_.outerIndexPtr(), matrix_.innerIndexPtr(), col, row);
  };
  const VecX du = u_b_ - u_a_;
  slot_.assign(J.nonZeros(), -1);
  factor_.assign(J.nonZeros(), 0.0);
  for (int r = 0; r < J.outerSize(); ++r)
    for (Eigen::Index e = J.outerIndexPtr()[r]; e < J.outerIndexPtr()[r + 1]; ++e) {
      const int k = column[J.innerIndexPtr()[e]];
      if (k >= 0) {
        slot_[e] = slot_of(r, k);
        factor_[e] = 1.0;
      } else if (k <= -2) {
        slot_[e] = slot_of(r, n);
        factor_[e] = du[-k - 2];
      }
    }
  normal_slot_.resize(n + 1);
  for (int j = 0; j <= n; ++j) normal_slot_[j] = slot_of(n, j);
}

bool ArcCorrector::factorize() {
  return lu_.factorize(matrix_);
}

VecX ArcCorrector::solve(const VecX& rhs) const {
  return lu_.solve(rhs);
}

bool ArcCorrector::correct(const VecX& normal, const VecX& y0, double offset, VecX& y, VecX& tangent_out,
                           int max_iterations) {
  const int n = static_cast<int>(free_.size());
  VecX residual, rhs(n + 1);
  double first = -1.0;
  for (int it = 0; it <= max_iterations; ++it) {
    if (!evaluate(y, normal, residual)) return false;
    const double plane = weighted_dot(normal, y - y0) - offset;
    const double r = residual.cwiseAbs().maxCoeff();
    if (first < 0.0) first = r;
    // Diverging: far above where it started (the step is too long for this branch).
    if (it >= 2 && r > 1e3 * std::max(first, tolerance_)) return false;
    if (!factorize()) return false;
    if (r <= tolerance_ && std::abs(plane) <= 1e-12 * (1.0 + std::abs(offset))) {
      rhs.setZero();
      rhs[n] = 1.0;
      const VecX z = solve(rhs);
      const double norm = std::sqrt(weighted_dot(z, z));
      if (!(norm > 0.0) || !z.allFinite()) return false;
      tangent_out = z / norm;
      return true;
    }
    if (it == max_iterations) break;
    rhs.head(n) = -residual;
    rhs[n] = -plane;
    const VecX dy = solve(rhs);
    if (!dy.allFinite()) return false;
    y += dy;
    ++iterations_;
  }
  return false;
}

bool ArcCorrector::start(const VecX& x, ArcPoint& out) {
  x_template_ = x;
  const int n = static_cast<int>(free_.size());
  VecX e_lambda = VecX::Zero(n + 1);
  e_lambda[n] = 1.0;
  weights_.setOnes();
  VecX y = free_vector(x, 0.0), residual;
  if (!evaluate(y, e_lambda, residual) || !factorize()) return false;
  VecX rhs = VecX::Zero(n + 1);
  rhs[n] = 1.0;
  const VecX z = solve(rhs);  // (dx/dlambda, 1)
  if (!z.allFinite()) return false;
  // W: each free unknown divided by its column's largest entry in the dimensionless residuals (its own
  // scale), all of them together scaled so that the start tangent has equal parts in x and lambda.
  VecX column_max = VecX::Zero(n);
  for (int k = 0; k < n; ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(matrix_, k); it; ++it)
      if (it.row() < n) column_max[k] = std::max(column_max[k], std::abs(it.value()));
  for (int k = 0; k < n; ++k) weights_[k] = column_max[k] > 0.0 ? column_max[k] * column_max[k] : 1.0;
  const double x_part = (weights_.head(n).array() * z.head(n).array().square()).sum();
  if (x_part > 0.0 && std::isfinite(x_part)) weights_.head(n) /= x_part;
  weights_[n] = 1.0;
  out.x = x;
  out.lambda = 0.0;
  out.tangent = z / std::sqrt(weighted_dot(z, z));
  return true;
}

void ArcCorrector::rebalance(ArcPoint& p) {
  const int n = static_cast<int>(free_.size());
  const double tau = p.tau();
  const double x_part = (weights_.head(n).array() * p.tangent.head(n).array().square()).sum();
  if (!(x_part > 0.0) || !(std::abs(tau) > 0.0)) return;
  // W_x -> c W_x with c x_part / tau^2 = 1 (the x part of the tangent scaled to dlambda = 1 equal to
  // lambda's); not below 1e-8: a landing next to another fold (tau -> 0) keeps a usable metric.
  const double c = std::clamp(tau * tau / x_part, 1e-8, 1.0);
  weights_.head(n) *= c;
  p.tangent /= std::sqrt(weighted_dot(p.tangent, p.tangent));
}

ArcPoint ArcCorrector::predictor(const ArcPoint& from, double sigma) const {
  ArcPoint out;
  const VecX y = free_vector(from.x, from.lambda) + sigma * from.tangent;
  write_state(y, out.x);
  out.lambda = y[y.size() - 1];
  out.tangent = from.tangent;
  return out;
}

bool ArcCorrector::arclength_step(const ArcPoint& from, double sigma, ArcPoint& out, int max_iterations) {
  const VecX y0 = free_vector(from.x, from.lambda);
  VecX y = y0 + sigma * from.tangent, tangent;
  if (!correct(from.tangent, y0, sigma, y, tangent, max_iterations)) return false;
  write_state(y, out.x);
  out.lambda = y[y.size() - 1];
  out.tangent = tangent;
  return true;
}

bool ArcCorrector::at_lambda(const ArcPoint& guess, const VecX& orient, double target, ArcPoint& out,
                             int max_iterations) {
  const int n = static_cast<int>(free_.size());
  VecX e_lambda = VecX::Zero(n + 1);
  e_lambda[n] = 1.0;
  VecX y = free_vector(guess.x, guess.lambda), tangent;
  const VecX y0 = VecX::Zero(n + 1);
  if (!correct(e_lambda, y0, target, y, tangent, max_iterations)) return false;
  if (weighted_dot(orient, tangent) < 0.0) tangent = -tangent;
  write_state(y, out.x);
  out.lambda = y[n];
  out.tangent = tangent;
  return true;
}

}  // namespace pcr::kinematics
