#pragma once
// Private to pcr_rods: the condensed form's field rows (equations.hpp, condensed_field) with their
// Jacobian written out, for the Newton hot path (point_block.hpp takes it instead of Dual numbers).
#include "pcr/rods/collocation/equations.hpp"

namespace pcr::collocation {

inline constexpr int kCondensedLocal = CondensedZ::layout.size();

/// r (6) = condensed_field(z) and J = dr/dz (6 x kCondensedLocal, row-major).
void condensed_field_jacobian(const Eigen::Matrix<double, kCondensedLocal, 1>& z, const PointConstants& c,
                              const Vec3& moment_point, double* r, double* J);

/// The kernel of the condensed field rows: Dual numbers through operator() (pattern detection), the
/// written-out Jacobian through jacobian().
struct CondensedFieldKernel {
  PointConstants c;
  Vec3 moment_point;

  template <typename Local, typename T>
  void operator()(const Local& z, T* r) const {
    condensed_field(z, c, moment_point, r);
  }
  void jacobian(const Eigen::Matrix<double, kCondensedLocal, 1>& z, double* r, double* J) const {
    condensed_field_jacobian(z, c, moment_point, r, J);
  }
};

}  // namespace pcr::collocation
