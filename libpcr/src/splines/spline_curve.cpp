#include "pcr/splines/spline_curve.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "pcr/core/error.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr {

SplineCurve::SplineCurve(KnotVector knots, MatX control_points, VecX weights)
    : knots_(std::move(knots)), control_points_(std::move(control_points)), weights_(std::move(weights)) {
  const int n = knots_.num_basis();
  require(control_points_.rows() >= 1 && control_points_.cols() == n, "SplineCurve: control_points is ",
          control_points_.rows(), " x ", control_points_.cols(), ", expected d x ", n,
          " (d >= 1, one column per basis function)");
  require(control_points_.allFinite(), "SplineCurve: control_points contain a non-finite coordinate");
  require(weights_.size() == 0 || weights_.size() == n, "SplineCurve: ", weights_.size(),
          " weights given, expected 0 (B-spline) or ", n, " (NURBS)");
  for (Eigen::Index i = 0; i < weights_.size(); ++i)
    require(std::isfinite(weights_[i]) && weights_[i] > 0.0, "SplineCurve: weight[", i, "] = ", weights_[i],
            " must be finite and > 0");
}

VecX SplineCurve::evaluate(double u) const {
  return derivatives(u, 0).col(0);
}

MatX SplineCurve::derivatives(double u, int max_derivative) const {
  // C^(k)(u) = sum_i N_i^(k) P_i, or sum_i R_i^(k) P_i for NURBS (R_i from eq. 4.8 on the basis; the
  // same as A4.2 on the homogeneous curve).
  const BasisDerivatives basis = is_rational()
                                     ? rational_basis_derivatives(knots_, weights_, u, max_derivative)
                                     : basis_derivatives(knots_, u, max_derivative);
  return control_points_.middleCols(basis.first, knots_.degree() + 1) * basis.values.transpose();
}

MatX SplineCurve::homogeneous_points() const {
  if (!is_rational()) return control_points_;
  MatX Pw(dimension() + 1, control_points_.cols());
  Pw.topRows(dimension()) = control_points_ * weights_.asDiagonal();
  Pw.bottomRows(1) = weights_.transpose();
  return Pw;
}

SplineCurve SplineCurve::from_homogeneous(KnotVector knots, const MatX& points) const {
  if (!is_rational()) return SplineCurve(std::move(knots), points);
  const int d = dimension();
  VecX w = points.row(d).transpose();
  MatX P = points.topRows(d) * w.cwiseInverse().asDiagonal();
  return SplineCurve(std::move(knots), std::move(P), std::move(w));
}

SplineCurve SplineCurve::with_inserted_knot(double u, int times) const {
  const int p = knots_.degree();
  require(u > 0.0 && u < 1.0, "SplineCurve::with_inserted_knot: u = ", u, " must lie in (0, 1)");
  const int s = knots_.multiplicity(u);
  require(times >= 0 && s + times <= p, "SplineCurve::with_inserted_knot: times = ", times, " at u = ", u,
          " (multiplicity ", s, ") must be >= 0 and give a multiplicity <= degree ", p);
  if (times == 0) return *this;
  // The NURBS Book A5.1 (CurveKnotIns) on the homogeneous control points Pw.
  const int r = times, n = knots_.num_basis(), k = knots_.find_span(u);
  const std::vector<double>& U = knots_.knots();
  std::vector<double> UQ(U.begin(), U.begin() + k + 1);
  UQ.insert(UQ.end(), r, u);
  UQ.insert(UQ.end(), U.begin() + k + 1, U.end());
  const MatX Pw = homogeneous_points();
  MatX Qw(Pw.rows(), n + r);
  Qw.leftCols(k - p + 1) = Pw.leftCols(k - p + 1);  // unchanged before the affected points
  Qw.rightCols(n - (k - s)) = Pw.rightCols(n - (k - s));
  MatX Rw = Pw.middleCols(k - p, p - s + 1);  // the affected points, updated in place
  int L = k - p;
  for (int j = 1; j <= r; ++j) {
    L = k - p + j;
    for (int i = 0; i <= p - j - s; ++i) {
      const double alpha = (u - U[L + i]) / (U[i + k + 1] - U[L + i]);
      Rw.col(i) = alpha * Rw.col(i + 1) + (1.0 - alpha) * Rw.col(i);
    }
    Qw.col(L) = Rw.col(0);
    Qw.col(k + r - j - s) = Rw.col(p - j - s);
  }
  for (int i = L + 1; i < k - s; ++i) Qw.col(i) = Rw.col(i - L);
  return from_homogeneous(KnotVector(p, std::move(UQ)), Qw);
}

