#pragma once
// IK objective: f = 1/2 sum_i ((u_i - r_i) / scale_i)^2, the distance of the inputs u to reference
// inputs r (a fixed variable block, so the reference can change between solves).
#include <vector>

#include "pcr/solve/residual_block.hpp"

namespace pcr::kinematics {

class InputDistance final : public ObjectiveTerm {
 public:
  /// variables: one size-1 block per input, then the reference block (size = number of inputs).
  InputDistance(std::vector<VariableId> inputs, VariableId reference, VecX scales)
      : ObjectiveTerm("ik.input_distance", with(inputs, reference)), n_(static_cast<int>(inputs.size())),
        scales_(std::move(scales)) {}

  double evaluate(const double* const* values, double* const* gradients) const override {
    double f = 0.0;
    for (int i = 0; i < n_; ++i) {
      const double d = (values[i][0] - values[n_][i]) / scales_[i];
      f += 0.5 * d * d;
      if (gradients && gradients[i]) gradients[i][0] = d / scales_[i];
    }
    if (gradients && gradients[n_])
      for (int i = 0; i < n_; ++i) gradients[n_][i] = -(values[i][0] - values[n_][i]) / (scales_[i] * scales_[i]);
    return f;
  }

 private:
  static std::vector<VariableId> with(std::vector<VariableId> v, VariableId r) {
    v.push_back(r);
    return v;
  }
  int n_;
  VecX scales_;
};

}  // namespace pcr::kinematics
