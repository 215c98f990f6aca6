// Spline curves: the seed's sample curve, exact circles as NURBS, derivatives, and refinement (knot
// insertion, uniform h-refinement, degree elevation) that must leave the curve unchanged.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "pcr/splines/spline_curve.hpp"
#include "splines/reference_basis.hpp"

using namespace pcr;
using pcr_test::cox_de_boor;
using pcr_test::throws_input_error_naming;

namespace {

std::vector<double> grid(int count) {
  std::vector<double> u;
  for (int k = 0; k < count; ++k) u.push_back(k / (count - 1.0));
  return u;
}

// Full circle of radius 1 as a degree-2 NURBS (The NURBS Book ex. 7.2, 9 points, 4 arcs of 90 degrees).
SplineCurve full_circle() {
  const double s = std::sqrt(2.0) / 2.0;
  MatX P(2, 9);
  P << 1, 1, 0, -1, -1, -1, 0, 1, 1,  //
      0, 1, 1, 1, 0, -1, -1, -1, 0;
  VecX w(9);
  w << 1, s, 1, s, 1, s, 1, s, 1;
  return SplineCurve(KnotVector(2, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}), P, w);
}

SplineCurve quarter_circle() {
  MatX P(2, 3);
  P << 1, 1, 0,  //
      0, 1, 1;
  return SplineCurve(KnotVector(2, {0, 0, 0, 1, 1, 1}), P, Eigen::Vector3d(1, std::sqrt(2.0) / 2.0, 1));
}

// Random curve in R^3 on non-uniform knots with a double knot (p >= 2), coordinates in [-1, 1], weights
// in [0.5, 2] when rational.
SplineCurve random_curve(int p, bool rational, std::mt19937& rng) {
  std::vector<double> xi(p + 1, 0.0);
  xi.push_back(0.2);
  xi.insert(xi.end(), std::min(2, p), 0.45);
  xi.push_back(0.8);
  xi.insert(xi.end(), p + 1, 1.0);
  KnotVector knots(p, xi);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0), weight(0.5, 2.0);
  MatX P(3, knots.num_basis());
  for (Eigen::Index i = 0; i < P.size(); ++i) P(i) = coordinate(rng);
  VecX w;
  if (rational) {
    w.resize(knots.num_basis());
    for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = weight(rng);
  }
  return SplineCurve(knots, P, w);
}

double max_distance(const SplineCurve& a, const SplineCurve& b) {
  double error = 0.0;
  for (double u : grid(1001)) error = std::max(error, (a.evaluate(u) - b.evaluate(u)).cwiseAbs().maxCoeff());
  return error;
}

// Refined curves are evaluated from other control points: both sides carry a few eps of rounding
// relative to the coordinates (|P| <= 1), so 1e-14 (the task's requirement) is ~20 eps.
constexpr double kSameCurve = 1e-14;

}  // namespace

