#include "ik_objectives.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "pcr/core/error.hpp"
#include "pcr/math/gauss_legendre.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/rods/collocation/equations.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr::kinematics {
namespace {

constexpr int kQ = 3, kN = 7, kM = 10;  // offsets in a mixed control point [P, Q, N, M]

/// phi(n_b, m_b) with its partials g_n = dphi/dn_b, g_m = dphi/dm_b (body frame).
using BodyFunctional = std::function<double(const Vec3& n_b, const Vec3& m_b, Vec3& g_n, Vec3& g_m)>;

/// phi(R^T n, R^T m) at the orientation q, with what its gradient needs: R(q), dR/dq and the partials.
struct BodyValue {
  double value = 0.0;
  Mat3 R;
  QuatRotationJacobian dR;
  Vec3 g_n, g_m;

  BodyValue(const BodyFunctional& phi, const Quat& q, const Vec3& n, const Vec3& m) {
    rotation_matrix_derivatives(q, R, dR);
    value = phi(R.transpose() * n, R.transpose() * m, g_n, g_m);
  }
  /// dphi/dq_k through R(q) alone: sum_ab (n g_n^T + m g_m^T)_ab (dR/dq_k)_ab.
  Quat quaternion_gradient(const Vec3& n, const Vec3& m) const {
    const Mat3 D = n * g_n.transpose() + m * g_m.transpose();
    Quat dq;
    for (int k = 0; k < 4; ++k) dq[k] = D.cwiseProduct(dR[k]).sum();
    return dq;
  }
};

/// The control points of a rod whose basis functions b_j do not vanish at u: spline values there, and
/// gradients with respect to a value spread back onto the points.
class ActivePoints {
 public:
  ActivePoints(const CollocationRod& rod, const RodVariables& v, double u)
      : b_(basis_derivatives(rod.knots(), u, 0)),
        size_(rod.control_point_size()),
        first_(v.control_point_offset + b_.first * size_),
        count_(rod.discretization().degree + 1) {}

  /// sum_j b_j C_j with C_j the D components of control point j from `component` on.
  template <int D>
  Eigen::Matrix<double, D, 1> value(const VecX& x, int component) const {
    Eigen::Matrix<double, D, 1> sum = Eigen::Matrix<double, D, 1>::Zero();
    for (int j = 0; j < count_; ++j) sum += b_.values(0, j) * x.segment<D>(first_ + j * size_ + component);
    return sum;
  }
  /// gradient += weight * dphi/dC_j = weight b_j g for every j (g = dphi/d value<D>(x, component)).
  template <int D>
  void add_gradient(VecX& gradient, int component, double weight,
                    const Eigen::Matrix<double, D, 1>& g) const {
    for (int j = 0; j < count_; ++j)
      gradient.segment<D>(first_ + j * size_ + component) += (weight * b_.values(0, j)) * g;
  }

