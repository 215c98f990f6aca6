#include "pcr/splines/knot_vector.hpp"

#include <cmath>

#include "pcr/core/error.hpp"

namespace pcr {

KnotVector::KnotVector(int degree, std::vector<double> knots) : degree_(degree), knots_(std::move(knots)) {
  require(degree_ >= 1, "KnotVector: degree = ", degree_, " must be >= 1");
  const int size = static_cast<int>(knots_.size());
  const int p = degree_;
  require(size >= 2 * (p + 1), "KnotVector: ", size, " knots given, degree ", p, " needs at least ",
          2 * (p + 1));
  for (int i = 0; i < size; ++i) {
    require(std::isfinite(knots_[i]), "KnotVector: knot[", i, "] = ", knots_[i], " is not finite");
    if (i > 0)
      require(knots_[i] >= knots_[i - 1], "KnotVector: knots decrease at index ", i, ": knot[", i - 1,
              "] = ", knots_[i - 1], " > knot[", i, "] = ", knots_[i]);
  }
  require(knots_.front() == 0.0, "KnotVector: first knot = ", knots_.front(), " must be 0");
  require(knots_.back() == 1.0, "KnotVector: last knot = ", knots_.back(), " must be 1");
  // Open knot vector: exactly p+1 copies of 0 and of 1 (more would make a basis function vanish).
  const int start = multiplicity(0.0), end = multiplicity(1.0);
  require(start == p + 1, "KnotVector: first knot 0 has multiplicity ", start,
          ", an open knot vector of degree ", p, " needs exactly ", p + 1);
  require(end == p + 1, "KnotVector: last knot 1 has multiplicity ", end, ", an open knot vector of degree ",
          p, " needs exactly ", p + 1);
  // Interior knots: multiplicity <= p keeps every basis function non-zero somewhere and the basis C^0.
  for (int i = p + 1; i < size - p - 1;) {
    int j = i;
    while (j + 1 < size && knots_[j + 1] == knots_[i]) ++j;
    require(j - i + 1 <= p, "KnotVector: interior knot ", knots_[i], " at index ", i, " has multiplicity ",
            j - i + 1, " > degree ", p);
    ++num_elements_;  // the span [knot[i-1], knot[i]) before this distinct interior knot
    i = j + 1;
  }
  ++num_elements_;  // the last span up to 1
}

KnotVector KnotVector::open_uniform(int degree, int num_elements) {
  require(degree >= 1, "KnotVector::open_uniform: degree = ", degree, " must be >= 1");
  require(num_elements >= 1, "KnotVector::open_uniform: num_elements = ", num_elements, " must be >= 1");
  std::vector<double> knots(degree + 1, 0.0);
  for (int e = 1; e < num_elements; ++e) knots.push_back(static_cast<double>(e) / num_elements);
  knots.insert(knots.end(), degree + 1, 1.0);
  return KnotVector(degree, std::move(knots));
}

int KnotVector::multiplicity(double u) const {
  int count = 0;
  for (double knot : knots_) count += knot == u ? 1 : 0;
  return count;
}

int KnotVector::find_span(double u) const {
  require(u >= 0.0 && u <= 1.0, "KnotVector::find_span: parameter u = ", u, " is outside [0, 1]");
  const int n = num_basis();
  if (u >= knots_[n]) return n - 1;  // u = 1: last non-empty span [xi_{n-1}, xi_n)
  // Binary search for xi_low <= u < xi_high, then the span is low (The NURBS Book A2.1).
  int low = degree_, high = n;
  while (high - low > 1) {
    const int mid = (low + high) / 2;
    if (u < knots_[mid])
      high = mid;
    else
      low = mid;
  }
  return low;
}

std::vector<double> KnotVector::greville() const {
  const int n = num_basis();
  std::vector<double> tau(n);
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int k = 1; k <= degree_; ++k) sum += knots_[i + k];
    tau[i] = sum / degree_;
  }
  // The sums of p equal end knots are exact, but keep the ends exactly 0 and 1 regardless.
  tau.front() = 0.0;
  tau.back() = 1.0;
  return tau;
}

std::vector<double> KnotVector::breakpoints() const {
  std::vector<double> points{knots_.front()};
  for (double knot : knots_)
    if (knot > points.back()) points.push_back(knot);
  return points;
}

}  // namespace pcr
