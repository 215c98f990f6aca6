#pragma once
// The 7 boundary equations at a rod end (DESIGN.md §1), from p, q, n, m at that end.
// Internal header of pcr::rods. Dirichlet (kinematic) conditions fix p and q (or parts of them);
// Neumann conditions fix n and m. Sign: n, m are the force and moment that the part s+ exerts on s-,
// so an external load (F, M) on the rod gives n = F, m = M at s = L and n = -F, m = -M at s = 0.
#include "equations.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr::collocation {

/// Data of one end condition with the load factor already applied to its loads.
struct EndData {
  RodEndKind kind = RodEndKind::Free;
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat(1, 0, 0, 0);  ///< normalised
  Mat3 frame = Mat3::Identity();        ///< R(orientation)
  Vec3 n_bar = Vec3::Zero(), m_bar = Vec3::Zero();  ///< prescribed n, m (signs applied)
};

/// r[0..7) from p, q, n, m at the end (all world frame).
template <typename T>
void end_conditions(const EndData& e, const PointConstants& c, const V3<T>& p, const V4<T>& q, const V3<T>& n,
                    const V3<T>& m, T* r) {
  const double L0 = c.length_scale, F0 = c.force_scale, M0 = c.moment_scale;
  switch (e.kind) {
    case RodEndKind::Clamped:
      for (int i = 0; i < 3; ++i) r[i] = (p[i] - e.position[i]) / L0;
      for (int i = 0; i < 4; ++i) r[3 + i] = q[i] - e.orientation[i];
      return;
    case RodEndKind::Collar: {
      // d3 stays perpendicular to the two frame axes across the collar axis; free torsion: m . d3 = 0.
      const V3<T> d3 = rotation(q).col(2);
      for (int i = 0; i < 3; ++i) r[i] = (p[i] - e.position[i]) / L0;
      r[3] = d3.dot(e.frame.col(0).template cast<T>());
      r[4] = d3.dot(e.frame.col(1).template cast<T>());
      r[5] = m.dot(d3) / M0;
      r[6] = q.squaredNorm() - 1.0;
      return;
    }
    case RodEndKind::Spherical:
      for (int i = 0; i < 3; ++i) {
        r[i] = (p[i] - e.position[i]) / L0;
        r[3 + i] = (m[i] - e.m_bar[i]) / M0;
      }
      r[6] = q.squaredNorm() - 1.0;
      return;
    case RodEndKind::Free:
      for (int i = 0; i < 3; ++i) {
        r[i] = (n[i] - e.n_bar[i]) / F0;
        r[3 + i] = (m[i] - e.m_bar[i]) / M0;
      }
      r[6] = q.squaredNorm() - 1.0;
      return;
  }
}

}  // namespace pcr::collocation
