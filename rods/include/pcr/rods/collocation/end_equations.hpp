#pragma once
// The 7 boundary equations at a rod end (docs/design.md §1), from p, q, n, m at that end. Shared by the
// single-rod end conditions (constant target frame) and the robot couplings (target frame = link
// pose * attachment, itself unknown). Dirichlet (kinematic) conditions fix p and q (or parts of them);
// Neumann conditions fix n and m. Sign: n, m are the force and moment that the part s+ exerts on s-,
// so an external load (F, M) on the rod gives n = F, m = M at s = L and n = -F, m = -M at s = 0.
#include "pcr/core/error.hpp"
#include "pcr/rods/collocation/equations.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr::collocation {

/// The frame an end is held in: position, quaternion (unit) and its rotation matrix.
template <typename T>
struct EndTarget {
  V3<T> position;
  V4<T> orientation;
  M3<T> frame;
};

/// Prescribed n, m at an end (load factor and signs applied); used by collar (torsion), spherical and
/// free ends.
struct EndLoads {
  Vec3 n_bar = Vec3::Zero(), m_bar = Vec3::Zero();
};

/// r[0..7) from p, q, n, m at the end (all world frame), scaled by the rod's reference scales.
template <typename T>
void end_conditions(RodEndKind kind, const EndTarget<T>& target, const EndLoads& loads,
                    const PointConstants& c, const V3<T>& p, const V4<T>& q, const V3<T>& n, const V3<T>& m,
                    T* r) {
  const double L0 = c.length_scale, F0 = c.force_scale, M0 = c.moment_scale;
  switch (kind) {
    case RodEndKind::Universal:
    case RodEndKind::Revolute:
      throw_input_error("collocation rod end: the ", to_string(kind), " coupling is not implemented yet");
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

}  // namespace pcr::collocation
