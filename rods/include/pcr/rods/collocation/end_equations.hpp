#pragma once
// The 7 boundary equations at a rod end (docs/design.md §1), from p, q, n, m at that end. Shared by the
// single-rod end conditions (constant target frame) and the robot couplings (target frame = link
// pose * attachment, itself unknown). Dirichlet (kinematic) conditions fix p and q (or parts of them);
// Neumann conditions fix n and m. Sign: n, m are the force and moment that the part s+ exerts on s-,
// so an external load (F, M) on the rod gives n = F, m = M at s = L and n = -F, m = -M at s = 0.
#include "pcr/rods/collocation/equations.hpp"
#include "pcr/rods/drawn_rod.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr::collocation {

/// The frame an end is held in: position, quaternion (unit) and its rotation matrix R_T; for universal
/// and revolute ends the joint axes [a, c1, c2] in that frame (joint_axes, end_axes.hpp: a the joint
/// axis, c1 = b the universal's second axis, c1, c2 the directions a pin blocks).
template <typename T>
struct EndTarget {
  V3<T> position;
  V4<T> orientation;
  M3<T> frame;
  Mat3 axes = Mat3::Identity();
};

/// Prescribed n, m at an end (load factor and signs applied); used by collar (torsion), spherical and
/// free ends.
struct EndLoads {
  Vec3 n_bar = Vec3::Zero(), m_bar = Vec3::Zero();
};

/// Hooke joint (universal), 7 rows: (p - p_T) / L0 (3); (R_T a) . (R b) (1); (m - m_bar) . (R_T a) / M0,
/// (m - m_bar) . (R b) / M0 (2); |q|^2 - 1 (1); a the first axis (fixed in the end frame), b = e3 x a /
/// |e3 x a| the second (fixed in the rod's body frame), R = R(q) the rod frame at the end.
/// The orientation row's zero set is exactly the joint's configurations R = R_T R_a(t1) R_b(t2): these
/// give R b = R_T R_a(t1) b, and a . R_a(t1) b = a . b = 0. Conversely, with R' = R_T^T R and
/// a . (R' b) = 0, R' b is a unit vector normal to a, so R' b = R_a(t1) b for some t1 (the unit vectors
/// normal to a are the circle R_a(t) b); then R_a(-t1) R' fixes b, so it is R_b(t2) for some t2. The
/// row's gradient in the rotation, R b x R_T a, never vanishes there (the two axes stay perpendicular):
/// no gimbal singularity in these equations. Torsion (the moment about R_T a x R b) is transmitted.
template <typename T>
void universal_conditions(const EndTarget<T>& target, const EndLoads& loads, const PointConstants& c,
                          const V3<T>& p, const V4<T>& q, const V3<T>& m, T* r) {
  const Mat3 axes = target.axes;                             // [a, b, a x b], end frame
  const V3<T> first = target.frame * axes.col(0).cast<T>();  // R_T a
  const V3<T> second = rotation(q) * axes.col(1).cast<T>();  // R b
  const V3<T> moment = m - loads.m_bar.cast<T>();
  for (int i = 0; i < 3; ++i) r[i] = (p[i] - target.position[i]) / c.length_scale;
  r[3] = first.dot(second);
  r[4] = moment.dot(first) / c.moment_scale;
  r[5] = moment.dot(second) / c.moment_scale;
  r[6] = q.squaredNorm() - 1.0;
}

/// Pin (revolute), 7 rows: (p - p_T) / L0 (3); (R a) . (R_T c1), (R a) . (R_T c2) (2): the rod frame
/// turns only about a, R a = R_T a; (m - m_bar) . (R_T a) / M0 (1); |q|^2 - 1 (1). Like the collar's,
/// the orientation rows also vanish on the flipped branch R a = -R_T a (the rod turned half a turn
/// about an axis normal to a); Newton from the attachment frame stays on R a = R_T a.
template <typename T>
void revolute_conditions(const EndTarget<T>& target, const EndLoads& loads, const PointConstants& c,
                         const V3<T>& p, const V4<T>& q, const V3<T>& m, T* r) {
  const Mat3 axes = target.axes;                              // [a, c1, c2], end frame
  const V3<T> pin_rod = rotation(q) * axes.col(0).cast<T>();  // R a
  const V3<T> pin = target.frame * axes.col(0).cast<T>();     // R_T a
  for (int i = 0; i < 3; ++i) r[i] = (p[i] - target.position[i]) / c.length_scale;
  r[3] = pin_rod.dot(target.frame * axes.col(1).cast<T>());
  r[4] = pin_rod.dot(target.frame * axes.col(2).cast<T>());
  r[5] = (m - loads.m_bar.cast<T>()).dot(pin) / c.moment_scale;
  r[6] = q.squaredNorm() - 1.0;
}

