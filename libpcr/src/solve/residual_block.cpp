#include "pcr/solve/residual_block.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "pcr/core/error.hpp"

namespace pcr {

ResidualBlock::ResidualBlock(std::string kind, std::string name, int num_rows,
                             std::vector<VariableId> variables)
    : kind_(std::move(kind)), name_(std::move(name)), num_rows_(num_rows), variables_(std::move(variables)) {
  require(num_rows_ >= 1, "residual block '", name_, "': num_rows = ", num_rows_, " < 1");
  require(!variables_.empty(), "residual block '", name_, "': touches no variable block");
  row_lower_ = VecX::Zero(num_rows_);
  row_upper_ = VecX::Zero(num_rows_);
}

void ResidualBlock::set_row_bounds(const VecX& lower, const VecX& upper) {
  require(lower.size() == num_rows_, "residual block '", name_, "': row lower bound size = ", lower.size(),
          ", expected ", num_rows_);
  require(upper.size() == num_rows_, "residual block '", name_, "': row upper bound size = ", upper.size(),
          ", expected ", num_rows_);
  for (int i = 0; i < num_rows_; ++i) {
    require(!std::isnan(lower[i]) && !std::isnan(upper[i]) && lower[i] <= upper[i], "residual block '", name_,
            "': row ", i, " bounds [", lower[i], ", ", upper[i], "] are not an interval");
  }
  row_lower_ = lower;
  row_upper_ = upper;
}

void ResidualBlock::structural_mask(int k, int size, char* mask) const {
  for (int r = 0; r < num_rows_; ++r)
    for (int j = 0; j < size; ++j) mask[r * size + j] = structural_nonzero(k, r, j) ? 1 : 0;
}

void ResidualBlock::evaluate_hessian(const double* const*, const double*, double*) const {
  throw std::logic_error("residual block '" + name_ + "' does not provide a Hessian");
}

ObjectiveTerm::ObjectiveTerm(std::string name, std::vector<VariableId> variables)
    : name_(std::move(name)), variables_(std::move(variables)) {
  require(!variables_.empty(), "objective term '", name_, "': touches no variable block");
}

void ObjectiveTerm::evaluate_hessian(const double* const*, double*) const {
  throw std::logic_error("objective term '" + name_ + "' does not provide a Hessian");
}

}  // namespace pcr
