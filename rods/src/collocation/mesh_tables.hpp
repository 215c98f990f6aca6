#pragma once
// Private to pcr_rods: the tables of a collocation mesh that do not depend on the rod (its stiffness,
// loads or ends), only on the degree and element count (the open uniform knot vector): the Greville
// abscissae with the factorised interpolation matrix N_j(tau_i), and the bases at the equally spaced
// points where a solve checks the axial stretch. Built once per mesh and shared process-wide (thread-safe;
// a solve of many rods of one mesh builds them once).
#include <memory>
#include <vector>

#include "pcr/solve/band_lu.hpp"
#include "pcr/splines/basis.hpp"
#include "pcr/splines/knot_vector.hpp"

namespace pcr::collocation {

struct MeshTables {
  int degree = 0, elements = 0;
  std::vector<double> greville;  ///< tau_0 = 0 < ... < tau_{n-1} = 1
  /// N_j(tau_i), n x n with p sub- and superdiagonals, factorised (interpolate_at_greville).
  BandLu greville_lu;
  bool greville_regular = false;  ///< whether that factorisation succeeded
  /// Bases (values and first u-derivatives) at u_k = k / (4 n), k = 0 .. 4 n (the collapse check of
  /// rod_solve.cpp).
  std::vector<BasisDerivatives> check_basis;
};

/// The tables of open_uniform(degree, elements), shared (at most a few dozen meshes are kept; others
/// are built for the caller alone).
std::shared_ptr<const MeshTables> mesh_tables(int degree, int elements);

/// Control points (n x columns) of the spline interpolating `values` (n x columns) at the Greville
/// abscissae; false when the interpolation matrix is singular.
bool interpolate_at_greville(const MeshTables& tables, const MatX& values, MatX& points);

}  // namespace pcr::collocation
