// The contact rows of one midpoint u_j (rod_contact.hpp): with p = sum_i N_i(u_j) P_i,
//   rows 0..2:   (F_j - sum_k lambda_k nu_k(p)) L0 / F0           (scaled as the mixed force balance)
//   row 3 + k:   phi(g_k(p) / L0, lambda_k L0 / F0)                (complementarity with obstacle k)
// Variables: the p + 1 active control points (only their P components enter), F_j (3), lambda_j (K).
// Jacobians by hand: d g / d p = nu, d nu / d p from obstacle_gap.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "edge_contact.hpp"
#include "pcr/core/error.hpp"
#include "pcr/rods/rod_contact.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr {

const char* to_string(ComplementarityFunction function) {
  if (function == ComplementarityFunction::GapOnly) return "gap_only";
  return function == ComplementarityFunction::Min ? "min" : "fischer_burmeister";
}

namespace contact {

void complementarity(ComplementarityFunction f, double a, double b, double& phi, double& phi_a,
                     double& phi_b) {
  if (f == ComplementarityFunction::GapOnly) {  // the gap row of the Ipopt treatment (contact_ipopt.cpp)
    phi = a;
    phi_a = 1.0;
    phi_b = 0.0;
    return;
  }
  if (f == ComplementarityFunction::Min) {
    phi = std::min(a, b);
    phi_a = a <= b ? 1.0 : 0.0;
    phi_b = 1.0 - phi_a;
    return;
  }
  // phi = a + b - rho, evaluated as 2 a b / (a + b + rho) where a + b > 0 (the same function, since
  // (a + b)^2 - rho^2 = 2 a b): the difference cancels where one argument dwarfs the other, leaving eps
  // max(a, b) of round-off in the row that the solver's round-off bound, eps sum_j |J_ij x_j|, does not
  // see (d phi / d b ~ 0 there): a planar_post rod pressed on the post left 5.9e-10 > the 1e-10 tolerance.
  const double rho = std::hypot(a, b);
  phi = a + b > 0.0 ? 2.0 * a * b / (a + b + rho) : a + b - rho;
  if (rho == 0.0) {
    phi_a = phi_b = 1.0 - 1.0 / std::sqrt(2.0);  // an element of the generalised Jacobian at (0, 0)
    return;
  }
  phi_a = 1.0 - a / rho;
  phi_b = 1.0 - b / rho;
}

}  // namespace contact

namespace {

using contact::complementarity;

// The density that a concentrated force F = G L at u_c puts into the force balance of midpoint j:
// W_j(u_c) G with W_j = sum_i B_i(u_j) w_i(u_c) / (tau_{i+1} - tau_i). The mixed form's n' is the spline
// sum_i D_i B_i(u) of degree p - 1 (knots without the end ones) with D_i = (N_{i+1} - N_i) / (L (tau_{i+1}
// - tau_i)); a force that sets D_i = -w_i G / (tau_{i+1} - tau_i) makes the control points N jump by
// exactly -w_i F, so the rod carries the whole of F (the plain midpoint densities w_j F / (L (tau_{j+1} -
// tau_j)) would not: the collocated n'(u_j) averages neighbouring D_i).
struct SharpShares {
  std::shared_ptr<const std::vector<double>> midpoints;
  std::vector<std::pair<int, double>> spread;  // (i, B_i(u_j) / (tau_{i+1} - tau_i)), B_i(u_j) != 0
  int count = 0;                               // sharp obstacles
};

// SharpShares::spread of every midpoint (degree 1, or an interior knot of multiplicity p: the identity,
// n' then being constant on each cell).
std::vector<std::vector<std::pair<int, double>>> derivative_spreads(const KnotVector& knots,
                                                                    const std::vector<double>& tau,
                                                                    const std::vector<double>& midpoints) {
  const int p = knots.degree();
  const std::vector<double>& t = knots.knots();
  bool c1 = p > 1;
  for (size_t i = p + 1; c1 && i + p + 1 < t.size(); ++i) c1 = knots.multiplicity(t[i]) < p;
  std::vector<std::vector<std::pair<int, double>>> out(midpoints.size());
  if (!c1) {
    for (size_t j = 0; j < midpoints.size(); ++j)
      out[j] = {{static_cast<int>(j), 1.0 / (tau[j + 1] - tau[j])}};
    return out;
  }
  const KnotVector derivative(p - 1, std::vector<double>(t.begin() + 1, t.end() - 1));
  for (size_t j = 0; j < midpoints.size(); ++j) {
    const BasisDerivatives b = basis_derivatives(derivative, midpoints[j], 0);
    for (int k = 0; k < b.values.cols(); ++k) {
      const int i = b.first + k;
      if (b.values(0, k) != 0.0) out[j].push_back({i, b.values(0, k) / (tau[i + 1] - tau[i])});
    }
  }
  return out;
}

class ContactBlock final : public ResidualBlock {
 public:
  ContactBlock(std::string name, std::vector<VariableId> variables, std::vector<double> basis, int point_size,
               int p_offset, std::vector<Obstacle> obstacles, const RodContactOptions& options,
               SharpShares sharp, double length_scale, double force_scale)
      : ResidualBlock("rod.contact", std::move(name), 3 + static_cast<int>(obstacles.size()),
                      std::move(variables)),
        basis_(std::move(basis)),
        point_size_(point_size),
        p_offset_(p_offset),
        obstacles_(std::move(obstacles)),
        radius_(options.radius),
        function_(options.function),
        sharp_(std::move(sharp)),
        length_scale_(length_scale),
        density_scale_(length_scale / force_scale) {}

