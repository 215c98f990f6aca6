#pragma once
// Private to pcr_rods: unit-quaternion rows |q(tau)|^2 - 1 = 0 at consecutive interior Greville abscissae
// of one rod (the forms that collocate their field equations at the midpoints), several rows as one
// residual block. Each row reads the p + 1 control points whose basis functions are active at its
// abscissa; q(tau) = sum_i B_i(tau) Q_i. Several rows a block, not one: a row is a few multiply-adds, and
// the per-block overhead of the Problem's loop (pointers to every touched block's values) cost more than
// the row itself; not all of a rod's rows in one block either: a block's dense Jacobian has rows x its
// control points entries (FormBuilder::add_unit_quaternion_rows takes 8 rows a block).
#include <memory>
#include <string>
#include <vector>

#include "pcr/rods/collocation/point_block.hpp"
#include "pcr/solve/residual_block.hpp"

namespace pcr::collocation {

/// control_points: consecutive control point blocks of a rod (cp_size components each, Q at q_offset);
/// bases: one per row (FormBuilder::basis_at, the values in slot 0), `first` indexing control_points.
std::shared_ptr<const ResidualBlock> make_unit_quaternion_rows(const std::string& name,
                                                               std::vector<int> control_points, int cp_size,
                                                               int q_offset, std::vector<PointBasis> bases);

}  // namespace pcr::collocation
