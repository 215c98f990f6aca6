// Knot vectors: validation messages, span search, Greville abscissae, breakpoints.
#define BOOST_TEST_MODULE splines
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>

#include "pcr/splines/knot_vector.hpp"
#include "splines/reference_basis.hpp"

using pcr::KnotVector;
using pcr_test::throws_input_error_naming;

BOOST_AUTO_TEST_CASE(invalid_knot_vectors_are_rejected_with_the_offending_value) {
  // Decreasing knots: both values and the index are named.
  BOOST_TEST(throws_input_error_naming(
      [] {
        KnotVector(1, {0, 0, 0.6, 0.4, 1, 1});
      },
      {"decrease", "0.6", "0.4", "3"}));
  // Wrong end multiplicities (too few and too many copies of 0 or 1).
  BOOST_TEST(throws_input_error_naming(
      [] {
        KnotVector(2, {0, 0, 0.5, 1, 1, 1});
      },
      {"first knot", "multiplicity 2"}));
  BOOST_TEST(throws_input_error_naming(
      [] {
        KnotVector(2, {0, 0, 0, 0, 0.5, 1, 1, 1});
      },
      {"first knot", "multiplicity 4"}));
  BOOST_TEST(throws_input_error_naming(
      [] {
        KnotVector(2, {0, 0, 0, 0.5, 1, 1});
      },
      {"last knot", "multiplicity 2"}));
  // End values other than 0 and 1.
  BOOST_TEST(throws_input_error_naming([] { KnotVector(1, {-0.5, -0.5, 1, 1}); }, {"first knot", "-0.5"}));
  BOOST_TEST(throws_input_error_naming([] { KnotVector(1, {0, 0, 2, 2}); }, {"last knot", "2"}));
  // Degree 0 and negative degrees.
  BOOST_TEST(throws_input_error_naming([] { KnotVector(0, {0, 1}); }, {"degree = 0"}));
  BOOST_TEST(throws_input_error_naming([] { KnotVector(-2, {0, 1}); }, {"degree = -2"}));
  BOOST_TEST(throws_input_error_naming([] { KnotVector::open_uniform(0, 3); }, {"degree = 0"}));
  BOOST_TEST(throws_input_error_naming([] { KnotVector::open_uniform(2, 0); }, {"num_elements = 0"}));
  // Too few knots for the degree.
  BOOST_TEST(throws_input_error_naming([] { KnotVector(2, {0, 0, 0, 1, 1}); }, {"5 knots", "6"}));
  // Interior knot repeated more than degree times.
  BOOST_TEST(throws_input_error_naming(
      [] {
        KnotVector(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1});
      },
      {"interior knot 0.5", "multiplicity 3"}));
  // Non-finite knots.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_TEST(throws_input_error_naming([nan] { KnotVector(1, {0, 0, nan, 1, 1}); }, {"knot[2]", "nan"}));
  const double inf = std::numeric_limits<double>::infinity();
  BOOST_TEST(throws_input_error_naming([inf] { KnotVector(1, {0, 0, 0.5, 1, inf}); }, {"knot[4]", "inf"}));
}

BOOST_AUTO_TEST_CASE(parameters_outside_the_domain_are_rejected) {
  const KnotVector knots = KnotVector::open_uniform(3, 4);
  BOOST_TEST(throws_input_error_naming([&] { knots.find_span(1.5); }, {"u = 1.5"}));
  BOOST_TEST(throws_input_error_naming([&] { knots.find_span(-0.25); }, {"u = -0.25"}));
  BOOST_TEST(throws_input_error_naming([&] { knots.find_span(std::nan("")); }, {"u = nan"}));
  BOOST_TEST(throws_input_error_naming([&] { knots.find_span(1.0 + 1e-12); }, {"outside [0, 1]"}));
}

BOOST_AUTO_TEST_CASE(sizes_of_an_open_uniform_knot_vector) {
  const KnotVector knots = KnotVector::open_uniform(3, 4);
  const std::vector<double> expected{0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1};
  BOOST_TEST(knots.knots() == expected, boost::test_tools::per_element());
  BOOST_TEST(knots.degree() == 3);
  BOOST_TEST(knots.num_basis() == 7);
  BOOST_TEST(knots.num_elements() == 4);
  BOOST_TEST(knots.multiplicity(0.5) == 1);
  BOOST_TEST(knots.multiplicity(1.0) == 4);
  BOOST_TEST(knots.multiplicity(0.3) == 0);
  const KnotVector single = KnotVector::open_uniform(2, 1);
  BOOST_TEST(single.num_basis() == 3);
  BOOST_TEST(single.num_elements() == 1);
}

BOOST_AUTO_TEST_CASE(span_search_finds_the_half_open_span) {
  // Repeated interior knot 0.5 (indices 3, 4) and simple knot 0.75 (index 5), degree 2: n = 6.
  const KnotVector knots(2, {0, 0, 0, 0.5, 0.5, 0.75, 1, 1, 1});
  BOOST_TEST(knots.num_basis() == 6);
  BOOST_TEST(knots.num_elements() == 3);
  BOOST_TEST(knots.find_span(0.0) == 2);
  BOOST_TEST(knots.find_span(0.49) == 2);
  BOOST_TEST(knots.find_span(0.5) == 4);  // the last copy of a repeated knot starts the next span
  BOOST_TEST(knots.find_span(0.7) == 4);
  BOOST_TEST(knots.find_span(0.75) == 5);
  BOOST_TEST(knots.find_span(1.0) == 5);  // u = 1 belongs to the last non-empty span
  // Exhaustive check against the definition xi_i <= u < xi_{i+1} on a fine grid.
  const std::vector<double>& xi = knots.knots();
  for (int k = 0; k < 1000; ++k) {
    const double u = k / 1000.0;
    const int span = knots.find_span(u);
    BOOST_TEST((xi[span] <= u && u < xi[span + 1]));
  }
}

BOOST_AUTO_TEST_CASE(greville_abscissae_and_breakpoints_of_known_knot_vectors) {
  // Degree 2, knots {0,0,0,0.5,1,1,1}: tau = (0+0)/2, (0+0.5)/2, (0.5+1)/2, (1+1)/2.
  const KnotVector quadratic(2, {0, 0, 0, 0.5, 1, 1, 1});
  const std::vector<double> tau2{0.0, 0.25, 0.75, 1.0};
  BOOST_TEST(quadratic.greville() == tau2, boost::test_tools::per_element());
  // Degree 3, 4 uniform elements: tau = 0, 1/12, 1/4, 1/2, 3/4, 11/12, 1 (sums of three knots / 3).
  const std::vector<double> tau3 = KnotVector::open_uniform(3, 4).greville();
  const std::vector<double> expected3{0.0, 1.0 / 12, 0.25, 0.5, 0.75, 11.0 / 12, 1.0};
  BOOST_TEST(tau3.size() == expected3.size());
  // Sums of three doubles divided by 3: a few rounding errors of size eps/2.
  for (std::size_t i = 0; i < tau3.size(); ++i) BOOST_TEST(std::abs(tau3[i] - expected3[i]) < 1e-15);
  const std::vector<double> breaks = KnotVector(2, {0, 0, 0, 0.5, 0.5, 0.75, 1, 1, 1}).breakpoints();
  const std::vector<double> expected_breaks{0.0, 0.5, 0.75, 1.0};
  BOOST_TEST(breaks == expected_breaks, boost::test_tools::per_element());
}
