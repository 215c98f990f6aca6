// Unit-quaternion rows of a rod, several as one residual block (unit_quaternion_rows.hpp).
#include "unit_quaternion_rows.hpp"

#include <algorithm>

#include <Eigen/Core>

#include "pcr/core/error.hpp"

namespace pcr::collocation {

namespace {

class UnitQuaternionRows final : public ResidualBlock {
 public:
  UnitQuaternionRows(const std::string& name, std::vector<int> control_points, int cp_size, int q_offset,
                     std::vector<PointBasis> bases)
      : ResidualBlock("rod.unit_quaternion", name, static_cast<int>(bases.size()), std::move(control_points)),
        cp_size_(cp_size),
        q_(q_offset),
        bases_(std::move(bases)) {
    const int n = static_cast<int>(variables().size());
    require(q_ >= 0 && q_ + 4 <= cp_size_, "unit quaternion rows '", this->name(), "': Q at ", q_, " of ",
            cp_size_);
    for (const PointBasis& b : bases_)
      require(
          b.first >= 0 && b.count >= 1 && b.first + b.count <= n && static_cast<int>(b.B.size()) == b.count,
          "unit quaternion rows '", this->name(), "': basis from ", b.first, " (", b.count, " functions) of ",
          n, " control points");
  }

  int expected_variable_size(int) const override { return cp_size_; }

  bool structural_nonzero(int k, int row, int column) const override {
    return column >= q_ && column < q_ + 4 && basis_value(row, k) != 0.0;
  }

  void structural_mask(int k, int size, char* mask) const override {
    std::fill(mask, mask + num_rows() * size, char{0});
    for (int row = 0; row < num_rows(); ++row)
      if (basis_value(row, k) != 0.0)
        for (int c = q_; c < q_ + 4; ++c) mask[row * size + c] = 1;
  }

  // r_j = |q|^2 - 1, dr_j / dQ_i = 2 q^T B_i(tau_j); q summed as PointBlock's gather sums (the first term,
  // then the others added in order).
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    if (jacobians != nullptr)
      for (size_t k = 0; k < variables().size(); ++k)
        if (jacobians[k] != nullptr) std::fill(jacobians[k], jacobians[k] + num_rows() * cp_size_, 0.0);
    for (int row = 0; row < num_rows(); ++row) {
      const PointBasis& b = bases_[row];
      Eigen::Vector4d q = b.B[0][0] * Eigen::Map<const Eigen::Vector4d>(values[b.first] + q_);
      for (int i = 1; i < b.count; ++i)
        q += b.B[i][0] * Eigen::Map<const Eigen::Vector4d>(values[b.first + i] + q_);
      residual[row] = q.squaredNorm() - 1.0;
      if (jacobians == nullptr) continue;
      for (int i = 0; i < b.count; ++i) {
        double* J = jacobians[b.first + i];
        if (J == nullptr || b.B[i][0] == 0.0) continue;
        for (int c = 0; c < 4; ++c) J[row * cp_size_ + q_ + c] = (2.0 * q[c]) * b.B[i][0];
      }
    }
  }

 private:
  double basis_value(int row, int k) const {
    const PointBasis& b = bases_[row];
    const int i = k - b.first;
    return i >= 0 && i < b.count ? b.B[i][0] : 0.0;
  }

  int cp_size_, q_;
  std::vector<PointBasis> bases_;
};

}  // namespace

std::shared_ptr<const ResidualBlock> make_unit_quaternion_rows(const std::string& name,
                                                               std::vector<int> control_points, int cp_size,
                                                               int q_offset, std::vector<PointBasis> bases) {
  return std::make_shared<UnitQuaternionRows>(name, std::move(control_points), cp_size, q_offset,
                                              std::move(bases));
}

}  // namespace pcr::collocation