  int num_points() const { return static_cast<int>(basis_.size()); }
  int num_obstacles() const { return static_cast<int>(obstacles_.size()); }
  // Variable index of the multipliers (when num_obstacles() > 0) and of the first sharp obstacle block.
  int multiplier_index() const { return num_points() + 1; }
  int sharp_index() const { return num_points() + 1 + (num_obstacles() > 0 ? 1 : 0); }

  int expected_variable_size(int k) const override {
    if (k < num_points()) return point_size_;
    if (k == num_points()) return 3;
    return k >= sharp_index() ? 5 : num_obstacles();
  }

  bool structural_nonzero(int k, int row, int column) const override {
    if (k < num_points()) return column >= p_offset_ && column < p_offset_ + 3;
    if (k == num_points()) return row == column;
    if (k >= sharp_index()) return row < 3 && (column == 0 || column == 2 + row);
    return row < 3 || row - 3 == column;
  }

  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < num_points(); ++i) p += basis_[i] * Eigen::Map<const Vec3>(values[i] + p_offset_);
    const Eigen::Map<const Vec3> F(values[num_points()]);
    const double* lambda = num_obstacles() > 0 ? values[multiplier_index()] : nullptr;
    const int K = num_obstacles(), rows = 3 + K;
    Vec3 balance = F;
    Mat3 d_balance_dp = Mat3::Zero();  // d (F - sum lambda nu) / d p
    std::vector<ObstacleGap> gaps(K);
    std::vector<double> phi_a(K), phi_b(K);
    for (int k = 0; k < K; ++k) {
      gaps[k] = obstacle_gap(obstacles_[k], p, radius_);
      balance -= lambda[k] * gaps[k].normal;
      d_balance_dp -= lambda[k] * gaps[k].normal_derivative;
      complementarity(function_, gaps[k].gap / length_scale_, lambda[k] * density_scale_, residual[3 + k],
                      phi_a[k], phi_b[k]);
    }
    std::vector<contact::HatWeight> shares(sharp_.count);  // W_j(u_c) and its derivative
    for (int e = 0; e < sharp_.count; ++e) {
      const double* v = values[sharp_index() + e];
      for (const auto& [i, c] : sharp_.spread) {
        const contact::HatWeight w = contact::midpoint_share(*sharp_.midpoints, i, v[0]);
        shares[e].weight += c * w.weight;
        shares[e].derivative += c * w.derivative;
      }
      balance -= shares[e].weight * Eigen::Map<const Vec3>(v + 2);
    }
    for (int i = 0; i < 3; ++i) residual[i] = balance[i] * density_scale_;
    if (jacobians == nullptr) return;
    for (int i = 0; i < num_points(); ++i) {
      double* J = jacobians[i];
      if (J == nullptr) continue;
      std::fill(J, J + rows * point_size_, 0.0);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          J[r * point_size_ + p_offset_ + c] = d_balance_dp(r, c) * basis_[i] * density_scale_;
      for (int k = 0; k < K; ++k)
        for (int c = 0; c < 3; ++c)
          J[(3 + k) * point_size_ + p_offset_ + c] = phi_a[k] * gaps[k].normal[c] * basis_[i] / length_scale_;
    }
    if (double* J = jacobians[num_points()]) {
      std::fill(J, J + rows * 3, 0.0);
      for (int r = 0; r < 3; ++r) J[r * 3 + r] = density_scale_;
    }
    if (double* J = K > 0 ? jacobians[multiplier_index()] : nullptr) {
      std::fill(J, J + rows * K, 0.0);
      for (int k = 0; k < K; ++k) {
        for (int r = 0; r < 3; ++r) J[r * K + k] = -gaps[k].normal[r] * density_scale_;
        J[(3 + k) * K + k] = phi_b[k] * density_scale_;
      }
    }
    for (int e = 0; e < sharp_.count; ++e) {
      double* J = jacobians[sharp_index() + e];
      if (J == nullptr) continue;
      std::fill(J, J + rows * 5, 0.0);
      const Eigen::Map<const Vec3> G(values[sharp_index() + e] + 2);
      for (int r = 0; r < 3; ++r) {
        J[r * 5] = -shares[e].derivative * G[r] * density_scale_;
        J[r * 5 + 2 + r] = -shares[e].weight * density_scale_;
      }
    }
  }

 private:
  std::vector<double> basis_;  // N_i(u_j) of the active control points
  int point_size_, p_offset_;
  std::vector<Obstacle> obstacles_;  // the distributed (not sharp) obstacles
  double radius_;
  ComplementarityFunction function_;
  SharpShares sharp_;
  double length_scale_, density_scale_;
};

