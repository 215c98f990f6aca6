#pragma once
// Independent reference for the spline tests: the Cox-de Boor recursion (The NURBS Book eq. 2.5) and
// the derivative formula eq. 2.7, evaluated for every basis function (not only the active ones) with
// the convention 0/0 = 0, half-open spans [xi_i, xi_{i+1}) and u = 1 in the last non-empty span.
#include <cmath>
#include <string>
#include <vector>

#include "pcr/core/error.hpp"

namespace pcr_test {

/// d-th derivative of N_{i,k}(u) on the knots xi.
inline double cox_de_boor(const std::vector<double>& xi, int i, int k, double u, int d = 0) {
  if (k == 0) {
    if (d > 0) return 0.0;
    if (u == xi.back()) return xi[i] < xi[i + 1] && xi[i + 1] == xi.back() ? 1.0 : 0.0;
    return xi[i] <= u && u < xi[i + 1] ? 1.0 : 0.0;
  }
  const double left_width = xi[i + k] - xi[i], right_width = xi[i + k + 1] - xi[i + 1];
  double value = 0.0;
  if (d == 0) {
    if (left_width > 0.0) value += (u - xi[i]) / left_width * cox_de_boor(xi, i, k - 1, u);
    if (right_width > 0.0) value += (xi[i + k + 1] - u) / right_width * cox_de_boor(xi, i + 1, k - 1, u);
  } else {  // eq. 2.7 applied d times: N^(d)_{i,k} = k (N^(d-1)_{i,k-1}/left - N^(d-1)_{i+1,k-1}/right)
    if (left_width > 0.0) value += k * cox_de_boor(xi, i, k - 1, u, d - 1) / left_width;
    if (right_width > 0.0) value -= k * cox_de_boor(xi, i + 1, k - 1, u, d - 1) / right_width;
  }
  return value;
}

/// Runs f and returns true iff it throws pcr::InputError whose message contains every needle.
template <typename F>
bool throws_input_error_naming(F&& f, const std::vector<std::string>& needles) {
  try {
    f();
  } catch (const pcr::InputError& e) {
    const std::string message = e.what();
    for (const std::string& needle : needles)
      if (message.find(needle) == std::string::npos) return false;
    return true;
  } catch (...) {
    return false;
  }
  return false;
}

}  // namespace pcr_test
