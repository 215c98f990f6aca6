// Start points along a path (robots/src/kinematics/path_predictor.hpp): polynomial extrapolation is exact
// for solutions that are polynomials of the arc length of the same degree (two points: linear, three:
// quadratic, four: cubic), falls back to the last solution where the path turns or reverses.
#define BOOST_TEST_MODULE path_predictor
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "../../robots/src/kinematics/path_predictor.hpp"

using namespace pcr;
using pcr::kinematics::PathPredictor;

namespace {

/// A straight path z(s) = z0 + s d (|d| = 1) and a solution x(s) = c0 + c1 s + c2 s^2 + c3 s^3.
struct Path {
  VecX z0 = (VecX(3) << 0.1, -0.2, 0.3).finished();
  VecX d = (VecX(3) << 2.0, 1.0, 2.0).finished() / 3.0;
  VecX c0 = (VecX(2) << 1.0, -1.0).finished();
  VecX c1 = (VecX(2) << 0.5, 2.0).finished();
  VecX c2 = (VecX(2) << -3.0, 0.7).finished();
  VecX c3 = VecX::Zero(2);
  VecX z(double s) const { return z0 + s * d; }
  VecX x(double s) const { return c0 + s * c1 + s * s * c2 + s * s * s * c3; }
};

double error_at(const Path& p, const PathPredictor& predictor, double s_last, double s_new) {
  return (predictor.predict(p.x(s_last), p.z(s_new)) - p.x(s_new)).lpNorm<Eigen::Infinity>();
}

}  // namespace

BOOST_AUTO_TEST_CASE(three_points_extrapolate_a_quadratic_exactly_on_uneven_steps) {
  Path p;
  PathPredictor predictor;
  const double s[] = {0.0, 0.3, 0.45};  // steps 0.3 and 0.15, next step 0.2
  for (double si : s) predictor.accept(p.x(si), p.z(si));
  // Exact up to round-off of the weights (values of order 1; 1e-12 leaves a margin of ~1e3 eps).
  BOOST_TEST(error_at(p, predictor, 0.45, 0.65) < 1e-12);
}

BOOST_AUTO_TEST_CASE(four_points_extrapolate_a_cubic_exactly_three_points_do_not) {
  Path p;
  p.c3 = (VecX(2) << 2.0, -1.5).finished();
  PathPredictor quadratic, cubic;
  const double s[] = {0.0, 0.3, 0.45, 0.7};  // steps 0.3, 0.15 and 0.25, next step 0.2
  for (int k = 1; k < 4; ++k) quadratic.accept(p.x(s[k]), p.z(s[k]));
  for (double si : s) cubic.accept(p.x(si), p.z(si));
  BOOST_TEST(error_at(p, cubic, 0.7, 0.9) < 1e-12);  // round-off of weights of order 10 on values of order 1
  // The quadratic through s = 0.3, 0.45, 0.7 misses c3 (s - 0.3)(s - 0.45)(s - 0.7) at s = 0.9:
  // |c3|max * 0.6 * 0.45 * 0.2 = 0.108.
  BOOST_TEST(std::abs(error_at(p, quadratic, 0.7, 0.9) - 0.108) < 1e-12);
}

BOOST_AUTO_TEST_CASE(only_the_last_points_are_used) {
  // A cubic on the last kMaxPoints points, preceded by points of another curve: the prediction stays
  // exact (the order, adapted to the accepted points, ends at four or more: the cubic's points are
  // predicted exactly from four on, and worse from three).
  Path p;
  p.c3 = (VecX(2) << 2.0, -1.5).finished();
  Path other = p;
  other.c2 *= -5.0;
  PathPredictor predictor;
  for (double si : {-0.4, -0.2}) predictor.accept(other.x(si), other.z(si));
  static_assert(PathPredictor::kMaxPoints == 6, "six points of the cubic below");
  for (double si : {0.0, 0.3, 0.45, 0.7, 0.9, 1.0}) predictor.accept(p.x(si), p.z(si));
  BOOST_TEST(predictor.order() >= 4);
  BOOST_TEST(error_at(p, predictor, 1.0, 1.2) < 1e-12);
}

BOOST_AUTO_TEST_CASE(two_points_extrapolate_a_line_exactly_but_not_a_parabola) {
  Path line;
  line.c2.setZero();
  PathPredictor predictor;
  predictor.accept(line.x(0.0), line.z(0.0));
  predictor.accept(line.x(0.3), line.z(0.3));
  BOOST_TEST(error_at(line, predictor, 0.3, 0.5) < 1e-12);

  Path parabola;
  PathPredictor linear_only;
  linear_only.accept(parabola.x(0.0), parabola.z(0.0));
  linear_only.accept(parabola.x(0.3), parabola.z(0.3));
  // Linear extrapolation misses c2 s (s - 0.3) at s = 0.5: |c2|max * 0.5 * 0.2 = 0.3.
  BOOST_TEST(std::abs(error_at(parabola, linear_only, 0.3, 0.5) - 0.3) < 1e-12);
}

