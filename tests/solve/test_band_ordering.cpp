// The column order of BorderedBlockLu's groups (libpcr/src/solve/band_ordering.hpp) on the pattern of
// a rod in contact: a chain of points with their unknowns interleaved, coupled to their neighbours,
// plus per point a few "contact" columns stored after the whole chain and coupled to that point only.
// The reference order is the interleaved one, written out by hand: point k's unknowns, then its
// contact columns. Solutions against Eigen's dense PartialPivLU (an independent implementation).
//
// Tolerance of the solves: cond(A) n 1e-14, as in test_structured_lu.cpp (Golub & Van Loan, sec. 3.3:
// a backward-stable LU solve errs by about cond(A) n eps; a factor 50 for pivoting within a band).
#define BOOST_TEST_MODULE band_ordering
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "pcr/math/dense_decompositions.hpp"
#include "pcr/solve/bordered_block_lu.hpp"
#include "solve/band_ordering.hpp"

using namespace pcr;

namespace {

constexpr int kPoints = 30, kUnknowns = 4, kContact = 2;  // per point: 4 chain unknowns, 2 contact columns
constexpr int kChain = kPoints * kUnknowns, kSize = kChain + kPoints * kContact;

int chain_column(int point, int k) {
  return point * kUnknowns + k;
}
int contact_column(int point, int k) {
  return kChain + point * kContact + k;
}

/// Rows of point i: kUnknowns rows over the chain unknowns of points i-1 .. i+1 and i's contact
/// columns, then kContact rows over point i's unknowns and its contact columns (a gap and its
/// multiplier). Random entries, a diagonal shift for a regular matrix.
MatX rod_in_contact(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatX A = MatX::Zero(kSize, kSize);
  int row = 0;
  for (int i = 0; i < kPoints; ++i) {
    for (int r = 0; r < kUnknowns; ++r, ++row) {
      for (int j = std::max(0, i - 1); j <= std::min(kPoints - 1, i + 1); ++j)
        for (int k = 0; k < kUnknowns; ++k)
          A(row, chain_column(j, k)) = u(rng) + (j == i && k == r ? 4.0 : 0.0);
      for (int k = 0; k < kContact; ++k) A(row, contact_column(i, k)) = u(rng);
    }
  }
  for (int i = 0; i < kPoints; ++i) {
    for (int r = 0; r < kContact; ++r, ++row) {
      for (int k = 0; k < kUnknowns; ++k) A(row, chain_column(i, k)) = u(rng);
      for (int k = 0; k < kContact; ++k) A(row, contact_column(i, k)) = u(rng) + (k == r ? 4.0 : 0.0);
    }
  }
  return A;
}

std::vector<int> all(int n) {
  std::vector<int> v(n);
  for (int k = 0; k < n; ++k) v[k] = k;
  return v;
}

}  // namespace

BOOST_AUTO_TEST_CASE(contact_columns_join_their_points) {
  std::mt19937 rng(5);
  const MatX A = rod_in_contact(rng);
  const Eigen::SparseMatrix<double> S = A.sparseView();  // compressed (assigned from an expression)
  const std::vector<std::vector<int>> rows = {all(kSize)};
  std::vector<std::vector<int>> columns = {all(kSize)};
  std::vector<int> interleaved;
  for (int i = 0; i < kPoints; ++i) {
    for (int k = 0; k < kUnknowns; ++k) interleaved.push_back(chain_column(i, k));
    for (int k = 0; k < kContact; ++k) interleaved.push_back(contact_column(i, k));
  }
  const BandWidths stored = group_band_widths(S, rows[0], columns[0]);
  const BandWidths by_hand = group_band_widths(S, rows[0], interleaved);
  // Stored order: the last point's contact rows reach from its chain unknowns to the group's end.
  BOOST_TEST(stored.ku >= kPoints * kContact);
  // Interleaved: the rows of a point reach over three points' unknowns and contact columns.
  BOOST_TEST(by_hand.kl + by_hand.ku <= 3 * (kUnknowns + kContact));

  order_columns_for_narrow_band(S, rows, columns);
  std::vector<int> sorted = columns[0];
  std::sort(sorted.begin(), sorted.end());
  BOOST_TEST(sorted == all(kSize), "a permutation of the group's columns");
  const BandWidths ordered = group_band_widths(S, rows[0], columns[0]);
  BOOST_TEST(factorization_cost(ordered) <= factorization_cost(by_hand), ordered.kl << " " << ordered.ku);
  BOOST_TEST(2 * factorization_cost(ordered) < factorization_cost(stored));

  // BorderedBlockLu (one group) solves the system in the new order like the dense LU.
  BorderedBlockLu lu;
  BOOST_REQUIRE_MESSAGE(lu.analyze_pattern(S, std::vector<int>(kSize, 0)), lu.error_message());
  BOOST_REQUIRE_MESSAGE(lu.factorize(S), lu.error_message());
  const VecX b = VecX::Random(kSize);
  VecX x;
  lu.solve(b, x);
  const VecX expected = A.partialPivLu().solve(b);
  const VecX s = singular_values(A);
  BOOST_TEST((x - expected).norm() <= s[0] / s[s.size() - 1] * kSize * 1e-14 * expected.norm());
}

BOOST_AUTO_TEST_CASE(a_chain_keeps_its_order) {
  // The chain alone (its contact rows and columns dropped): the stored order is already the narrow one.
  std::mt19937 rng(6);
  const MatX A = rod_in_contact(rng).topLeftCorner(kChain, kChain);
  const Eigen::SparseMatrix<double> S = A.sparseView();  // compressed (assigned from an expression)
  std::vector<std::vector<int>> columns = {all(kChain)};
  order_columns_for_narrow_band(S, {all(kChain)}, columns);
  BOOST_TEST(columns[0] == all(kChain));
}
