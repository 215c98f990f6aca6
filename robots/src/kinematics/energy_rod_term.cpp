// The rod's energy in the Ritz form (energy_terms.hpp RodEnergyTerm).
#include <algorithm>
#include <cmath>
#include <utility>

#include "energy_kinematics.hpp"
#include "energy_terms.hpp"
#include "pcr/math/gauss_legendre.hpp"
#include "pcr/math/hyper_dual.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr::kinematics {

namespace {

/// The local quantities at a quadrature node: z = [p_s (3), q (4), q_s (4)].
constexpr int kLocal = 11;
using D = Dual<kLocal>;

/// Shear-extension part 1/2 (v - v*)^T K_SE (v - v*) of the strain energy density [J/m].
template <class T>
T shear_energy_density(const V3<T>& ps, const V4<T>& q, const Vec3& eps0, const Vec3& k_se) {
  const V3<T> shear = collocation::rotation(q).transpose() * ps - (Vec3::UnitZ() + eps0).cast<T>();
  T e(0.0);
  for (int i = 0; i < 3; ++i) e += 0.5 * k_se[i] * shear[i] * shear[i];
  return e;
}

/// Bending-torsion part 1/2 (u - u*)^T K_BT (u - u*) [J/m].
template <class T>
T bending_energy_density(const V4<T>& q, const V4<T>& qs, const Vec3& kappa0, const Vec3& k_bt) {
  const V3<T> bend = collocation::body_curvature(q, qs) - kappa0.cast<T>();
  T e(0.0);
  for (int i = 0; i < 3; ++i) e += 0.5 * k_bt[i] * bend[i] * bend[i];
  return e;
}

/// Strain energy density 1/2 (v - v*)^T K_SE (v - v*) + 1/2 (u - u*)^T K_BT (u - u*) [J/m].
template <class T>
T strain_energy_density(const V3<T>& ps, const V4<T>& q, const V4<T>& qs, const Vec3& eps0,
                        const Vec3& kappa0, const Vec3& k_se, const Vec3& k_bt) {
  return shear_energy_density(ps, q, eps0, k_se) + bending_energy_density(q, qs, kappa0, k_bt);
}

/// The density's exact Hessian in z = [p_s, q, q_s] (second-order forward mode), each part over only the
/// quantities it depends on: the shear part over [p_s, q] (7), the bending part over [q, q_s] (8); a
/// HyperDual's operations cost ~N^2, so this is half the work of both over all 11.
Eigen::Matrix<double, kLocal, kLocal> strain_energy_hessian(const Eigen::Matrix<double, kLocal, 1>& z,
                                                            const Vec3& eps0, const Vec3& kappa0,
                                                            const Vec3& k_se, const Vec3& k_bt) {
  using H7 = HyperDual<7>;
  using H8 = HyperDual<8>;
  V3<H7> ps;
  V4<H7> q7;
  V4<H8> q8, qs;
  for (int i = 0; i < 3; ++i) ps[i] = H7::variable(z[i], i);
  for (int i = 0; i < 4; ++i) {
    q7[i] = H7::variable(z[3 + i], 3 + i);
    q8[i] = H8::variable(z[3 + i], i);
    qs[i] = H8::variable(z[7 + i], 4 + i);
  }
  Eigen::Matrix<double, kLocal, kLocal> H = Eigen::Matrix<double, kLocal, kLocal>::Zero();
  H.topLeftCorner<7, 7>() = shear_energy_density(ps, q7, eps0, k_se).H;
  H.bottomRightCorner<8, 8>() += bending_energy_density(q8, qs, kappa0, k_bt).H;
  return H;
}

}  // namespace