// Throws when the initial centerline point p (at u) penetrates an obstacle.
void check_initial_gap(const CollocationRod& rod, const Obstacle& obstacle, double radius, const Vec3& p,
                       double u) {
  const double g = obstacle_gap(obstacle, p, radius).gap;
  require(g >= -1e-9 * rod.length_scale(), "rod '", rod.model().name,
          "': the initial guess penetrates obstacle '", obstacle.name, "' at s = ", u * rod.model().length,
          " m (gap ", g, " m with contact radius ", radius,
          " m); start the rod clear of the obstacle (move the obstacle or change the default inputs)");
}

// The centerline point p(u) of the configuration x.
Vec3 centerline_at(const Problem& problem, const CollocationRod& rod, const RodVariables& vars, const VecX& x,
                   double u) {
  const BasisDerivatives b = basis_derivatives(rod.knots(), u, 0);
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < b.values.cols(); ++i)
    p += b.values(0, i) *
         x.segment<3>(problem.variable(vars.control_points[b.first + i]).offset + rod.point_layout().p);
  return p;
}

// The variable block [u_c, lambda, G] of a sharp obstacle, started at the section of the initial guess
// nearest to it (16 samples per collocation cell), and its rows (edge_contact.hpp). Throws when the
// initial guess penetrates it at a sample.
void add_sharp_obstacle(Problem& problem, const CollocationRod& rod, const RodVariables& vars,
                        const RodContactOptions& options, const Obstacle& obstacle,
                        const ContactBlockWrapper& wrap_block, RodContactVariables& out) {
  const VecX x0 = problem.initial_values();
  const int samples = 16 * (rod.num_control_points() - 1);
  double best_u = 0.0, best_gap = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= samples; ++i) {
    const double u = static_cast<double>(i) / samples;
    const Vec3 p = centerline_at(problem, rod, vars, x0, u);
    check_initial_gap(rod, obstacle, options.radius, p, u);
    const double g = obstacle_gap(obstacle, p, options.radius).gap;
    if (g < best_gap) best_gap = g, best_u = u;
  }
  VecX initial = VecX::Zero(5);
  initial[0] = best_u;
  const std::string where = rod.model().name + "/" + obstacle.name;
  const double L = x0[vars.length_offset], sigma = obstacle.adhesive_section();
  Vec3 reference_normal = Vec3::UnitZ();  // nu_0: at the stuck section of the initial guess
  if (adhesive(obstacle)) {
    require(
        rod.model().drawing_speed == 0.0, "rod '", rod.model().name, "': adhesive roller '", obstacle.name,
        "' on a drawn rod (drawing_speed ", rod.model().drawing_speed,
        " m/s): not supported (the no-slip law of a drawn rod prescribes its axial strain at the contact; "
        "docs/contact.md, \"Rollers\")");
    require(obstacle.stuck_section <= L && sigma >= 0.0 && sigma <= L, "rod '", rod.model().name,
            "': the section stuck to roller '", obstacle.name, "' (stuck section ", obstacle.stuck_section,
            " m, minus radius x angle: ", sigma, " m) is not on the rod [0, ", L, "] m");
    initial[0] = sigma / L;
    const Vec3 p0 = centerline_at(problem, rod, vars, x0, obstacle.stuck_section / L);
    reference_normal = obstacle_gap(obstacle, p0, options.radius).normal;
  }
  const VariableId id = problem.add_variable_block(where + ".sharp_contact", initial);
  const int group = problem.variable(vars.control_points[0]).group;
  if (group >= 0) problem.set_variable_group(id, group);
  std::vector<VariableId> v = vars.control_points;
  v.push_back(id);
  out.sharp_variables.push_back(id);
  out.sharp_offsets.push_back(problem.variable(id).offset);
  out.tangential_offsets.push_back(-1);
  if (!adhesive(obstacle)) {
    std::shared_ptr<ResidualBlock> block = contact::make_sharp_contact_block(
        where, std::move(v), rod.knots(), rod.control_point_size(), rod.point_layout().p, obstacle,
        options.radius, options.function, rod.length_scale(), rod.force_scale());
    out.sharp_blocks.push_back(problem.add_residual_block(wrap_block ? wrap_block(block) : block));
    return;
  }
  require(!wrap_block, "rod '", rod.model().name, "': adhesive roller '", obstacle.name,
          "' on a moving link: not supported (the no-slip kinematics are written for a fixed roller axis; "
          "docs/contact.md)");
  const VariableId mu = problem.add_variable_block(where + ".tangential_force", VecX::Zero(1));
  if (group >= 0) problem.set_variable_group(mu, group);
  out.tangential_offsets.back() = problem.variable(mu).offset;
  v.push_back(mu);
  v.push_back(vars.length);
  out.sharp_blocks.push_back(problem.add_residual_block(contact::make_adhesive_contact_block(
      where, std::move(v), rod.knots(), rod.control_point_size(), rod.point_layout().p, obstacle,
      reference_normal, options.radius, options.function, rod.length_scale(), rod.force_scale())));
}

}  // namespace