 private:
  BasisDerivatives b_;
  int size_, first_, count_;
};

/// phi at parameter u of a mixed rod; when gradient is given, adds weight * dphi/dx to it.
double mixed_point_functional(const CollocationRod& rod, const RodVariables& v, const VecX& x, double u,
                              const BodyFunctional& phi, double weight, VecX* gradient) {
  // n = sum b_i N_i, m = sum b_i M_i, q = sum b_i Q_i; dphi/dn = R g_n, dphi/dm = R g_m,
  // dphi/dq_k = sum_ab (n g_n^T + m g_m^T)_ab (dR/dq_k)_ab.
  const ActivePoints active(rod, v, u);
  const Vec3 n = active.value<3>(x, kN), m = active.value<3>(x, kM);
  const BodyValue phi_at(phi, active.value<4>(x, kQ), n, m);
  if (gradient) {
    active.add_gradient<4>(*gradient, kQ, weight, phi_at.quaternion_gradient(n, m));
    active.add_gradient<3>(*gradient, kN, weight, phi_at.R * phi_at.g_n);
    active.add_gradient<3>(*gradient, kM, weight, phi_at.R * phi_at.g_m);
  }
  return phi_at.value;
}

/// phi at parameter u of a condensed rod; when gradient is given, adds weight * dphi/dx to it.
double condensed_point_functional(const CollocationRod& rod, const RodVariables& v, const VecX& x, double u,
                                  const BodyFunctional& phi, double weight, VecX* gradient) {
  // n = N - f s, m = H - a x n - l s - L (I - c u) x f with s = u L, a = p - c, p = sum b_i P_i,
  // I = sum_j J_j P_j (J_j = integral_0^u N_j; f = l = 0 without distributed loads), q = sum b_i Q_i:
  // with dm = R g_m: dphi/dH = dm, dphi/dN = R g_n + a x dm, dphi/dP_i = b_i (dm x n) + L J_i (dm x f),
  // dphi/dL = R g_n . (-f u) + dm . (u a x f - l u - (I - c u) x f), dphi/dq as above.
  const int cp = rod.control_point_size();
  const bool loads = rod.condensed_with_loads();
  const VecX J = loads ? basis_integrals(rod.knots(), u) : VecX();
  const Vec3 f = loads ? rod.model().distributed_force() : Vec3::Zero();
  const Vec3 l = loads ? Vec3(rod.model().loads.moment_per_length) : Vec3::Zero();
  const Vec3 c = rod.moment_point();
  const double L = rod.length(x, v);
  const ActivePoints active(rod, v, u);
  const Vec3 p = active.value<3>(x, 0);
  Vec3 I = Vec3::Zero();
  for (int j = 0; j < J.size(); ++j) I += J[j] * x.segment<3>(v.control_point_offset + j * cp);
  const Vec3 arm = p - c, n = x.segment<3>(v.wrench_offset) - f * (u * L);
  collocation::PointConstants distributed;
  distributed.f = f;
  distributed.l = l;
  const Vec3 m =
      collocation::condensed_moment<double>(p, n, x.segment<3>(v.wrench_offset + 3), L, I, distributed, c, u);
  const BodyValue phi_at(phi, active.value<4>(x, kQ), n, m);
  if (gradient) {
    const Vec3 dm = phi_at.R * phi_at.g_m, dn = phi_at.R * phi_at.g_n + arm.cross(dm), dp = dm.cross(n),
               dI = L * dm.cross(f);
    active.add_gradient<3>(*gradient, 0, weight, dp);
    active.add_gradient<4>(*gradient, kQ, weight, phi_at.quaternion_gradient(n, m));
    for (int j = 0; j < J.size(); ++j)
      if (J[j] != 0.0) gradient->segment<3>(v.control_point_offset + j * cp) += (weight * J[j]) * dI;
    gradient->segment<3>(v.wrench_offset) += weight * dn;
    gradient->segment<3>(v.wrench_offset + 3) += weight * dm;
    if (loads) {
      const Vec3 dm_dL = u * arm.cross(f) - l * u - (I - c * u).cross(f);
      (*gradient)[v.length_offset] += weight * ((phi_at.R * phi_at.g_n).dot(-f * u) + dm.dot(dm_dL));
    }
  }
  return phi_at.value;
}

/// phi at parameter u of a primal rod; when gradient is given, adds weight * dphi/dx to it. work: a copy
/// of x (perturbed and restored).
double primal_point_functional(const CollocationRod& rod, const RodVariables& v, const VecX& x, VecX& work,
                               double u, const BodyFunctional& phi, double weight, VecX* gradient) {
  // Primal: n, m from state_at; central differences over the p + 1 control points whose basis
  // functions do not vanish at u, and the length. Step 1e-6 (1 + |x_e|): truncation ~1e-12,
  // round-off ~1e-10 relative.
  auto evaluate = [&](const VecX& xx) {
    const RodState st = rod.state_at(xx, v, u * rod.length(xx, v));
    Vec3 gn, gm;
    return phi(st.rotation.transpose() * st.force, st.rotation.transpose() * st.moment, gn, gm);
  };
  const double value = evaluate(x);
  if (gradient) {
    const BasisDerivatives b = basis_derivatives(rod.knots(), u, 0);
    const int cp = rod.control_point_size();
    std::vector<int> entries;
    for (int k = 0; k < (rod.discretization().degree + 1) * cp; ++k)
      entries.push_back(v.control_point_offset + b.first * cp + k);
    entries.push_back(v.length_offset);
    for (int e : entries) {
      const double h = 1e-6 * (1.0 + std::abs(x[e]));
      work[e] = x[e] + h;
      const double fp = evaluate(work);
      work[e] = x[e] - h;
      const double fm = evaluate(work);
      work[e] = x[e];
      (*gradient)[e] += weight * (fp - fm) / (2.0 * h);
    }
  }
  return value;
}

/// phi at parameter u of a rod; when gradient is given, adds weight * dphi/dx to it. work: a copy of x
/// (primal rods perturb it and restore it).
double point_functional(const CollocationRod& rod, const RodVariables& v, const VecX& x, VecX& work, double u,
                        const BodyFunctional& phi, double weight, VecX* gradient) {
  switch (rod.discretization().formulation) {
    case RodFormulation::Mixed: return mixed_point_functional(rod, v, x, u, phi, weight, gradient);
    case RodFormulation::Condensed: return condensed_point_functional(rod, v, x, u, phi, weight, gradient);
    default: return primal_point_functional(rod, v, x, work, u, phi, weight, gradient);
  }
}

/// Rods fed by an input (their length is actuated).
std::vector<int> fed_rods(const RobotAssembly& a) {
  std::vector<int> rods;
  for (const ActuationInput& in : a.model().inputs())
    if (in.kind == ActuationInput::Kind::RodLength) rods.push_back(in.index);
  return rods;
}

double smooth_abs(double v, double delta) {
  return std::sqrt(v * v + delta * delta);
}

}  // namespace

