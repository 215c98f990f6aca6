#include "stability/discrete_rods.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/hyper_dual.hpp"

namespace pcr::test {

namespace {

constexpr int kLocal = 12;  // most local variables of a term: node (3) + frame (3) + platform (6)
using HD = HyperDual<kLocal>;
using V3 = std::array<HD, 3>;
using Q4 = std::array<HD, 4>;

V3 constant(const Vec3& v) {
  return {HD(v[0]), HD(v[1]), HD(v[2])};
}
Q4 constant(const Eigen::Vector4d& q) {
  return {HD(q[0]), HD(q[1]), HD(q[2]), HD(q[3])};
}
V3 add(const V3& a, const V3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
V3 sub(const V3& a, const V3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
V3 scale(const V3& a, double c) {
  return {a[0] * c, a[1] * c, a[2] * c};
}
HD dot(const V3& a, const V3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// Hamilton product, scalar first.
Q4 mul(const Q4& a, const Q4& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}
Q4 conj(const Q4& q) {
  return {q[0], -q[1], -q[2], -q[3]};
}
V3 vec(const Q4& q) {
  return {q[1], q[2], q[3]};
}
/// R(q) w for a unit q: w + 2 q_w (q_v x w) + 2 q_v x (q_v x w).
V3 rotate(const Q4& q, const V3& w) {
  const V3 qv = vec(q);
  const V3 t = scale(cross(qv, w), 2.0);
  return add(add(w, {q[0] * t[0], q[0] * t[1], q[0] * t[2]}), cross(qv, t));
}
/// normalise([1, phi / 2]) (x) q0.
Q4 perturbed(const V3& phi, const Q4& q0) {
  const HD n = inverse(sqrt(HD(1.0) + dot(phi, phi) * 0.25));
  const Q4 d = {n, phi[0] * 0.5 * n, phi[1] * 0.5 * n, phi[2] * 0.5 * n};
  return mul(d, q0);
}
/// h / 2 u^T K u with u = (2 / d) vec(conj(qa) (x) qb), the sign of qb chosen so that they are close.
HD bending(const Q4& qa, const Q4& qb, double d, double weight, const Vec3& k) {
  const Q4 rel = mul(conj(qa), qb);
  const double sign = rel[0].a < 0.0 ? -1.0 : 1.0;
  HD e(0.0);
  for (int j = 0; j < 3; ++j) {
    const HD u = rel[j + 1] * (2.0 * sign / d);
    e += u * u * (0.5 * k[j] * weight);
  }
  return e;
}
Eigen::Vector4d quat_of(const Mat3& R) {
  const Eigen::Quaterniond q(R);
  return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
}
Eigen::Vector4d quat_product(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
  Q4 r = mul(constant(a), constant(b));
  return Eigen::Vector4d(r[0].a, r[1].a, r[2].a, r[3].a);
}
Eigen::Vector4d retracted(const Vec3& phi, const Eigen::Vector4d& q) {
  Eigen::Vector4d d(1.0, 0.5 * phi[0], 0.5 * phi[1], 0.5 * phi[2]);
  return quat_product(d.normalized(), q).normalized();
}

/// The local variables of one term: slot k is global variable global[k].
struct Local {
  std::vector<int> global;
  HD var(int g) {
    for (size_t k = 0; k < global.size(); ++k)
      if (global[k] == g) return HD::variable(0.0, static_cast<int>(k));
    if (global.size() == kLocal) throw std::logic_error("discrete_rods: too many local variables");
    global.push_back(g);
    return HD::variable(0.0, static_cast<int>(global.size()) - 1);
  }
  V3 vars(int first) { return {var(first), var(first + 1), var(first + 2)}; }
};

}  // namespace

/// The energy terms, with access to the state.
struct DiscreteTerms {
  const DiscreteRods& s;
  double energy = 0.0;
  VecX* gradient;
  MatX* hessian;

  void accumulate(const Local& local, const HD& e) {
    energy += e.a;
    for (size_t k = 0; k < local.global.size(); ++k) {
      if (gradient) (*gradient)[local.global[k]] += e.g[k];
      if (hessian)
        for (size_t l = 0; l < local.global.size(); ++l)
          (*hessian)(local.global[k], local.global[l]) += e.H(k, l);
    }
  }
  Q4 platform_frame(int p, Local& L) const {
    const auto& P = s.platforms_[p];
    return perturbed(L.vars(P.index + 3), constant(P.Q));
  }
  Q4 hinge_turn(int h, Local& L) const {
    const auto& H = s.hinges_[h];
    const HD t = L.var(H.index);
    return perturbed({t * H.spec.axis[0], t * H.spec.axis[1], t * H.spec.axis[2]}, constant(H.turn));
  }
  /// A point given at the hinge's value, turned with it.
  V3 on_hinge(int h, const Vec3& point, Local& L) const {
    const Vec3& o = s.hinges_[h].spec.origin;
    return add(constant(o), rotate(hinge_turn(h, L), constant(Vec3(point - o))));
  }
  Q4 base_frame(int r, Local& L) const {
    const auto& rod = s.rods_[r];
    if (rod.spec.base_hinge < 0) return constant(rod.base_q);
    return mul(hinge_turn(rod.spec.base_hinge, L), constant(rod.base_q));
  }
  V3 node(int r, int i, Local& L) const {
    const auto& rod = s.rods_[r];
    const int idx = rod.p_index[i];
    if (idx == -1) return constant(rod.p[i]);
    if (idx == -3) return on_hinge(rod.spec.base_hinge, rod.spec.base_position, L);
    if (idx >= 0) return add(constant(rod.p[i]), L.vars(idx));
    const auto& P = s.platforms_[rod.spec.platform];  // attached tip: x + R(Q) r
    return add(add(constant(P.x), L.vars(P.index)),
               rotate(platform_frame(rod.spec.platform, L), constant(rod.spec.attachment_position)));
  }
  Q4 frame(int r, int i, Local& L) const {
    const auto& rod = s.rods_[r];
    return perturbed(L.vars(rod.q_index[i]), constant(rod.q[i]));
  }
  Q4 tip_frame(int r, Local& L) const {
    const auto& rod = s.rods_[r];
    Q4 q = mul(platform_frame(rod.spec.platform, L), constant(quat_of(rod.spec.attachment_rotation)));
    if (rod.spec.tip == DiscreteTip::Collar) {
      const HD psi = L.var(rod.twist_index);
      q = mul(q, perturbed({HD(0.0), HD(0.0), psi}, constant(rod.twist_q)));
    }
    return q;
  }

  void rod_terms(int r) {
    const auto& rod = s.rods_[r];
    const int N = rod.spec.segments;
    const double h = rod.spec.length / N;
    for (int i = 0; i < N; ++i) {  // shear and extension
      Local L;
      const V3 pa = node(r, i, L), pb = node(r, i + 1, L);
      const Q4 q = frame(r, i, L);
      const V3 v = scale(rotate(conj(q), sub(pb, pa)), 1.0 / h);
      HD e(0.0);
      for (int j = 0; j < 3; ++j) {
        const HD strain = v[j] - (j == 2 ? 1.0 : 0.0);
        e += strain * strain * (0.5 * rod.spec.k_se[j] * h);
      }
      accumulate(L, e);
    }
    for (int i = 1; i < N; ++i) {  // bending and torsion between segment centres
      Local L;
      const Q4 qa = frame(r, i - 1, L), qb = frame(r, i, L);
      accumulate(L, bending(qa, qb, h, h, rod.spec.k_bt));
    }
    {
      Local L;
      const Q4 q0 = frame(r, 0, L);
      accumulate(L, bending(base_frame(r, L), q0, 0.5 * h, 0.5 * h, rod.spec.k_bt));
    }
    if (rod.spec.tip == DiscreteTip::Clamped || rod.spec.tip == DiscreteTip::Collar) {
      Local L;
      const Q4 qa = frame(r, N - 1, L), qb = tip_frame(r, L);
      accumulate(L, bending(qa, qb, 0.5 * h, 0.5 * h, rod.spec.k_bt));
    }
    for (int i = 1; i <= N; ++i) {  // dead loads on the nodes (trapezoid)
      Vec3 F = rod.spec.distributed_force * (i == N ? 0.5 * h : h);
      if (i == N && rod.spec.tip == DiscreteTip::Free) F += rod.spec.tip_force;
      Local L;
      accumulate(L, -dot(constant(F), node(r, i, L)));
    }
  }
  void hinge_terms(int h) {
    const auto& H = s.hinges_[h];
    {
      Local L;
      const HD angle = L.var(H.index) + (H.spec.value + H.angle - H.spec.rest);
      accumulate(L, angle * angle * (0.5 * H.spec.stiffness));
    }
    for (const auto& f : H.spec.forces) {
      Local L;
      accumulate(L, -dot(constant(f.second), on_hinge(h, f.first, L)));
    }
  }
  void platform_terms(int p) {
    const auto& P = s.platforms_[p];
    for (const auto& f : P.spec.forces) {
      Local L;
      const V3 point =
          add(add(constant(P.x), L.vars(P.index)), rotate(platform_frame(p, L), constant(f.first)));
      accumulate(L, -dot(constant(f.second), point));
    }
  }
};

DiscreteRods::DiscreteRods(std::vector<DiscreteRodSpec> rods, std::vector<DiscretePlatformSpec> platforms,
                           std::vector<DiscreteHingeSpec> hinges) {
  for (auto& spec : hinges) {
    Hinge H;
    H.spec = spec;
    H.index = num_variables_++;
    hinges_.push_back(H);
  }
  for (auto& spec : rods) {
    Rod rod;
    rod.spec = spec;
    const int N = spec.segments;
    rod.p.assign(N + 1, Vec3::Zero());
    rod.q.assign(N, Eigen::Vector4d(1, 0, 0, 0));
    rod.p_index.assign(N + 1, -1);
    if (spec.base_hinge >= 0) rod.p_index[0] = -3;
    rod.q_index.assign(N, -1);
    for (int i = 1; i <= N; ++i) {
      if (i == N && spec.tip != DiscreteTip::Free) {
        rod.p_index[i] = -2;
      } else {
        rod.p_index[i] = num_variables_;
        num_variables_ += 3;
      }
    }
    for (int i = 0; i < N; ++i) {
      rod.q_index[i] = num_variables_;
      num_variables_ += 3;
    }
    if (spec.tip == DiscreteTip::Collar) rod.twist_index = num_variables_++;
    rod.base_q = quat_of(spec.base_rotation);
    rod.twist_q = Eigen::Vector4d(1, 0, 0, 0);
    rods_.push_back(rod);
  }
  for (auto& spec : platforms) {
    Platform P;
    P.spec = spec;
    P.index = num_variables_;
    num_variables_ += 6;
    platforms_.push_back(P);
  }
}

void DiscreteRods::set_platform(int p, const Vec3& x, const Mat3& R) {
  platforms_[p].x = x;
  platforms_[p].Q = quat_of(R);
}

void DiscreteRods::set_rod(int r, const std::function<void(double s, Vec3& p, Mat3& R)>& state) {
  Rod& rod = rods_[r];
  const int N = rod.spec.segments;
  const double h = rod.spec.length / N;
  Mat3 R;
  for (int i = 0; i <= N; ++i) state(i * h, rod.p[i], R);
  Vec3 p;
  for (int i = 0; i < N; ++i) {
    state((i + 0.5) * h, p, R);
    rod.q[i] = quat_of(R);
    if (i > 0 && rod.q[i].dot(rod.q[i - 1]) < 0.0) rod.q[i] = -rod.q[i];
  }
  if (rod.spec.tip == DiscreteTip::Collar) {  // the twist about the collar axis that the state has at s = L
    state(rod.spec.length, p, R);
    const Platform& P = platforms_[rod.spec.platform];
    const Mat3 Rz =
        (Eigen::Quaterniond(P.Q[0], P.Q[1], P.Q[2], P.Q[3]).toRotationMatrix() * rod.spec.attachment_rotation)
            .transpose() *
        R;
    const double psi = std::atan2(Rz(1, 0) - Rz(0, 1), Rz(0, 0) + Rz(1, 1));
    rod.twist_q = Eigen::Vector4d(std::cos(0.5 * psi), 0, 0, std::sin(0.5 * psi));
  }
}

double DiscreteRods::assemble(VecX* gradient, MatX* hessian) const {
  if (gradient) gradient->setZero(num_variables_);
  if (hessian) hessian->setZero(num_variables_, num_variables_);
  DiscreteTerms terms{*this, 0.0, gradient, hessian};
  for (size_t r = 0; r < rods_.size(); ++r) terms.rod_terms(static_cast<int>(r));
  for (size_t p = 0; p < platforms_.size(); ++p) terms.platform_terms(static_cast<int>(p));
  for (size_t h = 0; h < hinges_.size(); ++h) terms.hinge_terms(static_cast<int>(h));
  return terms.energy;
}

void DiscreteRods::step(const VecX& dy) {
  for (Rod& rod : rods_) {
    for (size_t i = 0; i < rod.p.size(); ++i)
      if (rod.p_index[i] >= 0) rod.p[i] += dy.segment<3>(rod.p_index[i]);
    for (size_t i = 0; i < rod.q.size(); ++i) rod.q[i] = retracted(dy.segment<3>(rod.q_index[i]), rod.q[i]);
    if (rod.twist_index >= 0) rod.twist_q = retracted(Vec3(0, 0, dy[rod.twist_index]), rod.twist_q);
  }
  for (Platform& P : platforms_) {
    P.x += dy.segment<3>(P.index);
    P.Q = retracted(dy.segment<3>(P.index + 3), P.Q);
  }
  for (Hinge& H : hinges_) {  // the turn's angle: 2 atan(t / 2) (DiscreteHingeSpec)
    H.turn = retracted(dy[H.index] * H.spec.axis, H.turn);
    H.angle += 2.0 * std::atan(0.5 * dy[H.index]);
  }
  for (Rod& rod : rods_)  // bases on hinges turn with them
    if (rod.spec.base_hinge >= 0) {
      const Hinge& H = hinges_[rod.spec.base_hinge];
      rod.p[0] =
          H.spec.origin + Eigen::Quaterniond(H.turn[0], H.turn[1], H.turn[2], H.turn[3]).toRotationMatrix() *
                              (rod.spec.base_position - H.spec.origin);
    }
  for (Rod& rod : rods_)  // attached tips follow their platform
    if (rod.spec.tip != DiscreteTip::Free) {
      const Platform& P = platforms_[rod.spec.platform];
      rod.p.back() = P.x + Eigen::Quaterniond(P.Q[0], P.Q[1], P.Q[2], P.Q[3]).toRotationMatrix() *
                               rod.spec.attachment_position;
    }
}

bool DiscreteRods::relax(int max_iterations) {
  double L = 0.0;
  for (const Rod& rod : rods_) L = std::max(L, rod.spec.length);
  VecX g;
  MatX H;
  for (int it = 0; it < max_iterations; ++it) {
    assemble(&g, &H);
    const VecX dy = H.partialPivLu().solve(-g);
    if (!dy.allFinite()) return false;
    step(dy);
    double largest = 0.0;
    for (const Rod& rod : rods_) {
      for (int idx : rod.p_index)
        if (idx >= 0) largest = std::max(largest, dy.segment<3>(idx).cwiseAbs().maxCoeff() / L);
      for (int idx : rod.q_index) largest = std::max(largest, dy.segment<3>(idx).cwiseAbs().maxCoeff());
    }
    for (const Hinge& H : hinges_) largest = std::max(largest, std::abs(dy[H.index]));
    if (largest < 1e-11) return true;
  }
  return false;
}

DiscreteRods::Inertia DiscreteRods::inertia(double zero_tolerance) const {
  MatX H;
  assemble(nullptr, &H);
  VecX d(num_variables_);
  for (int i = 0; i < num_variables_; ++i) d[i] = 1.0 / std::sqrt(std::max(std::abs(H(i, i)), 1e-300));
  const VecX lambda = symmetric_eigenvalues(d.asDiagonal() * H * d.asDiagonal());
  Inertia out;
  out.smallest = lambda[0];
  for (int i = 0; i < lambda.size(); ++i) {
    if (lambda[i] < -zero_tolerance)
      ++out.negative;
    else if (lambda[i] <= zero_tolerance)
      ++out.zero;
  }
  return out;
}

}  // namespace pcr::test
