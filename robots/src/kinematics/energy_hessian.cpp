// Hessians by central differences of exact first derivatives (energy_hessian.hpp).
#include "energy_hessian.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace pcr::kinematics {

namespace {

/// The stacked variables as one vector, and pointers into it per block.
struct Stacked {
  Stacked(const std::vector<int>& sizes, const double* const* values) {
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      offsets.push_back(static_cast<int>(x.size()));
      x.insert(x.end(), values[k], values[k] + sizes[k]);
    }
  }
  std::vector<const double*> pointers() const {
    std::vector<const double*> p;
    for (int o : offsets) p.push_back(x.data() + o);
    return p;
  }
  std::vector<double> x;
  std::vector<int> offsets;
};

/// H(:, k) = (g(x + h e_k) - g(x - h e_k)) / (2 h), symmetrised; gradient(values, g) fills g (size n).
void central_differences(Stacked& s, const std::function<void(const double* const*, double*)>& gradient,
                         double* hessian) {
  const int n = static_cast<int>(s.x.size());
  std::vector<double> plus(n), minus(n);
  for (int k = 0; k < n; ++k) {
    const double x0 = s.x[k], h = 1e-6 * std::max(1.0, std::abs(x0));
    s.x[k] = x0 + h;
    gradient(s.pointers().data(), plus.data());
    s.x[k] = x0 - h;
    gradient(s.pointers().data(), minus.data());
    s.x[k] = x0;
    for (int i = 0; i < n; ++i) hessian[i * n + k] = (plus[i] - minus[i]) / (2.0 * h);
  }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < i; ++k)
      hessian[i * n + k] = hessian[k * n + i] = 0.5 * (hessian[i * n + k] + hessian[k * n + i]);
}

}  // namespace

void gradient_difference_hessian(const ObjectiveTerm& term, const std::vector<int>& sizes,
                                 const double* const* values, double* hessian) {
  Stacked s(sizes, values);
  central_differences(
      s,
      [&](const double* const* v, double* g) {
        std::vector<double*> parts;
        for (int o : s.offsets) parts.push_back(g + o);
        term.evaluate(v, parts.data());
      },
      hessian);
}

void jacobian_difference_hessian(const ResidualBlock& block, const std::vector<int>& sizes,
                                 const double* const* values, const double* weights, double* hessian) {
  Stacked s(sizes, values);
  const int rows = block.num_rows();
  std::vector<std::vector<double>> jacobians(sizes.size());
  std::vector<double*> parts;
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    jacobians[k].resize(static_cast<std::size_t>(rows * sizes[k]));
    parts.push_back(jacobians[k].data());
  }
  std::vector<double> residual(rows);
  central_differences(
      s,
      [&](const double* const* v, double* g) {  // g = J^T weights
        block.evaluate(v, residual.data(), parts.data());
        for (std::size_t k = 0; k < sizes.size(); ++k)
          for (int c = 0; c < sizes[k]; ++c) {
            double sum = 0.0;
            for (int r = 0; r < rows; ++r) sum += weights[r] * jacobians[k][r * sizes[k] + c];
            g[s.offsets[k] + c] = sum;
          }
      },
      hessian);
}

}  // namespace pcr::kinematics
