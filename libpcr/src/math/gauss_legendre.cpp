#include "pcr/math/gauss_legendre.hpp"

#include <cmath>

#include "pcr/core/error.hpp"

namespace pcr {

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  require(n >= 1, "gauss_legendre: need at least one node, got ", n);
  constexpr double kPi = 3.14159265358979323846;
  nodes.assign(n, 0.0);
  weights.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double t = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = t;  // P_0, P_1; recurrence (k+1) P_{k+1} = (2k+1) t P_k - k P_{k-1}
      for (int k = 1; k < n; ++k) {
        const double p2 = ((2.0 * k + 1.0) * t * p1 - k * p0) / (k + 1.0);
        p0 = p1;
        p1 = p2;
      }
      dp = n * (t * p1 - p0) / (t * t - 1.0);
      const double dt = p1 / dp;
      t -= dt;
      if (std::abs(dt) < 1e-15) break;
    }
    nodes[i] = t;
    weights[i] = 2.0 / ((1.0 - t * t) * dp * dp);
  }
}

}  // namespace pcr
