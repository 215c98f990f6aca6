#pragma once
// B-spline and NURBS curves with knot insertion and degree elevation (The NURBS Book, ch. 3-5).
#include "pcr/core/types.hpp"
#include "pcr/splines/knot_vector.hpp"

namespace pcr {

/// B-spline curve (weights empty) or NURBS curve in R^d; control_points is d x num_basis.
/// C(u) = sum_i N_i(u) w_i P_i / sum_i N_i(u) w_i (w_i = 1 for a B-spline).
class SplineCurve {
 public:
  /// Throws InputError if control_points is not d x num_basis (d >= 1), weights is neither empty nor of
  /// size num_basis, a weight is not > 0, or a coordinate is not finite.
  SplineCurve(KnotVector knots, MatX control_points, VecX weights = VecX());

  const KnotVector& knots() const { return knots_; }
  const MatX& control_points() const { return control_points_; }
  const VecX& weights() const { return weights_; }
  bool is_rational() const { return weights_.size() > 0; }
  int dimension() const { return static_cast<int>(control_points_.rows()); }

  VecX evaluate(double u) const;
  /// d x (max_derivative+1): column k is the k-th derivative with respect to u.
  MatX derivatives(double u, int max_derivative) const;

  /// Knot insertion (The NURBS Book A5.1; in homogeneous coordinates for NURBS): same curve, more control
  /// points. Requires 0 < u < 1, times >= 0 and multiplicity(u) + times <= degree.
  SplineCurve with_inserted_knot(double u, int times = 1) const;
  /// Degree elevation by `times` >= 0 (The NURBS Book A5.9, homogeneous coordinates for NURBS): same
  /// curve; every knot multiplicity grows by `times`.
  SplineCurve with_elevated_degree(int times = 1) const;
  /// Inserts knots so that every element is split into `parts` >= 1 equal parts (h-refinement).
  SplineCurve with_uniform_refinement(int parts) const;

 private:
  /// (d+1) x n control points [w_i P_i; w_i] (NURBS) or the d x n control points (B-spline).
  MatX homogeneous_points() const;
  /// Inverse of homogeneous_points() for a curve of the same kind.
  SplineCurve from_homogeneous(KnotVector knots, const MatX& points) const;

  KnotVector knots_;
  MatX control_points_;
  VecX weights_;
};

}  // namespace pcr
