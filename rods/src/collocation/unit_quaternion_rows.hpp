#pragma once
// Private to pcr_rods: the unit-quaternion rows |q(tau_j)|^2 - 1 = 0 of one rod at its interior Greville
// abscissae tau_1 .. tau_{n-2} (the forms that collocate their field equations at the midpoints), as one
// residual block. Row j reads the p + 1 control points whose basis functions are active at tau_{j+1};
// q(tau) = sum_i B_i(tau) Q_i. One block for the rod, not one per point: a row is a few multiply-adds, and
// the per-block overhead of the Problem's loop (pointers to every touched block's values) cost more than
// the rows themselves.
#include <memory>
#include <string>
#include <vector>

#include "pcr/solve/residual_block.hpp"

namespace pcr::collocation {

/// The basis at one abscissa: the values B_{first + i}(tau), i <= degree.
struct AbscissaBasis {
  int first = 0;
  std::vector<double> values;
};

/// control_points: the rod's control point blocks in order (cp_size components each, Q at q_offset);
/// bases: one per row, indices into control_points.
std::shared_ptr<const ResidualBlock> make_unit_quaternion_rows(const std::string& name,
                                                               std::vector<int> control_points, int cp_size,
                                                               int q_offset,
                                                               std::vector<AbscissaBasis> bases);

}  // namespace pcr::collocation
