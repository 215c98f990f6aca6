// Scholtes' relaxation of the contact rows for Ipopt (contact_ipopt.hpp): a block wrapping the GapOnly
// contact rows of rod_contact.hpp, with one product row per pair, and the homotopy in mu.
#include "pcr/rods/contact_ipopt.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "pcr/core/error.hpp"

namespace pcr {

const char* to_string(ContactMethod method) {
  return method == ContactMethod::Ipopt ? "ipopt" : "semismooth";
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// One contact pair of a wrapped block: its gap row a = c_row (GapOnly) and its force
/// b = scale x[variable][column] (the multiplier lambda, scale L0 / F0).
struct ContactPair {
  int row = 0, variable = 0, column = 0;
  double scale = 1.0;
};

// The rows of `inner` (the gap rows bounded below by 0, the others as inner's), then per pair
//   S (a b - mu) <= 0,   S = kRelaxedProductScale,
// with mu the value of the last variable block. Jacobian of a product row: S (b da/dx + a db/dx - dmu).
class RelaxedContactBlock final : public ResidualBlock {
 public:
  RelaxedContactBlock(std::shared_ptr<const ResidualBlock> inner, std::vector<ContactPair> pairs,
                      std::vector<int> sizes, VariableId relaxation)
      : ResidualBlock(inner->kind() + "_relaxed", inner->name(),
                      inner->num_rows() + static_cast<int>(pairs.size()),
                      with(inner->variables(), relaxation)),
        inner_(std::move(inner)),
        pairs_(std::move(pairs)),
        sizes_(std::move(sizes)) {
    const int R = inner_->num_rows(), P = static_cast<int>(pairs_.size());
    VecX lower(R + P), upper(R + P);
    lower.head(R) = inner_->row_lower();
    upper.head(R) = inner_->row_upper();
    for (int q = 0; q < P; ++q) {
      lower[pairs_[q].row] = 0.0, upper[pairs_[q].row] = kInfinity;  // a >= 0
      lower[R + q] = -kInfinity, upper[R + q] = 0.0;                 // a b - mu <= 0
    }
    set_row_bounds(lower, upper);
  }

  int expected_variable_size(int k) const override { return k < inner_size() ? sizes_[k] : 1; }

  bool structural_nonzero(int k, int row, int column) const override {
    const int R = inner_->num_rows();
    if (k == inner_size()) return row >= R;
    if (row < R) return inner_->structural_nonzero(k, row, column);
    const ContactPair& q = pairs_[row - R];
    return inner_->structural_nonzero(k, q.row, column) || (k == q.variable && column == q.column);
  }

  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    // The inner rows first: row-major, so inner's R x size Jacobians are the first R rows of ours.
    inner_->evaluate(values, residual, jacobians);
    const int R = inner_->num_rows(), P = static_cast<int>(pairs_.size());
    const double mu = values[inner_size()][0];
    for (int q = 0; q < P; ++q) {
      const ContactPair& pair = pairs_[q];
      residual[R + q] =
          kRelaxedProductScale * (residual[pair.row] * pair.scale * values[pair.variable][pair.column] - mu);
    }
    if (jacobians == nullptr) return;
    for (int k = 0; k < inner_size(); ++k) {
      double* J = jacobians[k];
      if (J == nullptr) continue;
      const int s = sizes_[k];
      for (int q = 0; q < P; ++q) {
        const ContactPair& pair = pairs_[q];
        const double Sb = kRelaxedProductScale * pair.scale * values[pair.variable][pair.column];
        for (int c = 0; c < s; ++c) J[(R + q) * s + c] = Sb * J[pair.row * s + c];
        if (k == pair.variable)
          J[(R + q) * s + pair.column] += kRelaxedProductScale * residual[pair.row] * pair.scale;
      }
    }
    if (double* J = jacobians[inner_size()]) {
      std::fill(J, J + R, 0.0);
      std::fill(J + R, J + R + P, -kRelaxedProductScale);
    }
  }

 private:
  static std::vector<VariableId> with(std::vector<VariableId> variables, VariableId relaxation) {
    variables.push_back(relaxation);
    return variables;
  }
  int inner_size() const { return static_cast<int>(sizes_.size()); }

  std::shared_ptr<const ResidualBlock> inner_;
  std::vector<ContactPair> pairs_;
  std::vector<int> sizes_;  // of inner's variable blocks
};

// Index of variable v among the block's variables.
int variable_index(const ResidualBlock& block, VariableId v) {
  const auto& vars = block.variables();
  const auto it = std::find(vars.begin(), vars.end(), v);
  require(it != vars.end(), "relax_rod_contact: block '", block.name(), "' does not touch variable ", v);
  return static_cast<int>(it - vars.begin());
}

// Switches off block `id` and adds its relaxed form with `pairs` (pair.variable: a variable id, turned
// into its index here).
ResidualId relax_block(Problem& problem, ResidualId id, std::vector<ContactPair> pairs,
                       VariableId relaxation) {
  const std::shared_ptr<const ResidualBlock> inner = problem.residual_block(id);
  std::vector<int> sizes;
  for (VariableId v : inner->variables()) sizes.push_back(problem.variable(v).size);
  for (ContactPair& pair : pairs) pair.variable = variable_index(*inner, pair.variable);
  problem.set_residual_active(id, false);
  return problem.add_residual_block(
      std::make_shared<RelaxedContactBlock>(inner, std::move(pairs), std::move(sizes), relaxation));
}

}  // namespace

