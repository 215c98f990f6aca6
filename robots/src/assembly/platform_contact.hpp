#pragma once
// The reaction of a rod's contact with obstacles carried by a platform, for the platform's balance
// (internal header of pcr::robots; docs/contact.md, "Obstacles on moving links"). The rod's distributed
// contact force in cell j is c_j F_j, F_j its density unknown (N/m, world frame; rod_contact.hpp) and c_j =
// L (tau_{j+1} - tau_j) the cell's length (L the rod's length unknown, fixed or an input), acting through the
// centerline point p_j = sum_i N_i(u_j) P_i of the cell's midpoint. By Newton's third law the platform feels
// -c_j F_j at p_j: with its origin x,
//   force  -= sum_j c_j F_j,     moment about x  -= sum_j c_j (p_j - x) x F_j.
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/solve/residual_block.hpp"

namespace pcr::assembly {

struct PlatformContactCell {
  std::vector<VariableId> points;  ///< the control points active at u_j
  std::vector<double> basis;       ///< N_i(u_j)
  VariableId force = -1;           ///< F_j
  VariableId length = -1;          ///< the rod's length L
  double fraction = 0.0;           ///< tau_{j+1} - tau_j: c_j = L fraction
};

/// The cells of one rod; p_offset: the centerline's offset in a control point of point_size values.
struct PlatformContact {
  int p_offset = 0, point_size = 0;
  std::vector<PlatformContactCell> cells;
};

class PlatformContactReaction {
 public:
  PlatformContactReaction() = default;
  /// Appends to `variables` the contact variables not yet in it (a balance block lists each once).
  PlatformContactReaction(std::vector<PlatformContact> contacts, std::vector<VariableId>& variables);

  /// Zeroes the Jacobian blocks of the variables this reaction appended (index >= first_appended).
  void zero_appended(double* const* jacobians, int rows) const;
  /// Adds the reaction to force and moment (about x) and its derivatives: d moment / dx to dmoment_dx,
  /// the others (rows 0..2 / force_scale, 3..5 / moment_scale) added into `jacobians` (row-major, `rows`
  /// rows).
  void add(const double* const* values, const Vec3& x, Vec3& force, Vec3& moment, Mat3& dmoment_dx,
           double* const* jacobians, int rows, double force_scale, double moment_scale) const;

 private:
  struct Cell {
    std::vector<int> points;  // indices in the block's variables
    std::vector<double> basis;
    int force = -1, length = -1;
    double fraction = 0.0;
    int p_offset = 0, point_size = 0;
  };
  std::vector<Cell> cells_;
  std::vector<std::pair<int, int>> appended_;  // (index, size) of the appended variables
};

}  // namespace pcr::assembly
