// The contact rows of one midpoint u_j (rod_contact.hpp): with p = sum_i N_i(u_j) P_i,
//   rows 0..2:   (F_j - sum_k lambda_k nu_k(p)) L0 / F0           (scaled as the mixed force balance)
//   row 3 + k:   phi(g_k(p) / L0, lambda_k L0 / F0)                (complementarity with obstacle k)
// Variables: the p + 1 active control points (only their P components enter), F_j (3), lambda_j (K).
// Jacobians by hand: d g / d p = nu, d nu / d p from obstacle_gap.
#include <algorithm>
#include <cmath>
#include <memory>

#include "pcr/core/error.hpp"
#include "pcr/rods/rod_contact.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr {

const char* to_string(ComplementarityFunction function) {
  return function == ComplementarityFunction::Min ? "min" : "fischer_burmeister";
}

namespace {

// phi(a, b) and its (generalised) partial derivatives.
void complementarity(ComplementarityFunction f, double a, double b, double& phi, double& phi_a,
                     double& phi_b) {
  if (f == ComplementarityFunction::Min) {
    phi = std::min(a, b);
    phi_a = a <= b ? 1.0 : 0.0;
    phi_b = 1.0 - phi_a;
    return;
  }
  const double rho = std::hypot(a, b);
  phi = a + b - rho;
  if (rho == 0.0) {
    phi_a = phi_b = 1.0 - 1.0 / std::sqrt(2.0);  // an element of the generalised Jacobian at (0, 0)
    return;
  }
  phi_a = 1.0 - a / rho;
  phi_b = 1.0 - b / rho;
}

class ContactBlock final : public ResidualBlock {
 public:
  ContactBlock(std::string name, std::vector<VariableId> variables, std::vector<double> basis, int point_size,
               int p_offset, const RodContactOptions& options, double length_scale, double force_scale)
      : ResidualBlock("rod.contact", std::move(name), 3 + static_cast<int>(options.obstacles.size()),
                      std::move(variables)),
        basis_(std::move(basis)),
        point_size_(point_size),
        p_offset_(p_offset),
        options_(options),
        length_scale_(length_scale),
        density_scale_(length_scale / force_scale) {}

  int num_points() const { return static_cast<int>(basis_.size()); }
  int num_obstacles() const { return static_cast<int>(options_.obstacles.size()); }

  int expected_variable_size(int k) const override {
    return k < num_points() ? point_size_ : k == num_points() ? 3 : num_obstacles();
  }

  bool structural_nonzero(int k, int row, int column) const override {
    if (k < num_points()) return column >= p_offset_ && column < p_offset_ + 3;
    if (k == num_points()) return row == column;
    return row < 3 || row - 3 == column;
  }

  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < num_points(); ++i) p += basis_[i] * Eigen::Map<const Vec3>(values[i] + p_offset_);
    const Eigen::Map<const Vec3> F(values[num_points()]);
    const double* lambda = values[num_points() + 1];
    const int K = num_obstacles(), rows = 3 + K;
    Vec3 balance = F;
    Mat3 d_balance_dp = Mat3::Zero();  // d (F - sum lambda nu) / d p
    std::vector<ObstacleGap> gaps(K);
    std::vector<double> phi_a(K), phi_b(K);
    for (int k = 0; k < K; ++k) {
      gaps[k] = obstacle_gap(options_.obstacles[k], p, options_.radius);
      balance -= lambda[k] * gaps[k].normal;
      d_balance_dp -= lambda[k] * gaps[k].normal_derivative;
      complementarity(options_.function, gaps[k].gap / length_scale_, lambda[k] * density_scale_,
                      residual[3 + k], phi_a[k], phi_b[k]);
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
    if (double* J = jacobians[num_points() + 1]) {
      std::fill(J, J + rows * K, 0.0);
      for (int k = 0; k < K; ++k) {
        for (int r = 0; r < 3; ++r) J[r * K + k] = -gaps[k].normal[r] * density_scale_;
        J[(3 + k) * K + k] = phi_b[k] * density_scale_;
      }
    }
  }

 private:
  std::vector<double> basis_;  // N_i(u_j) of the active control points
  int point_size_, p_offset_;
  RodContactOptions options_;
  double length_scale_, density_scale_;
};

// Throws when the initial centerline point p (at u) penetrates an obstacle.
void check_initial_gap(const CollocationRod& rod, const RodContactOptions& o, const Vec3& p, double u) {
  for (const Obstacle& obstacle : o.obstacles) {
    const double g = obstacle_gap(obstacle, p, o.radius).gap;
    require(g >= -1e-9 * rod.length_scale(), "rod '", rod.model().name,
            "': the initial guess penetrates obstacle '", obstacle.name, "' at s = ", u * rod.model().length,
            " m (gap ", g, " m with contact radius ", o.radius,
            " m); start the rod clear of the obstacle (move the obstacle or change the default inputs)");
  }
}

}  // namespace

RodContactVariables add_rod_contact(Problem& problem, const CollocationRod& rod, const RodVariables& vars,
                                    const RodContactOptions& options) {
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
  const int K = static_cast<int>(options.obstacles.size()), n = rod.num_control_points();
  require(static_cast<int>(vars.contact_forces.size()) == n - 1, "rod '", name,
          "': ", vars.contact_forces.size(), " contact force blocks for ", n - 1, " midpoints");
  const std::vector<double> tau = rod.knots().greville();
  const VecX x0 = problem.initial_values();
  const int cp = rod.control_point_size(), po = rod.point_layout().p;
  RodContactVariables out;
  out.options = options;
  for (int j = 0; j + 1 < n; ++j) {
    const double u = 0.5 * (tau[j] + tau[j + 1]);
    const BasisDerivatives b = basis_derivatives(rod.knots(), u, 0);
    std::vector<VariableId> v;
    std::vector<double> basis;
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < b.values.cols(); ++i) {
      v.push_back(vars.control_points[b.first + i]);
      basis.push_back(b.values(0, i));
      p += b.values(0, i) * x0.segment<3>(problem.variable(v.back()).offset + po);
    }
    check_initial_gap(rod, options, p, u);
    const std::string where = name + "@u=" + std::to_string(u);
    out.midpoints.push_back(u);
    out.multipliers.push_back(problem.add_variable_block(where + ".contact_lambda", VecX::Zero(K)));
    out.multiplier_offsets.push_back(problem.variable(out.multipliers.back()).offset);
    const int group = problem.variable(vars.control_points[0]).group;
    if (group >= 0) problem.set_variable_group(out.multipliers.back(), group);
    v.push_back(vars.contact_forces[j]);
    v.push_back(out.multipliers.back());
    out.blocks.push_back(problem.add_residual_block(std::make_shared<ContactBlock>(
        where, std::move(v), std::move(basis), cp, po, options, rod.length_scale(), rod.force_scale())));
  }
  return out;
}

}  // namespace pcr