void relax_rod_contact(Problem& problem, const CollocationRod& rod, RodContactVariables& contact,
                       double relaxation) {
  const std::string& name = rod.model().name;
  require(contact.options.function == ComplementarityFunction::GapOnly, "rod '", name,
          "': the Ipopt treatment of contact needs the GapOnly rows (complementarity function ",
          to_string(contact.options.function), ")");
  require(contact.relaxation < 0, "rod '", name, "': contact relaxed twice");
  require(std::isfinite(relaxation) && relaxation >= 0.0, "rod '", name,
          "': contact relaxation mu = ", relaxation, " (must be >= 0)");
  contact.relaxation =
      problem.add_variable_block(name + ".contact_relaxation", VecX::Constant(1, relaxation));
  problem.fix_variable(contact.relaxation, VecX::Constant(1, relaxation));
  const double scale = rod.length_scale() / rod.force_scale();  // b = lambda L0 / F0
  const int K = static_cast<int>(contact.distributed.size());
  for (size_t j = 0; K > 0 && j < contact.blocks.size(); ++j) {
    const VariableId lambda = contact.multipliers[j];
    problem.set_variable_bounds(lambda, VecX::Zero(K), VecX::Constant(K, kInfinity));
    std::vector<ContactPair> pairs;
    for (int k = 0; k < K; ++k) pairs.push_back({3 + k, lambda, k, scale});  // rows 3 + k: g_k / L0
    contact.relaxed_blocks.push_back(
        relax_block(problem, contact.blocks[j], std::move(pairs), contact.relaxation));
  }
  for (size_t e = 0; e < contact.sharp_blocks.size(); ++e) {
    require(e >= contact.tangential_offsets.size() || contact.tangential_offsets[e] < 0, "rod '", name,
            "': the Ipopt treatment of contact does not cover adhesive rollers (use semismooth)");
    // [u_c, lambda, G]: lambda >= 0; row 4 is g(p(u_c)) / L0 (edge_contact_block.cpp).
    const VariableId v = contact.sharp_variables[e];
    VecX lower = VecX::Constant(5, -kInfinity), upper = VecX::Constant(5, kInfinity);
    lower[1] = 0.0;
    problem.set_variable_bounds(v, lower, upper);
    contact.relaxed_blocks.push_back(
        relax_block(problem, contact.sharp_blocks[e], {{4, v, 1, scale}}, contact.relaxation));
  }
}

IpoptOptions contact_ipopt_options(const ContactIpoptOptions& options) {
  IpoptOptions o;
  // Ipopt stops when its scaled overall error is below tol AND the unscaled violation below
  // constr_viol_tol. Without an objective every feasible point is a solution: the dual infeasibility
  // (part of the overall error) carries no information, and from the quasi-Newton Hessian it can stall
  // near 4e-9 while the rows hold to 1e-14 (seen on the propped cantilever: 500 iterations). So tol
  // checks optimality loosely and the constraint tolerance is the rows' tolerance.
  o.tol = std::max(options.tolerance, 1e-6);
  o.constraint_tolerance = options.tolerance;
  o.max_iterations = options.max_iterations;
  o.print_level = options.print_level;
  o.warm_start = true;
  return o;
}

SolveSummary solve_contact_homotopy(const Problem& problem,
                                    const std::vector<const RodContactVariables*>& contacts,
                                    IpoptSolver& solver, const ContactIpoptOptions& options, VecX& x) {
  require(!options.relaxations.empty(), "ContactIpoptOptions: no relaxation values");
  const auto start = std::chrono::steady_clock::now();
  SolveSummary summary;
  int iterations = 0, jacobians = 0;
  solver.reset_warm_start();
  for (size_t stage = 0; stage < options.relaxations.size(); ++stage) {
    const double mu = options.relaxations[stage];
    require(std::isfinite(mu) && mu >= 0.0, "ContactIpoptOptions: relaxation ", mu, " (must be >= 0)");
    for (const RodContactVariables* c : contacts) {
      require(c != nullptr && c->relaxation >= 0, "solve_contact_homotopy: a contact is not relaxed");
      x[problem.variable(c->relaxation).offset] = mu;
    }
    summary = solver.solve(x);
    iterations += summary.iterations;
    jacobians += summary.jacobian_evaluations;
    if (!summary.converged()) {
      char buffer[96];
      std::snprintf(buffer, sizeof buffer, " (contact homotopy stage %zu of %zu, mu = %.3g)", stage + 1,
                    options.relaxations.size(), mu);
      summary.message += buffer;
      break;
    }
  }
  summary.iterations = iterations;
  summary.jacobian_evaluations = jacobians;
  summary.solver = "ipopt (contact homotopy)";
  summary.wall_time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace pcr
