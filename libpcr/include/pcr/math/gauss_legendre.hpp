#pragma once
// Gauss-Legendre quadrature: n nodes integrate polynomials of degree <= 2 n - 1 exactly.
#include <vector>

namespace pcr {

/// Nodes and weights on [-1, 1] (Newton on P_n from the Chebyshev guesses), n >= 1.
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

}  // namespace pcr
