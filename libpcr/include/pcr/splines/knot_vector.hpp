#pragma once
// Open knot vectors on [0, 1] for B-spline/NURBS bases (The NURBS Book, Piegl & Tiller, ch. 2).
#include <vector>

namespace pcr {

/// An open (clamped) knot vector xi_0 <= ... <= xi_{n+p} on [0, 1] for degree p: the end knots 0 and 1
/// have multiplicity exactly p+1, interior knots at most p (so the basis is at least C^0).
class KnotVector {
 public:
  /// Validates: degree >= 1; knots non-decreasing, finite; first knot 0 and last knot 1 each with
  /// multiplicity exactly degree+1 (open); interior multiplicity <= degree; at least 2(degree+1) knots.
  /// Throws pcr::InputError with a message naming the problem and the offending value/index.
  KnotVector(int degree, std::vector<double> knots);
  /// Open uniform knot vector on [0,1] with num_elements >= 1 equal elements.
  static KnotVector open_uniform(int degree, int num_elements);

  int degree() const { return degree_; }
  /// n = knots.size() - degree - 1.
  int num_basis() const { return static_cast<int>(knots_.size()) - degree_ - 1; }
  /// Number of non-empty knot spans.
  int num_elements() const { return num_elements_; }
  const std::vector<double>& knots() const { return knots_; }
  /// Multiplicity of the value u among the knots (0 when u is not a knot).
  int multiplicity(double u) const;

  /// Span index i with xi_i <= u < xi_{i+1} (The NURBS Book A2.1, binary search); u = 1 maps to the last
  /// non-empty span; u outside [0,1] (or NaN) throws InputError.
  int find_span(double u) const;
  /// Greville abscissae tau_i = (xi_{i+1} + ... + xi_{i+p}) / p, i = 0..n-1 (tau_0 = 0, tau_{n-1} = 1).
  std::vector<double> greville() const;
  /// Distinct knot values (element boundaries) 0 = u_0 < ... < u_E = 1.
  std::vector<double> breakpoints() const;

 private:
  int degree_;
  std::vector<double> knots_;
  int num_elements_ = 0;
};

}  // namespace pcr
