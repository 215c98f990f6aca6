#pragma once
// The quantities at one end of a collocation rod — y = [p (3), q (4), n (3), m (3)] in the world
// frame — as functions of the rod's variable blocks, with their Jacobians. Coupling and balance
// blocks of a robot are built on top of this (robots/): they never need to know the formulation.
// Mixed form: y is the end control point itself (open knot vector: the spline interpolates its end
// control points). Condensed form: p, q from the end control point, n and m = h - (p - c) x n from
// the rod's wrench block [n, h]; with distributed loads the tip's n, m also read L and the integral of p:
// the end control point's running integral T, or every control point (collocation_rod.hpp). Primal form: p, q
// from the end control point, n = R K_SE (eps - eps0) and m = R K_BT (kappa - kappa0) from the p+1 end
// control points and L. Drawn rods (drawn_rod.hpp): n, m are the effective N, M of the unknowns (the
// primal form with the effective constants), so robot couplings balance N, M at a guide.
#include <vector>

#include "pcr/rods/collocation_rod.hpp"

namespace pcr {

using RodEndVector = Eigen::Matrix<double, 13, 1>;

class RodEndEvaluator {
 public:
  /// at_tip: the s = L end, else s = 0.
  RodEndEvaluator(const CollocationRod& rod, const RodVariables& variables, bool at_tip);

  /// Variable blocks y depends on (control points, and L for the primal form).
  const std::vector<VariableId>& variables() const { return variables_; }
  bool at_tip() const { return at_tip_; }

  /// values[k]: values of variables()[k]. jacobians: null for values only, else (*jacobians)[k] is
  /// set to the 13 x size(k) matrix dy / d(block k).
  void evaluate(const double* const* values, RodEndVector& y, std::vector<MatX>* jacobians) const;

 private:
  void evaluate_mixed(const double* const* values, RodEndVector& y, std::vector<MatX>* jacobians) const;
  void evaluate_condensed_with_loads(const double* const* values, RodEndVector& y,
                                     std::vector<MatX>* jacobians) const;
  void evaluate_condensed(const double* const* values, RodEndVector& y, std::vector<MatX>* jacobians) const;
  void evaluate_primal(const double* const* values, RodEndVector& y, std::vector<MatX>* jacobians) const;

  bool at_tip_;
  bool mixed_;
  bool condensed_;
  int cp_size_;
  int count_;  ///< control points touched
  std::vector<VariableId> variables_;
  std::vector<double> value_basis_, derivative_basis_;  ///< N_i and N_i' at the end
  Vec3 k_se_, k_bt_, eps0_, kappa0_;
  Vec3 moment_point_ = Vec3::Zero();  ///< condensed form
  bool loads_ = false;  ///< condensed form with distributed loads, tip: reads the integral of p and L
  int integral_ = -1;   ///< component of T in the control points (running integrals), else -1
  std::vector<double> integral_weights_;  ///< integral_0^1 N_j of the control points read
  Vec3 f_ = Vec3::Zero(), l_ = Vec3::Zero();
};

}  // namespace pcr