namespace {

double binomial(int n, int k) {
  double result = 1.0;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

// Bezier degree elevation coefficients (The NURBS Book eq. 5.36): row i, column j of the (p + t + 1) x
// (p + 1) matrix is C(p, j) C(t, i - j) / C(p + t, i), the weight of the degree-p point j in the elevated
// point i.
MatX bezier_elevation_coefficients(int p, int t) {
  const int ph = p + t, ph2 = ph / 2;
  MatX bezalfs = MatX::Zero(ph + 1, p + 1);
  bezalfs(0, 0) = bezalfs(ph, p) = 1.0;
  for (int i = 1; i <= ph2; ++i) {
    const double inv = 1.0 / binomial(ph, i);
    for (int j = std::max(0, i - t); j <= std::min(p, i); ++j)
      bezalfs(i, j) = inv * binomial(p, j) * binomial(t, i - j);
  }
  for (int i = ph2 + 1; i <= ph - 1; ++i)
    for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) bezalfs(i, j) = bezalfs(ph - i, p - j);
  return bezalfs;
}

// Inserts the knot ub r times into the current segment bpts (knots U from index a, ub of multiplicity mul),
// leaving the Bezier segment [ua, ub] in bpts and the leftmost points of the next segment in next_bpts
// (The NURBS Book A5.9, the knot insertion step).
void insert_to_bezier(const std::vector<double>& U, int p, int a, int mul, int r, double ua, double ub,
                      std::vector<double>& alfs, MatX& bpts, MatX& next_bpts) {
  const double numer = ub - ua;
  for (int k = p; k > mul; --k) alfs[k - mul - 1] = numer / (U[a + k] - ua);
  for (int j = 1; j <= r; ++j) {
    const int save = r - j, s = mul + j;
    for (int k = p; k >= s; --k)
      bpts.col(k) = alfs[k - s] * bpts.col(k) + (1.0 - alfs[k - s]) * bpts.col(k - 1);
    next_bpts.col(save) = bpts.col(p);
  }
}

// Degree elevation of the Bezier segment bpts (degree p) by t into ebpts, columns lbz..p + t (The NURBS
// Book eq. 5.36).
void elevate_bezier(const MatX& bezalfs, int p, int t, int lbz, const MatX& bpts, MatX& ebpts) {
  for (int i = lbz; i <= p + t; ++i) {
    ebpts.col(i).setZero();
    for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) ebpts.col(i) += bezalfs(i, j) * bpts.col(j);
  }
}

// Removes the knot ua oldr times (it was inserted oldr times in the previous pass) from the control
// points written so far (Qw up to cind, knots Uh up to kind) and the elevated segment ebpts
// (The NURBS Book A5.9, the knot removal step).
void remove_inserted_knot(const std::vector<double>& Uh, int ph, int oldr, int kind, int cind, int lbz,
                          double ua, double ub, MatX& Qw, MatX& ebpts) {
  int first = kind - 2, last = kind;
  const double den = ub - ua;
  const double bet = (ub - Uh[kind - 1]) / den;
  for (int tr = 1; tr < oldr; ++tr) {
    int i = first, j = last, kj = j - kind + 1;
    while (j - i > tr) {
      if (i < cind) {
        const double alf = (ub - Uh[i]) / (ua - Uh[i]);
        Qw.col(i) = alf * Qw.col(i) + (1.0 - alf) * Qw.col(i - 1);
      }
      if (j >= lbz) {
        if (j - tr <= kind - ph + oldr) {
          const double gam = (ub - Uh[j - tr]) / den;
          ebpts.col(kj) = gam * ebpts.col(kj) + (1.0 - gam) * ebpts.col(kj + 1);
        } else {
          ebpts.col(kj) = bet * ebpts.col(kj) + (1.0 - bet) * ebpts.col(kj + 1);
        }
      }
      ++i;
      --j;
      --kj;
    }
    --first;
    ++last;
  }
}

}  // namespace