RodEnergyTerm::RodEnergyTerm(const CollocationRod& rod, double length, std::vector<VariableId> points,
                             double energy_scale)
    : ObjectiveTerm("energy.rod." + rod.model().name, std::move(points)),
      rod_(rod),
      length_(length),
      scale_(energy_scale) {
  // Gauss-Legendre with degree + 1 nodes per knot span: the strains are polynomials of degree <= p - 1
  // (positions) and rational (rotations), integrated well beyond the collocation's own accuracy.
  const int degree = rod.knots().degree();
  std::vector<double> xi, w;
  gauss_legendre(degree + 1, xi, w);
  const std::vector<double> breaks = rod.knots().breakpoints();
  for (std::size_t e = 0; e + 1 < breaks.size(); ++e) {
    const double a = breaks[e], b = breaks[e + 1];
    for (std::size_t k = 0; k < xi.size(); ++k)
      nodes_.push_back(node_at(0.5 * (a + b) + 0.5 * (b - a) * xi[k], 0.5 * (b - a) * w[k] * length));
  }
}

RodEnergyTerm::Node RodEnergyTerm::node_at(double u, double weight) const {
  Node n;
  n.u = u;
  n.weight = weight;
  const BasisDerivatives d = basis_derivatives(rod_.knots(), u, 1);
  n.first = d.first;
  n.basis = d.values.topRows(2);
  n.basis.row(1) /= length_;  // d/ds = (1 / L) d/du
  rod_.model().intrinsic.at(u * length_, n.eps0, n.kappa0);
  return n;
}

double RodEnergyTerm::evaluate(const double* const* values, double* const* gradients) const {
  const RodModel& m = rod_.model();
  const Vec3 f = m.distributed_force();
  const int count = static_cast<int>(variables().size());
  if (gradients)
    for (int i = 0; i < count; ++i)
      if (gradients[i]) std::fill(gradients[i], gradients[i] + 7, 0.0);
  double energy = 0.0;
  for (const Node& n : nodes_) {
    Vec3 p = Vec3::Zero(), ps = Vec3::Zero();
    Quat q = Quat::Zero(), qs = Quat::Zero();
    for (int j = 0; j < n.basis.cols(); ++j) {
      const double* c = values[n.first + j];
      p += n.basis(0, j) * Eigen::Map<const Vec3>(c);
      ps += n.basis(1, j) * Eigen::Map<const Vec3>(c);
      q += n.basis(0, j) * Eigen::Map<const Quat>(c + 3);
      qs += n.basis(1, j) * Eigen::Map<const Quat>(c + 3);
    }
    V3<D> dps;
    V4<D> dq, dqs;
    for (int i = 0; i < 3; ++i) dps[i] = D::variable(ps[i], i);
    for (int i = 0; i < 4; ++i) dq[i] = D::variable(q[i], 3 + i), dqs[i] = D::variable(qs[i], 7 + i);
    const D e = strain_energy_density(dps, dq, dqs, n.eps0, n.kappa0, m.shear_extension_stiffness,
                                      m.bending_torsion_stiffness);
    energy += n.weight * (e.a - f.dot(p));
    if (!gradients) continue;
    // Chain rule: p_s = sum_j N_j' P_j, q = sum_j N_j Q_j, q_s = sum_j N_j' Q_j, p = sum_j N_j P_j.
    for (int j = 0; j < n.basis.cols(); ++j) {
      double* g = gradients[n.first + j];
      if (!g) continue;
      const double w = n.weight / scale_;
      Eigen::Map<Vec3>(g) += w * (n.basis(1, j) * e.v.head<3>() - n.basis(0, j) * f);
      Eigen::Map<Quat>(g + 3) += w * (n.basis(0, j) * e.v.segment<4>(3) + n.basis(1, j) * e.v.tail<4>());
    }
  }
  // Dead forces on free ends: -F . p(0), -F . p(L) (open knots: the end control points).
  const int last = count - 1;
  for (const auto& [end, point] : {std::pair<const RodEnd*, int>{&m.base, 0}, {&m.tip, last}}) {
    if (end->kind != RodEndKind::Free) continue;
    energy -= end->force.dot(Eigen::Map<const Vec3>(values[point]));
    if (gradients && gradients[point]) Eigen::Map<Vec3>(gradients[point]) -= end->force / scale_;
  }
  return energy / scale_;
}