BOOST_AUTO_TEST_CASE(seed_sample_curve_matches_cox_de_boor) {
  MatX P(2, 6);
  P << 0, 0.3, 0.3, 0.5, 0.9, 0.8,  //
      0, 0.25, 0.7, 0.8, 0.3, 1;
  const SplineCurve curve(KnotVector::open_uniform(3, 3), P);
  BOOST_TEST(curve.dimension() == 2);
  BOOST_TEST(!curve.is_rational());
  for (double u : grid(101)) {
    Eigen::Vector2d reference = Eigen::Vector2d::Zero(), tangent = Eigen::Vector2d::Zero();
    for (int i = 0; i < 6; ++i) {
      reference += cox_de_boor(curve.knots().knots(), i, 3, u) * P.col(i);
      tangent += cox_de_boor(curve.knots().knots(), i, 3, u, 1) * P.col(i);
    }
    // Sums of 4 products with coordinates <= 1: a few eps.
    BOOST_TEST((curve.evaluate(u) - reference).cwiseAbs().maxCoeff() < 1e-15);
    // First derivatives ~ p / h = 9 times larger: 1e-14.
    BOOST_TEST((curve.derivatives(u, 1).col(1) - tangent).cwiseAbs().maxCoeff() < 1e-14);
  }
  // Open knot vector: the curve interpolates the end control points (exactly: N_0(0) = N_5(1) = 1).
  BOOST_TEST((curve.evaluate(0.0) - P.col(0)).norm() == 0.0);
  BOOST_TEST((curve.evaluate(1.0) - P.col(5)).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(nurbs_circles_have_exact_radius) {
  for (const SplineCurve& circle : {quarter_circle(), full_circle()}) {
    BOOST_TEST(circle.is_rational());
    double radius_error = 0.0, tangent_error = 0.0, curvature_error = 0.0;
    for (double u : grid(1000)) {
      const MatX C = circle.derivatives(u, 2);
      radius_error = std::max(radius_error, std::abs(C.col(0).norm() - 1.0));
      // |C|^2 = 1 implies C.C' = 0 and C'.C' + C.C'' = 0 (analytic identities of a circle).
      tangent_error = std::max(tangent_error, std::abs(C.col(0).dot(C.col(1))));
      curvature_error = std::max(curvature_error, std::abs(C.col(1).squaredNorm() + C.col(0).dot(C.col(2))));
    }
    // Task requirement; rounding of a rational quadratic with O(1) coordinates is a few eps.
    BOOST_TEST(radius_error < 1e-14);
    // The full circle runs 4 quarter arcs per unit of u: |C'| <= 6.7 and |C''| <= 44 (|C'|^2 + |C.C''|
    // <= 90); rounding is a few eps of those sizes, so 1e-13 (~70 eps) and 2e-13 (~10 eps * 90).
    BOOST_TEST(tangent_error < 1e-13);
    BOOST_TEST(curvature_error < 2e-13);
  }
  // The full circle passes through the axis points at the knots.
  const SplineCurve circle = full_circle();
  BOOST_TEST((circle.evaluate(0.25) - Eigen::Vector2d(0, 1)).norm() < 1e-15);  // exact control point
  BOOST_TEST((circle.evaluate(0.5) - Eigen::Vector2d(-1, 0)).norm() < 1e-15);
  BOOST_TEST((circle.evaluate(0.75) - Eigen::Vector2d(0, -1)).norm() < 1e-15);
  // Quarter circle midpoint is at 45 degrees.
  const VecX mid = quarter_circle().evaluate(0.5);
  BOOST_TEST(std::abs(mid[0] - mid[1]) < 1e-15);
}

BOOST_AUTO_TEST_CASE(curve_derivatives_match_central_differences) {
  std::mt19937 rng(5);
  const double h = 1e-6;
  for (int p = 2; p <= 5; ++p)
    for (bool rational : {false, true}) {
      const SplineCurve curve = random_curve(p, rational, rng);
      for (double u : {0.1, 0.3, 0.6, 0.93}) {
        const MatX C = curve.derivatives(u, 3);
        const MatX plus = curve.derivatives(u + h, 2), minus = curve.derivatives(u - h, 2);
        for (int d = 1; d <= 3; ++d) {
          // Truncation h^2/6 |C^(d+2)| and round-off ~4 eps |C^(d-1)| / h. With |P| <= 1, elements >= 0.2
          // and weight ratios <= 4, each derivative gains a factor below 20p, so |C^(k)| < (20p)^k and the
          // error is below (h^2/6 (20p)^2 + 4 eps / h) (20p)^d; tolerance: 5 times that.
          const double eps = std::numeric_limits<double>::epsilon();
          const double tol = 5 * (h * h / 6 * std::pow(20.0 * p, 2) + 4 * eps / h) * std::pow(20.0 * p, d);
          const VecX fd = (plus.col(d - 1) - minus.col(d - 1)) / (2 * h);
          BOOST_TEST((C.col(d) - fd).cwiseAbs().maxCoeff() < tol,
                     "p = " << p << ", u = " << u << ", d = " << d);
        }
      }
    }
}

BOOST_AUTO_TEST_CASE(knot_insertion_keeps_the_curve) {
  std::mt19937 rng(1);
  for (int p = 1; p <= 8; ++p)
    for (bool rational : {false, true}) {
      const SplineCurve curve = random_curve(p, rational, rng);
      const int n = curve.knots().num_basis();
      // A new knot, once and up to p times.
      for (int times = 1; times <= p; ++times) {
        const SplineCurve refined = curve.with_inserted_knot(0.6, times);
        BOOST_TEST(refined.knots().num_basis() == n + times);
        BOOST_TEST(refined.knots().multiplicity(0.6) == times);
        BOOST_TEST(refined.is_rational() == rational);
        BOOST_TEST(max_distance(curve, refined) < kSameCurve, "p = " << p << ", times = " << times);
      }
      // An existing knot (0.45 has multiplicity min(2, p)) raised to multiplicity p.
      const int s = curve.knots().multiplicity(0.45);
      if (s < p) {
        const SplineCurve refined = curve.with_inserted_knot(0.45, p - s);
        BOOST_TEST(refined.knots().multiplicity(0.45) == p);
        BOOST_TEST(max_distance(curve, refined) < kSameCurve);
      }
      BOOST_TEST(
          throws_input_error_naming([&] { curve.with_inserted_knot(0.45, p - s + 1); }, {"0.45", "times"}));
      BOOST_TEST(throws_input_error_naming([&] { curve.with_inserted_knot(1.0); }, {"u = 1"}));
    }
  // The circle stays a circle (homogeneous coordinates).
  const SplineCurve circle = full_circle().with_inserted_knot(0.1).with_inserted_knot(0.6, 2);
  for (double u : grid(1000)) BOOST_TEST(std::abs(circle.evaluate(u).norm() - 1.0) < 1e-14);
}

BOOST_AUTO_TEST_CASE(uniform_refinement_keeps_the_curve) {
  std::mt19937 rng(2);
  for (int p = 1; p <= 8; ++p)
    for (bool rational : {false, true}) {
      const SplineCurve curve = random_curve(p, rational, rng);
      const int elements = curve.knots().num_elements();
      for (int parts = 1; parts <= 3; ++parts) {
        const SplineCurve refined = curve.with_uniform_refinement(parts);
        BOOST_TEST(refined.knots().num_elements() == elements * parts);
        BOOST_TEST(refined.knots().num_basis() == curve.knots().num_basis() + elements * (parts - 1));
        BOOST_TEST(max_distance(curve, refined) < kSameCurve, "p = " << p << ", parts = " << parts);
      }
      BOOST_TEST(throws_input_error_naming([&] { curve.with_uniform_refinement(0); }, {"parts = 0"}));
    }
}

BOOST_AUTO_TEST_CASE(degree_elevation_keeps_the_curve) {
  std::mt19937 rng(3);
  for (int p = 1; p <= 8; ++p)
    for (bool rational : {false, true}) {
      const SplineCurve curve = random_curve(p, rational, rng);
      const KnotVector& knots = curve.knots();
      for (int times = 1; times <= 2; ++times) {
        const SplineCurve elevated = curve.with_elevated_degree(times);
        BOOST_TEST(elevated.knots().degree() == p + times);
        BOOST_TEST(elevated.knots().num_basis() == knots.num_basis() + times * knots.num_elements());
        // Every distinct knot gains `times` copies (continuity is kept).
        for (double x : knots.breakpoints())
          BOOST_TEST(elevated.knots().multiplicity(x) == knots.multiplicity(x) + times);
        BOOST_TEST(elevated.is_rational() == rational);
        BOOST_TEST(max_distance(curve, elevated) < kSameCurve, "p = " << p << ", times = " << times);
      }
    }
  // Elevated circles and the seed's sample curve; a single Bezier segment (no interior knots).
  const SplineCurve circle = full_circle().with_elevated_degree(2);
  for (double u : grid(1000)) BOOST_TEST(std::abs(circle.evaluate(u).norm() - 1.0) < 1e-14);
  const SplineCurve quarter = quarter_circle();
  BOOST_TEST(max_distance(quarter, quarter.with_elevated_degree(1)) < kSameCurve);
  BOOST_TEST(max_distance(quarter, quarter.with_elevated_degree(2)) < kSameCurve);
  BOOST_TEST(throws_input_error_naming([&] { quarter.with_elevated_degree(-1); }, {"times = -1"}));
}

BOOST_AUTO_TEST_CASE(invalid_curves_are_rejected) {
  const KnotVector knots = KnotVector::open_uniform(2, 2);  // 4 basis functions
  BOOST_TEST(throws_input_error_naming([&] { SplineCurve(knots, MatX::Zero(2, 5)); }, {"2 x 5", "4"}));
  BOOST_TEST(
      throws_input_error_naming([&] { SplineCurve(knots, MatX::Zero(2, 4), VecX::Ones(3)); }, {"3 weights"}));
  VecX w = VecX::Ones(4);
  w[3] = 0.0;
  BOOST_TEST(throws_input_error_naming([&] { SplineCurve(knots, MatX::Zero(2, 4), w); }, {"weight[3] = 0"}));
  MatX P = MatX::Zero(2, 4);
  P(1, 2) = std::nan("");
  BOOST_TEST(throws_input_error_naming([&] { SplineCurve(knots, P); }, {"non-finite"}));
  BOOST_TEST(
      throws_input_error_naming([&] { SplineCurve(knots, MatX::Zero(2, 4)).evaluate(2.0); }, {"u = 2"}));
}