SplineCurve SplineCurve::with_elevated_degree(int times) const {
  require(times >= 0, "SplineCurve::with_elevated_degree: times = ", times, " must be >= 0");
  if (times == 0) return *this;
  // The NURBS Book A5.9 (DegreeElevateCurve): extract each Bezier segment by knot insertion, elevate it
  // (eq. 5.36), and remove the inserted knots again while writing the new control points.
  const int p = knots_.degree(), t = times, ph = p + t;
  const std::vector<double>& U = knots_.knots();
  const int m = static_cast<int>(U.size()) - 1;  // last knot index
  const MatX Pw = homogeneous_points();
  const Eigen::Index dim = Pw.rows();
  const int new_num_basis = knots_.num_basis() + t * knots_.num_elements();
  std::vector<double> Uh(U.size() + t * (knots_.num_elements() + 1));
  MatX Qw = MatX::Zero(dim, new_num_basis);

  const MatX bezalfs = bezier_elevation_coefficients(p, t);

  MatX bpts = Pw.leftCols(p + 1);                        // current Bezier segment, degree p
  MatX ebpts = MatX::Zero(dim, ph + 1);                  // elevated segment, degree ph
  MatX next_bpts = MatX::Zero(dim, std::max(p - 1, 1));  // leftmost points of the next segment
  std::vector<double> alfs(std::max(p - 1, 1));
  int kind = ph + 1, cind = 1, r = -1, a = p, b = p + 1;
  double ua = U[0];
  Qw.col(0) = Pw.col(0);
  std::fill(Uh.begin(), Uh.begin() + ph + 1, ua);
  while (b < m) {
    const int i0 = b;
    while (b < m && U[b] == U[b + 1]) ++b;
    const int mul = b - i0 + 1;
    const double ub = U[b];
    const int oldr = r;
    r = p - mul;  // insert ub r times to reach multiplicity p
    const int lbz = oldr > 0 ? (oldr + 2) / 2 : 1;
    const int rbz = r > 0 ? ph - (r + 1) / 2 : ph;
    if (r > 0) insert_to_bezier(U, p, a, mul, r, ua, ub, alfs, bpts, next_bpts);
    elevate_bezier(bezalfs, p, t, lbz, bpts, ebpts);
    if (oldr > 1) remove_inserted_knot(Uh, ph, oldr, kind, cind, lbz, ua, ub, Qw, ebpts);
    if (a != p)  // load the knot ua with its elevated multiplicity
      for (int i = 0; i < ph - oldr; ++i) Uh[kind++] = ua;
    for (int j = lbz; j <= rbz; ++j) Qw.col(cind++) = ebpts.col(j);
    if (b < m) {  // set up the next segment
      for (int j = 0; j < r; ++j) bpts.col(j) = next_bpts.col(j);
      for (int j = r; j <= p; ++j) bpts.col(j) = Pw.col(b - p + j);
      a = b;
      ++b;
      ua = ub;
    } else {
      for (int i = 0; i <= ph; ++i) Uh[kind + i] = ub;  // end knot
    }
  }
  require(cind == new_num_basis, "SplineCurve::with_elevated_degree: internal error, ", cind,
          " control points written, expected ", new_num_basis);
  return from_homogeneous(KnotVector(ph, std::move(Uh)), Qw);
}

SplineCurve SplineCurve::with_uniform_refinement(int parts) const {
  require(parts >= 1, "SplineCurve::with_uniform_refinement: parts = ", parts, " must be >= 1");
  const std::vector<double> breaks = knots_.breakpoints();
  SplineCurve refined = *this;
  for (std::size_t e = 0; e + 1 < breaks.size(); ++e)
    for (int k = 1; k < parts; ++k)
      refined = refined.with_inserted_knot(breaks[e] + (breaks[e + 1] - breaks[e]) * k / parts);
  return refined;
}

}  // namespace pcr