RodContactVariables add_rod_contact(Problem& problem, const CollocationRod& rod, const RodVariables& vars,
                                    const RodContactOptions& options, const ContactBlockWrapper& wrap_block) {
  const std::string& name = rod.model().name;
  const RodDiscretization& d = rod.discretization();
  require(
      d.contact_forces && d.formulation == RodFormulation::Mixed && d.mixed_points == MixedPoints::Midpoints,
      "rod '", name, "': contact needs the mixed form at the midpoints with contact_forces (formulation ",
      to_string(d.formulation), ")");
  require(!options.obstacles.empty(), "rod '", name, "': contact without obstacles");
  require(std::isfinite(options.radius) && options.radius > 0.0, "rod '", name,
          "': contact radius = ", options.radius, " (must be > 0)");
  for (const Obstacle& o : options.obstacles) o.validate();
  const int n = rod.num_control_points();
  require(static_cast<int>(vars.contact_forces.size()) == n - 1, "rod '", name,
          "': ", vars.contact_forces.size(), " contact force blocks for ", n - 1, " midpoints");
  const std::vector<double> tau = rod.knots().greville();
  const VecX x0 = problem.initial_values();
  const int cp = rod.control_point_size(), po = rod.point_layout().p;
  RodContactVariables out;
  out.options = options;
  std::vector<Obstacle> distributed;
  for (int k = 0; k < static_cast<int>(options.obstacles.size()); ++k) {
    const bool sharp = concentrated_contact(options.obstacles[k]);
    (sharp ? out.sharp : out.distributed).push_back(k);
    if (!sharp) distributed.push_back(options.obstacles[k]);
  }
  require(out.sharp.empty() || n >= 3, "rod '", name, "': a sharp obstacle needs at least 2 midpoints (",
          n - 1, ")");
  auto midpoints = std::make_shared<std::vector<double>>();
  for (int j = 0; j + 1 < n; ++j) midpoints->push_back(0.5 * (tau[j] + tau[j + 1]));
  for (int k : out.sharp)
    add_sharp_obstacle(problem, rod, vars, options, options.obstacles[k], wrap_block, out);
  const int K = static_cast<int>(distributed.size());
  const auto spreads = derivative_spreads(rod.knots(), tau, *midpoints);
  for (int j = 0; j + 1 < n; ++j) {
    const double u = (*midpoints)[j];
    const BasisDerivatives b = basis_derivatives(rod.knots(), u, 0);
    std::vector<VariableId> v;
    std::vector<double> basis;
    for (int i = 0; i < b.values.cols(); ++i) {
      v.push_back(vars.control_points[b.first + i]);
      basis.push_back(b.values(0, i));
    }
    const Vec3 p = centerline_at(problem, rod, vars, x0, u);
    for (const Obstacle& o : distributed) check_initial_gap(rod, o, options.radius, p, u);
    const std::string where = name + "@u=" + std::to_string(u);
    out.midpoints.push_back(u);
    v.push_back(vars.contact_forces[j]);
    if (K > 0) {
      out.multipliers.push_back(problem.add_variable_block(where + ".contact_lambda", VecX::Zero(K)));
      out.multiplier_offsets.push_back(problem.variable(out.multipliers.back()).offset);
      const int group = problem.variable(vars.control_points[0]).group;
      if (group >= 0) problem.set_variable_group(out.multipliers.back(), group);
      v.push_back(out.multipliers.back());
    }
    for (VariableId e : out.sharp_variables) v.push_back(e);
    const SharpShares shares{midpoints, spreads[j], static_cast<int>(out.sharp.size())};
    std::shared_ptr<ResidualBlock> block =
        std::make_shared<ContactBlock>(where, std::move(v), std::move(basis), cp, po, distributed, options,
                                       shares, rod.length_scale(), rod.force_scale());
    out.blocks.push_back(problem.add_residual_block(wrap_block ? wrap_block(block) : block));
  }
  return out;
}

}  // namespace pcr