void RodEnergyTerm::evaluate_hessian(const double* const* values, double* hessian) const {
  const RodModel& m = rod_.model();
  const int n = 7 * static_cast<int>(variables().size());
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> H(hessian, n, n);
  H.setZero();
  for (const Node& node : nodes_) {
    Eigen::Matrix<double, kLocal, 1> z = Eigen::Matrix<double, kLocal, 1>::Zero();
    for (int j = 0; j < node.basis.cols(); ++j) {
      const double* c = values[node.first + j];
      z.head<3>() += node.basis(1, j) * Eigen::Map<const Vec3>(c);
      z.segment<4>(3) += node.basis(0, j) * Eigen::Map<const Quat>(c + 3);
      z.tail<4>() += node.basis(1, j) * Eigen::Map<const Quat>(c + 3);
    }
    const Eigen::Matrix<double, kLocal, kLocal> Hz = strain_energy_hessian(
        z, node.eps0, node.kappa0, m.shear_extension_stiffness, m.bending_torsion_stiffness);
    // z = sum_j G_j c_j with G_j = N_j E0 + N_j' E1 (11 x 7): E0 puts Q into q, E1 puts P into p_s and Q into
    // q_s. The (j, k) block of G^T Hz G is N_j N_k H00 + N_j N_k' H01 + N_j' N_k H10 + N_j' N_k' H11 with
    // Hab = Ea^T Hz Eb (7 x 7, once per node); the (k, j) block its transpose.
    using M7 = Eigen::Matrix<double, 7, 7>;
    static const Eigen::Matrix<double, kLocal, 7> E0 = [] {
      Eigen::Matrix<double, kLocal, 7> e = Eigen::Matrix<double, kLocal, 7>::Zero();
      e.block<4, 4>(3, 3).setIdentity();
      return e;
    }();
    static const Eigen::Matrix<double, kLocal, 7> E1 = [] {
      Eigen::Matrix<double, kLocal, 7> e = Eigen::Matrix<double, kLocal, 7>::Zero();
      e.block<3, 3>(0, 0).setIdentity();
      e.block<4, 4>(7, 3).setIdentity();
      return e;
    }();
    const double w = node.weight / scale_;
    const M7 H00 = w * E0.transpose() * Hz * E0, H01 = w * E0.transpose() * Hz * E1,
             H10 = w * E1.transpose() * Hz * E0, H11 = w * E1.transpose() * Hz * E1;
    const int count = static_cast<int>(node.basis.cols());
    for (int j = 0; j < count; ++j) {
      const double Nj = node.basis(0, j), dNj = node.basis(1, j);
      for (int k = 0; k <= j; ++k) {
        const double Nk = node.basis(0, k), dNk = node.basis(1, k);
        const M7 block = (Nj * Nk) * H00 + (Nj * dNk) * H01 + (dNj * Nk) * H10 + (dNj * dNk) * H11;
        H.block<7, 7>(7 * (node.first + j), 7 * (node.first + k)) += block;
        if (k < j) H.block<7, 7>(7 * (node.first + k), 7 * (node.first + j)) += block.transpose();
      }
    }
  }
}

void RodEnergyTerm::section(const double* const* values, double u, Vec3& p, Vec3& n, Vec3& m) const {
  const Node node = node_at(u, 0.0);
  const RodModel& rod = rod_.model();
  p.setZero();
  Vec3 ps = Vec3::Zero();
  Quat q = Quat::Zero(), qs = Quat::Zero();
  for (int j = 0; j < node.basis.cols(); ++j) {
    const double* c = values[node.first + j];
    p += node.basis(0, j) * Eigen::Map<const Vec3>(c);
    ps += node.basis(1, j) * Eigen::Map<const Vec3>(c);
    q += node.basis(0, j) * Eigen::Map<const Quat>(c + 3);
    qs += node.basis(1, j) * Eigen::Map<const Quat>(c + 3);
  }
  const Mat3 R = collocation::rotation<double>(q);
  // n = R K_SE (v - v*), m = R K_BT (u - u*) (the constitutive law, docs/design.md §1).
  n = R * rod.shear_extension_stiffness.cwiseProduct(R.transpose() * ps - Vec3::UnitZ() - node.eps0);
  m = R *
      rod.bending_torsion_stiffness.cwiseProduct(collocation::body_curvature<double>(q, qs) - node.kappa0);
}

}  // namespace pcr::kinematics