/// r[0..7) from p, q and the section force and moment n, m at the end (all world frame), scaled by the
/// rod's reference scales.
template <typename T>
void section_end_conditions(RodEndKind kind, const EndTarget<T>& target, const EndLoads& loads,
                            const PointConstants& c, const V3<T>& p, const V4<T>& q, const V3<T>& n,
                            const V3<T>& m, T* r) {
  const double L0 = c.length_scale, F0 = c.force_scale, M0 = c.moment_scale;
  switch (kind) {
    case RodEndKind::Universal: universal_conditions(target, loads, c, p, q, m, r); return;
    case RodEndKind::Revolute: revolute_conditions(target, loads, c, p, q, m, r); return;
    case RodEndKind::Clamped:
      for (int i = 0; i < 3; ++i) r[i] = (p[i] - target.position[i]) / L0;
      for (int i = 0; i < 4; ++i) r[3 + i] = q[i] - target.orientation[i];
      return;
    case RodEndKind::Collar: {
      // d3 stays perpendicular to the two frame axes across the collar axis; free in torsion: only
      // the applied torsional moment is transmitted, (m - m_bar) . d3 = 0 (0 for a plain collar).
      const V3<T> d3 = rotation(q).col(2);
      for (int i = 0; i < 3; ++i) r[i] = (p[i] - target.position[i]) / L0;
      r[3] = d3.dot(target.frame.col(0));
      r[4] = d3.dot(target.frame.col(1));
      r[5] = (m - loads.m_bar.cast<T>()).dot(d3) / M0;
      r[6] = q.squaredNorm() - 1.0;
      return;
    }
    case RodEndKind::Spherical:
      for (int i = 0; i < 3; ++i) {
        r[i] = (p[i] - target.position[i]) / L0;
        r[3 + i] = (m[i] - loads.m_bar[i]) / M0;
      }
      r[6] = q.squaredNorm() - 1.0;
      return;
    case RodEndKind::Free:
      for (int i = 0; i < 3; ++i) {
        r[i] = (n[i] - loads.n_bar[i]) / F0;
        r[3 + i] = (m[i] - loads.m_bar[i]) / M0;
      }
      r[6] = q.squaredNorm() - 1.0;
      return;
  }
}

/// r[0..7) from p, q, n, m at the end (all world frame), scaled by the rod's reference scales. For a
/// drawn rod (c.flux_force or c.flux_moment set) n, m are the effective N, M of the unknowns and the
/// conditions hold for the section's n = N + rho A c^2 p', m = M + rho c^2 R J_rho kappa
/// (section_from_effective): a load (F, M) applied to the material section at s = L gives n(L) = F,
/// i.e. N(L) = F - rho A c^2 p'(L).
template <typename T>
void end_conditions(RodEndKind kind, const EndTarget<T>& target, const EndLoads& loads,
                    const PointConstants& c, const V3<T>& p, const V4<T>& q, const V3<T>& n, const V3<T>& m,
                    T* r) {
  if (c.flux_force == 0.0 && c.flux_moment.isZero(0.0)) {
    section_end_conditions<T>(kind, target, loads, c, p, q, n, m, r);
    return;
  }
  V3<T> n_section, m_section;
  section_from_effective<T>(rotation(q), n, m, c.flux_force, c.flux_moment, c.k_se, c.k_bt, c.eps0, c.kappa0,
                            n_section, m_section);
  section_end_conditions<T>(kind, target, loads, c, p, q, n_section, m_section, r);
}

}  // namespace pcr::collocation
