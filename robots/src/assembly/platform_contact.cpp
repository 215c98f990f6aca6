#include "platform_contact.hpp"

#include <algorithm>

#include "pcr/math/so3.hpp"

namespace pcr::assembly {
namespace {

int index_of(std::vector<VariableId>& variables, VariableId id, int size,
             std::vector<std::pair<int, int>>& appended) {
  const auto it = std::find(variables.begin(), variables.end(), id);
  if (it != variables.end()) return static_cast<int>(it - variables.begin());
  variables.push_back(id);
  appended.push_back({static_cast<int>(variables.size()) - 1, size});
  return static_cast<int>(variables.size()) - 1;
}

}  // namespace

PlatformContactReaction::PlatformContactReaction(std::vector<PlatformContact> contacts,
                                                 std::vector<VariableId>& variables) {
  for (const PlatformContact& contact : contacts)
    for (const PlatformContactCell& c : contact.cells) {
      Cell cell;
      for (VariableId p : c.points)
        cell.points.push_back(index_of(variables, p, contact.point_size, appended_));
      cell.basis = c.basis;
      cell.force = index_of(variables, c.force, 3, appended_);
      cell.length = index_of(variables, c.length, 1, appended_);
      cell.fraction = c.fraction;
      cell.p_offset = contact.p_offset;
      cell.point_size = contact.point_size;
      cells_.push_back(std::move(cell));
    }
}

void PlatformContactReaction::zero_appended(double* const* jacobians, int rows) const {
  for (const auto& [index, size] : appended_)
    if (jacobians[index] != nullptr) std::fill(jacobians[index], jacobians[index] + rows * size, 0.0);
}

void PlatformContactReaction::add(const double* const* values, const Vec3& x, Vec3& force, Vec3& moment,
                                  Mat3& dmoment_dx, double* const* jacobians, int rows, double force_scale,
                                  double moment_scale) const {
  for (const Cell& cell : cells_) {
    Vec3 p = Vec3::Zero();
    for (size_t i = 0; i < cell.points.size(); ++i)
      p += cell.basis[i] * Eigen::Map<const Vec3>(values[cell.points[i]] + cell.p_offset);
    const Vec3 F = Eigen::Map<const Vec3>(values[cell.force]);
    const double c = values[cell.length][0] * cell.fraction;
    const Vec3 arm_x_F = (p - x).cross(F);
    force -= c * F;
    moment -= c * arm_x_F;  // = -c hat(p - x) F = c hat(F) (p - x)
    if (jacobians == nullptr) continue;
    dmoment_dx -= c * hat(F);
    if (double* J = jacobians[cell.length]) {
      for (int r = 0; r < 3; ++r) {
        J[r] -= cell.fraction * F[r] / force_scale;
        J[3 + r] -= cell.fraction * arm_x_F[r] / moment_scale;
      }
    }
    if (double* J = jacobians[cell.force]) {
      Eigen::Map<RowMajorMatX> block(J, rows, 3);
      block.block<3, 3>(0, 0) -= c * Mat3::Identity() / force_scale;
      block.block<3, 3>(3, 0) -= c * hat(p - x) / moment_scale;
    }
    for (size_t i = 0; i < cell.points.size(); ++i)
      if (double* J = jacobians[cell.points[i]]) {
        Eigen::Map<RowMajorMatX> block(J, rows, cell.point_size);
        block.block<3, 3>(3, cell.p_offset) += c * cell.basis[i] * hat(F) / moment_scale;
      }
  }
}

}  // namespace pcr::assembly