double actuation_effort(const RobotAssembly& a, const VecX& x, VecX* gradient) {
  const std::vector<int> rods = fed_rods(a);
  require(!rods.empty(), "IK objective 'effort': robot '", a.model().name(),
          "' has no fed rod (joint efforts are not part of the effort objective)");
  if (gradient) gradient->setZero(x.size());
  VecX work = x;
  const double F0 = a.force_scale();
  // N = n(0) . d3(0) = n_b3 at u = 0.
  const BodyFunctional axial = [](const Vec3& n_b, const Vec3&, Vec3& g_n, Vec3& g_m) {
    g_n = Vec3::UnitZ();
    g_m.setZero();
    return n_b[2];
  };
  double f = 0.0;
  for (int r : rods) {
    const double N = point_functional(a.rod(r), a.rod_variables(r), x, work, 0.0, axial, 0.0, nullptr);
    f += 0.5 * (N / F0) * (N / F0);
    if (gradient)
      point_functional(a.rod(r), a.rod_variables(r), x, work, 0.0, axial, N / (F0 * F0), gradient);
  }
  return f;
}

double elastic_energy(const RobotAssembly& a, const VecX& x, VecX* gradient) {
  if (gradient) gradient->setZero(x.size());
  VecX work = x;
  double energy = 0.0;
  std::vector<double> nodes, weights;
  for (int r = 0; r < a.num_rods(); ++r) {
    const CollocationRod& rod = a.rod(r);
    const RodVariables& v = a.rod_variables(r);
    const Vec3 c_se = rod.model().shear_extension_stiffness.cwiseInverse();
    const Vec3 c_bt = rod.model().bending_torsion_stiffness.cwiseInverse();
    const BodyFunctional density = [&](const Vec3& n_b, const Vec3& m_b, Vec3& g_n, Vec3& g_m) {
      g_n = c_se.cwiseProduct(n_b);
      g_m = c_bt.cwiseProduct(m_b);
      return 0.5 * (n_b.dot(g_n) + m_b.dot(g_m));
    };
    const int spans = rod.discretization().elements;
    gauss_legendre(rod.discretization().degree + 1, nodes, weights);
    const double L = rod.length(x, v);
    double integral = 0.0;  // int_0^1 e du
    for (int k = 0; k < spans; ++k)
      for (size_t g = 0; g < nodes.size(); ++g) {
        const double u = std::clamp((k + 0.5 * (nodes[g] + 1.0)) / spans, 0.0, 1.0);
        const double w = 0.5 * weights[g] / spans;
        integral += w * point_functional(rod, v, x, work, u, density, L * w, gradient);
      }
    energy += L * integral;
    if (gradient) (*gradient)[v.length_offset] += integral;  // explicit dependence through ds = L du
  }
  return energy;
}

std::vector<StressPoint> stress_points(const RobotAssembly& a, int points_per_rod) {
  require(points_per_rod >= 2, "stress points per rod must be >= 2, got ", points_per_rod);
  std::vector<StressPoint> points;
  for (int r = 0; r < a.num_rods(); ++r)
    for (int j = 0; j < points_per_rod; ++j)
      points.push_back({r, static_cast<double>(j) / (points_per_rod - 1)});
  return points;
}

void check_stress_data(const RobotAssembly& a) {
  for (int r = 0; r < a.num_rods(); ++r) {
    const RodModel& m = a.rod(r).model();
    require(m.youngs_modulus > 0.0 && std::isfinite(m.youngs_modulus), "rod stress limit: rod '", m.name,
            "' has no Young's modulus (E = ", m.youngs_modulus, ")");
    require(m.outer_radius > 0.0 && std::isfinite(m.outer_radius), "rod stress limit: rod '", m.name,
            "' has no outer radius (", m.outer_radius, ")");
  }
}

VecX rod_stresses(const RobotAssembly& a, const VecX& x, const std::vector<StressPoint>& points,
                  MatX* jacobian) {
  VecX sigma(points.size());
  if (jacobian) jacobian->setZero(static_cast<int>(points.size()), x.size());
  VecX work = x, row(x.size());
  for (size_t j = 0; j < points.size(); ++j) {
    const CollocationRod& rod = a.rod(points[j].rod);
    const RodModel& m = rod.model();
    const double E = m.youngs_modulus, c = m.outer_radius;
    const double EA = m.shear_extension_stiffness[2];
    const double EI = std::min(m.bending_torsion_stiffness[0], m.bending_torsion_stiffness[1]);
    const double dN = 1e-9 * rod.force_scale(), dM = 1e-9 * rod.moment_scale();
    const BodyFunctional stress = [&](const Vec3& n_b, const Vec3& m_b, Vec3& g_n, Vec3& g_m) {
      const double N = smooth_abs(n_b[2], dN);
      const double M = std::sqrt(m_b[0] * m_b[0] + m_b[1] * m_b[1] + dM * dM);
      g_n = Vec3(0.0, 0.0, E * n_b[2] / (N * EA));
      g_m = Vec3(m_b[0], m_b[1], 0.0) * (E * c / (EI * M));
      return E * (N / EA + M * c / EI);
    };
    row.setZero();
    sigma[j] = point_functional(rod, a.rod_variables(points[j].rod), x, work, points[j].u, stress, 1.0,
                                jacobian ? &row : nullptr);
    if (jacobian) jacobian->row(j) = row.transpose();
  }
  return sigma;
}

}  // namespace pcr::kinematics