BOOST_AUTO_TEST_CASE(a_turn_or_a_jump_starts_from_the_last_solution) {
  Path p;
  PathPredictor predictor;
  for (double si : {0.0, 0.3, 0.45}) predictor.accept(p.x(si), p.z(si));
  const VecX last = p.x(0.45);
  const VecX sideways = p.z(0.45) + 0.1 * (VecX(3) << 1.0, -2.0, 0.0).finished() / std::sqrt(5.0);
  BOOST_TEST((predictor.predict(last, sideways) - last).norm() == 0.0);  // at right angles (d . e = 0)
  // A step more than twice the last one is not extrapolated either, forward or back.
  BOOST_TEST((predictor.predict(last, p.z(0.45 + 0.31)) - last).norm() == 0.0);
  BOOST_TEST((predictor.predict(last, p.z(0.45 - 0.31)) - last).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(going_back_along_the_path_interpolates_the_stored_solutions) {
  // Reversal on a cubic: back to s = 0.3 (a stored point, exact), then to 0.2 (inside the stored span:
  // the cubic through 0.0, 0.3, 0.45 and 0.7, exact); 1e-12 as in the tests above.
  Path p;
  p.c3 = (VecX(2) << 2.0, -1.5).finished();
  PathPredictor predictor;
  for (double si : {0.0, 0.3, 0.45, 0.7}) predictor.accept(p.x(si), p.z(si));
  BOOST_TEST(error_at(p, predictor, 0.7, 0.45) < 1e-12);
  BOOST_TEST(error_at(p, predictor, 0.7, 0.6) < 1e-12);
  // After the turn back the revisited point is one node (the newest solution there; the same node twice
  // would make the weights infinite): of the stored points 0.45 (new), 0.7, 0.45 (old, left out), 0.3
  // and 0.0, the cubic takes 0.45, 0.7, 0.3 and 0.0 and is exact again at 0.2. With three of them the
  // quadratic through 0.3, 0.45 and 0.7 would miss c3 (s - 0.3)(s - 0.45)(s - 0.7) at 0.2:
  // |c3|max * 0.1 * 0.25 * 0.5 = 0.025.
  predictor.accept(p.x(0.45), p.z(0.45));
  BOOST_TEST(predictor.order() >= 4);
  BOOST_TEST(error_at(p, predictor, 0.45, 0.2) < 1e-12);
}

BOOST_AUTO_TEST_CASE(after_a_turn_higher_orders_wait_for_points_on_the_new_line) {
  // The older step is at right angles to the last: only the linear extrapolation is used.
  Path p;
  PathPredictor predictor;
  const VecX e = (VecX(3) << 1.0, -2.0, 0.0).finished() / std::sqrt(5.0);
  predictor.accept(p.x(-1.0), p.z(0.0) - 0.2 * e);  // before the turn
  predictor.accept(p.x(0.0), p.z(0.0));
  predictor.accept(p.x(0.3), p.z(0.3));
  const double linear_error = 0.3;  // as in the test above
  BOOST_TEST(std::abs(error_at(p, predictor, 0.3, 0.5) - linear_error) < 1e-12);
  // One more point on the line: the quadratic through the three points on it (exact for this x), and
  // the point before the turn is still left out (with it, the cubic would miss).
  predictor.accept(p.x(0.5), p.z(0.5));
  BOOST_TEST(error_at(p, predictor, 0.5, 0.7) < 1e-12);
}

BOOST_AUTO_TEST_CASE(on_a_circle_the_arc_length_cubic_misses_by_the_fourth_difference) {
  // Parameters on a circle of radius r, equal steps of angle theta, solution x = z (so the start's error
  // is how far the weights' own parameters miss the new point). The cubic in the arc length of the
  // polygon (equal chords: weights -1, 4, -6, 4 on the four stored points) misses by the fourth
  // difference of r e^{i k theta}: r |e^{i theta} - 1|^4 = r (2 sin(theta / 2))^4. The projection on the
  // line of the last step drops the step's part across the line, of order r theta^2.
  const double r = 0.02, theta = 0.065;  // the R5b helix: 2 cm radius, 1.3 mm steps
  auto z = [&](int k) {
    return (VecX(3) << r * std::cos(k * theta), r * std::sin(k * theta), 0.5).finished();
  };
  PathPredictor predictor;
  for (int k = 0; k < 4; ++k) predictor.accept(z(k), z(k));
  const double error = (predictor.predict(z(3), z(4)) - z(4)).norm();
  const double fourth_difference = r * std::pow(2.0 * std::sin(0.5 * theta), 4);  // 3.6e-7 m
  // Round-off: weights of order 6 on values of order 0.5 (1e-15 m), far below the 3.6e-7 m.
  BOOST_TEST(std::abs(error - fourth_difference) < 1e-12);
  BOOST_TEST(fourth_difference < 1e-2 * r * theta * theta);  // 2 orders below the line's miss
}
