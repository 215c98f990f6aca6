#include "node_chain.hpp"

#include <cmath>

#include "pcr/math/dense_decompositions.hpp"

namespace pcr::stability {

namespace {

/// A pivot (at most 6 x 6) with its inverse and the count of its negative eigenvalues, from the
/// eigenvalues of its diagonal scaling D P D, D = diag(|P_ii|)^-1/2 (a congruence: same inertia;
/// without it the axial stiffness, 1e6 times the bending one, would swamp the bending eigenvalues).
struct Pivot {
  explicit Pivot(const MatX& P) {
    const int k = static_cast<int>(P.rows());
    if (k == 0) return;
    VecX d(k);
    for (int i = 0; i < k; ++i) d[i] = std::abs(P(i, i)) > 0.0 ? 1.0 / std::sqrt(std::abs(P(i, i))) : 1.0;
    const SymmetricEigen eig = symmetric_eigen(d.asDiagonal() * P * d.asDiagonal());
    const VecX& lambda = eig.values;
    for (int i = 0; i < k; ++i) negative += lambda[i] < 0.0;
    smallest_magnitude = lambda.cwiseAbs().minCoeff();
    // P^-1 = D V Lambda^-1 V^T D
    inverse = d.asDiagonal() * eig.vectors * lambda.cwiseInverse().asDiagonal() * eig.vectors.transpose() *
              d.asDiagonal();
  }
  int negative = 0;
  double smallest_magnitude = INFINITY;
  MatX inverse;
};

/// A scaled pivot eigenvalue below this means a conjugate point of the partial problem sits (nearly) on
/// that node: its inverse is unreliable, and the nodes are moved (the count does not depend on them).
constexpr double kNearSingularPivot = 1e-9;

struct Chain {
  const std::vector<Mat12>& K;
  const EndSpace& base;
  const EndSpace& tip;
  int N() const { return static_cast<int>(K.size()); }
  MatX Z(int j) const {
    if (j == 0) return base.Z;
    if (j == N()) return tip.Z;
    return MatX::Identity(6, 6);
  }
  MatX D(int j) const {
    if (j == 0) return base.Z.transpose() * K[0].topLeftCorner<6, 6>() * base.Z + base.B;
    if (j == N()) return tip.Z.transpose() * K[N() - 1].bottomRightCorner<6, 6>() * tip.Z + tip.B;
    return K[j - 1].bottomRightCorner<6, 6>() + K[j].topLeftCorner<6, 6>();
  }
  /// Coupling of node j (rows) with node j + 1 (columns).
  MatX E(int j) const { return Z(j).transpose() * K[j].topRightCorner<6, 6>() * Z(j + 1); }
};

}  // namespace

int probe_node(int segments, const EndSpace& base, const EndSpace& tip) {
  if (tip.size() > 0) return segments;
  if (base.size() > 0) return 0;
  return segments / 2;
}

ChainInertia chain_inertia(const std::vector<Mat12>& K, const EndSpace& base, const EndSpace& tip, int probe,
                           double tolerance) {
  const Chain c{K, base, tip};
  const int N = c.N();
  ChainInertia out;
  auto eliminate = [&](const MatX& P, const MatX& coupling, MatX& next) {  // next -= C^T P^-1 C
    if (P.rows() == 0) return;
    const Pivot pivot(P);
    out.negative += pivot.negative;
    out.near_singular_pivot = out.near_singular_pivot || pivot.smallest_magnitude < kNearSingularPivot;
    next -= coupling.transpose() * pivot.inverse * coupling;
  };
  MatX probe_pivot = c.D(probe);
  if (probe > 0) {
    MatX S = c.D(0);
    for (int j = 0; j < probe; ++j) {
      MatX next = j + 1 == probe ? MatX(MatX::Zero(c.Z(j + 1).cols(), c.Z(j + 1).cols())) : c.D(j + 1);
      eliminate(S, c.E(j), next);
      if (j + 1 == probe) probe_pivot += next;
      S = next;
    }
  }
  if (probe < N) {
    MatX S = c.D(N);
    for (int j = N; j > probe; --j) {
      MatX next = j - 1 == probe ? MatX(MatX::Zero(c.Z(j - 1).cols(), c.Z(j - 1).cols())) : c.D(j - 1);
      eliminate(S, c.E(j - 1).transpose(), next);
      if (j - 1 == probe) probe_pivot += next;
      S = next;
    }
  }
  if (probe_pivot.rows() > 0) {
    const VecX lambda = symmetric_eigen(0.5 * (probe_pivot + probe_pivot.transpose())).values;
    out.probe_min = lambda[0];
    for (int i = 0; i < lambda.size(); ++i) {
      if (lambda[i] < -tolerance)
        ++out.negative;
      else if (lambda[i] <= tolerance)
        ++out.neutral;
    }
  }
  return out;
}

}  // namespace pcr::stability
