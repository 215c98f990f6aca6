#include "moving_obstacle_block.hpp"

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"

namespace pcr::assembly {
namespace {

using RowMatX = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

std::vector<VariableId> joined_variables(const ResidualBlock& inner, const LinkFrame& frame) {
  std::vector<VariableId> v = inner.variables();
  v.insert(v.end(), frame.variables.begin(), frame.variables.end());
  return v;
}

class MovingObstacleBlock final : public ResidualBlock {
 public:
  MovingObstacleBlock(std::shared_ptr<const ResidualBlock> inner, std::vector<ContactVariableRole> roles,
                      int p_offset, LinkFrame frame, const Vec7& z0)
      : ResidualBlock(inner->kind(), inner->name() + ".moving", inner->num_rows(),
                      joined_variables(*inner, frame)),
        inner_(std::move(inner)),
        roles_(std::move(roles)),
        p_offset_(p_offset),
        frame_(std::move(frame)),
        x0_(z0.head<3>()),
        R0_(rotation_matrix(Quat(z0[3], z0[4], z0[5], z0[6]))) {
    require(roles_.size() == inner_->variables().size(), "moving obstacle block '", inner_->name(),
            "': ", roles_.size(), " roles for ", inner_->variables().size(), " variables");
    for (size_t k = 0; k < roles_.size(); ++k)
      sizes_.push_back(inner_->expected_variable_size(static_cast<int>(k)));
    for (size_t k = 0; k < frame_.variables.size(); ++k)
      sizes_.push_back(frame_.kind == LinkFrame::Kind::Platform ? 7 : 1);
  }

  int expected_variable_size(int k) const override { return sizes_[k]; }

  bool structural_nonzero(int k, int row, int column) const override {
    if (k >= num_inner()) return true;
    const int first = group_start(k);
    if (first < 0 || column < first || column >= first + 3) return inner_->structural_nonzero(k, row, column);
    bool any = false;  // A mixes the three components of the group
    for (int c = first; c < first + 3; ++c) any = any || inner_->structural_nonzero(k, row, c);
    return any;
  }

  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    const int n = num_inner(), rows = num_rows();
    Vec7 z;
    MatX dz;
    frame_.evaluate(values + n, z, jacobians ? &dz : nullptr);
    const Quat q(z[3], z[4], z[5], z[6]);
    Mat3 R;
    QuatRotationJacobian dR;
    rotation_matrix_derivatives(q, R, dR);
    const Mat3 A = R0_ * R.transpose();
    const Vec3 x = z.head<3>();
    std::vector<VecX> moved(n);
    std::vector<Vec3> originals(n, Vec3::Zero());  // P - x, or the vector v, per variable with a group
    std::vector<const double*> pointers(n);
    for (int k = 0; k < n; ++k) {
      moved[k] = Eigen::Map<const VecX>(values[k], sizes_[k]);
      const int first = group_start(k);
      if (first >= 0) {
        originals[k] = moved[k].segment<3>(first);
        if (roles_[k] == ContactVariableRole::ControlPoint) originals[k] -= x;
        moved[k].segment<3>(first) =
            A * originals[k] + (roles_[k] == ContactVariableRole::ControlPoint ? x0_ : Vec3::Zero());
      }
      pointers[k] = moved[k].data();
    }
    if (jacobians == nullptr) {
      inner_->evaluate(pointers.data(), residual, nullptr);
      return;
    }
    std::vector<RowMatX> J(n);
    std::vector<double*> inner_jacobians(n);
    for (int k = 0; k < n; ++k) {
      J[k].setZero(rows, sizes_[k]);
      inner_jacobians[k] = J[k].data();
    }
    inner_->evaluate(pointers.data(), residual, inner_jacobians.data());
    MatX d_dz = MatX::Zero(rows, 7);  // d residual / d z
    for (int k = 0; k < n; ++k) {
      const int first = group_start(k);
      if (first >= 0) {
        const MatX group = J[k].middleCols(first, 3);
        J[k].middleCols(first, 3) = group * A;
        if (roles_[k] == ContactVariableRole::ControlPoint) d_dz.leftCols(3) -= group * A;
        for (int m = 0; m < 4; ++m) d_dz.col(3 + m) += group * (R0_ * dR[m].transpose() * originals[k]);
      }
      if (jacobians[k] != nullptr) Eigen::Map<RowMatX>(jacobians[k], rows, sizes_[k]) = J[k];
    }
    const MatX d_frame = d_dz * dz;
    for (int k = n, column = 0; k < static_cast<int>(sizes_.size()); column += sizes_[k], ++k)
      if (jacobians[k] != nullptr)
        Eigen::Map<RowMatX>(jacobians[k], rows, sizes_[k]) = d_frame.middleCols(column, sizes_[k]);
  }

 private:
  int num_inner() const { return static_cast<int>(roles_.size()); }
  /// First column of the 3 world components of inner variable k, or -1 when it has none.
  int group_start(int k) const {
    switch (roles_[k]) {
      case ContactVariableRole::ControlPoint: return p_offset_;
      case ContactVariableRole::Vector: return 0;
      case ContactVariableRole::Sharp: return 2;
      default: return -1;
    }
  }

  std::shared_ptr<const ResidualBlock> inner_;
  std::vector<ContactVariableRole> roles_;
  int p_offset_;
  LinkFrame frame_;
  Vec3 x0_;
  Mat3 R0_;
  std::vector<int> sizes_;
};

}  // namespace

std::shared_ptr<ResidualBlock> make_moving_obstacle_block(std::shared_ptr<const ResidualBlock> inner,
                                                          std::vector<ContactVariableRole> roles,
                                                          int p_offset, LinkFrame frame, const Vec7& z0) {
  return std::make_shared<MovingObstacleBlock>(std::move(inner), std::move(roles), p_offset, std::move(frame),
                                               z0);
}

}  // namespace pcr::assembly
