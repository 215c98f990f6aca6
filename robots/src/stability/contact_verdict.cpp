// The verdict counted on the second variation of the energy's Ritz form (robot_stability_parts.hpp
// ritz_stability): for rods touching obstacles (the touching contacts held), and for a rod at a conjugate
// point with its links held.
#include <Eigen/QR>
#include <limits>
#include <sstream>

#include "../kinematics/energy_model.hpp"
#include "pcr/math/tangent_space_spectrum.hpp"
#include "pcr/solve/sparse_lu.hpp"
#include "robot_stability_parts.hpp"

namespace pcr::stability {

namespace {

using kinematics::EnergyModel;
using SpMat = Eigen::SparseMatrix<double>;

/// Newton on the Ritz form's stationarity conditions (the energy scaled by energy_scale(), positions in
/// m) runs until its residual stops halving, at the round-off of the stiff axial and shear terms (1e-8 -
/// 6e-8 at the default states of planar_three_rod, stewart_gough and passive_hinge, reached in 1-2
/// iterations from the collocation's equilibrium); beyond this the state is not next to a Ritz
/// equilibrium.
constexpr double kStationary = 1e-6;
constexpr int kMaxNewton = 40;

/// D: L0 for the positions of control points and platforms (the first 3 of each 7-block), 1 for the
/// rest, so that D H D is the Hessian against displacements / L0 (dimensionless as the border's K_hat).
VecX coordinate_scale(const Problem& p, double L0) {
  VecX d = VecX::Ones(p.num_variables());
  for (int b = 0; b < p.num_variable_blocks(); ++b)
    if (p.variable(b).size == 7) d.segment(p.variable(b).offset, 3).setConstant(L0);
  return d;
}

struct Active {
  std::vector<int> rows;  // all equality rows and the touching gap rows
  std::vector<int> gaps;  // the touching gap rows (indices into rows)
};

Active active_rows(const Problem& p, const VecX& c) {
  Active a;
  const VecX lower = p.row_lower(), upper = p.row_upper();
  for (int i = 0; i < c.size(); ++i) {
    const bool inequality = upper[i] > lower[i];
    if (inequality && c[i] > kTouchingGap) continue;  // gap rows are g / L0
    if (inequality) a.gaps.push_back(static_cast<int>(a.rows.size()));
    a.rows.push_back(i);
  }
  return a;
}

/// The rows of J listed in `rows`, in that order.
SpMat rows_of(const Eigen::SparseMatrix<double, Eigen::RowMajor>& J, const std::vector<int>& rows) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(J, rows[r]); it; ++it)
      t.emplace_back(static_cast<int>(r), static_cast<int>(it.col()), it.value());
  SpMat out(static_cast<int>(rows.size()), J.cols());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

/// The Lagrangian's Hessian (both triangles) at e with the multipliers y of the active rows.
SpMat lagrangian_hessian(const Problem& p, const VecX& e, const Active& a, const VecX& y) {
  VecX multipliers = VecX::Zero(p.num_rows());
  for (std::size_t r = 0; r < a.rows.size(); ++r) multipliers[a.rows[r]] = y[r];
  Eigen::SparseMatrix<double, Eigen::RowMajor> H;
  p.evaluate_hessian(e, 1.0, multipliers, H);
  return SpMat(SpMat(H).selfadjointView<Eigen::Lower>());
}

/// The KKT matrix [H J_a^T; J_a 0] of Newton on the stationarity conditions.
SpMat kkt_matrix(const SpMat& H, const SpMat& Ja) {
  const int n = static_cast<int>(H.rows()), m = static_cast<int>(Ja.rows());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(H.nonZeros() + 2 * Ja.nonZeros()));
  for (int c = 0; c < n; ++c)
    for (SpMat::InnerIterator it(H, c); it; ++it) t.emplace_back(static_cast<int>(it.row()), c, it.value());
  for (int c = 0; c < n; ++c)
    for (SpMat::InnerIterator it(Ja, c); it; ++it) {
      t.emplace_back(n + static_cast<int>(it.row()), c, it.value());
      t.emplace_back(c, n + static_cast<int>(it.row()), it.value());
    }
  SpMat K(n + m, n + m);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

/// The Ritz form's equilibrium next to the state: grad V + J_a^T y = 0, c_a = 0 (L = V + y . c_a).
struct RitzEquilibrium {
  VecX y;                     ///< the active rows' multipliers
  SpMat H, Ja;                ///< the Lagrangian's Hessian and the active rows' Jacobian there
  double stationarity = 0.0;  ///< max |(grad V + J_a^T y, c_a)| reached
};

/// The stationarity residual (grad V + J_a^T y, c_a) at (e, y), with J_a and grad V there.
VecX stationarity_residual(const Problem& p, const VecX& e, const VecX& y, const Active& a, SpMat& Ja) {
  VecX c, g;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;
  p.evaluate_residuals_and_jacobian(e, c, J);
  p.evaluate_objective(e, &g);
  Ja = rows_of(J, a.rows);
  const int n = p.num_variables(), m = static_cast<int>(a.rows.size());
  VecX r(n + m);
  r.head(n) = g + Ja.transpose() * (y.size() == m ? y : VecX::Zero(m));
  for (int i = 0; i < m; ++i) r[n + i] = c[a.rows[i]];
  return r;
}

/// Newton on the stationarity conditions from e (the collocation state's unknowns) and the least-squares
/// multipliers, with backtracking on max |residual| (the Ritz equilibrium of a rod pressed hard on an
/// obstacle lies farther from the collocation's: its constraints hold at points, the collocation's
/// densities spread over cells), until the residual, below kStationary, stops halving (round-off), or no
/// step decreases it. Chord steps: the KKT matrix is factorised again only where a step with the last
/// factors did not halve the residual (from the collocation state one matrix usually takes it to
/// round-off); the Hessian of the returned state is computed there, for the count.
RitzEquilibrium ritz_equilibrium(const Problem& p, VecX e, const Active& a) {
  const int n = p.num_variables(), m = static_cast<int>(a.rows.size());
  RitzEquilibrium r;
  VecX residual = stationarity_residual(p, e, VecX(), a, r.Ja);
  r.y = MatX(r.Ja.transpose()).colPivHouseholderQr().solve(-residual.head(n));
  residual.head(n) += r.Ja.transpose() * r.y;
  r.stationarity = residual.cwiseAbs().maxCoeff();
  SparseLu kkt;  // one pattern for every factorisation (the rows' and Hessian's patterns are fixed)
  bool analyzed = false, factors = false, hessian_at_e = false;
  const auto finish = [&]() -> RitzEquilibrium& {
    if (!hessian_at_e) r.H = lagrangian_hessian(p, e, a, r.y);
    return r;
  };
  for (int k = 0; k < kMaxNewton; ++k) {
    if (!factors) {
      r.H = lagrangian_hessian(p, e, a, r.y);
      hessian_at_e = true;
      const SpMat K = kkt_matrix(r.H, r.Ja);
      if (!analyzed) kkt.analyze_pattern(K), analyzed = true;
      if (!kkt.factorize(K)) return r;
      factors = true;
    }
    const bool chord = !hessian_at_e;
    const VecX step = kkt.solve(VecX(-residual));
    bool decreased = false;
    for (double alpha = 1.0; alpha >= 1.0 / 64 && !decreased; alpha /= 2) {
      SpMat Ja;
      const VecX trial_e = e + alpha * step.head(n), trial_y = r.y + alpha * step.tail(m);
      const VecX trial = stationarity_residual(p, trial_e, trial_y, a, Ja);
      const double s = trial.cwiseAbs().maxCoeff();
      if (!(s < r.stationarity)) continue;
      decreased = true;
      const bool halved = s <= 0.5 * r.stationarity;
      // At round-off (the step no longer halves the residual): the state before it.
      if (!halved && r.stationarity <= kStationary) return finish();
      e = trial_e, r.y = trial_y, r.Ja = Ja, residual = trial, r.stationarity = s;
      hessian_at_e = false;
      if (!halved) factors = false;  // the chord steps stopped contracting: fresh factors
    }
    if (!decreased) {
      if (!chord) return r;  // no decrease along a step of fresh factors (the Hessian is at e)
      factors = false;       // the old factors' step failed: once more with fresh ones
    }
  }
  return finish();
}

/// The counts of the Lagrangian's Hessian on the tangent space {J_a de = 0}: the eigenvalues of Z^T H Z
/// for an orthonormal basis Z of it in the scaled coordinates (D de), built block by block
/// (tangent_space_spectrum.hpp: the unit-quaternion rows per control point, then the couplings and gaps);
/// eigenvalues zero within n eps of the largest (n: the tangent space's dimension), the round-off of a
/// backward-stable eigensolver (Weyl) on the rods' exact Hessians. The stiff axial terms set the largest
/// eigenvalue (3.9e8 at planar_post's default state, whose smallest are -2.875 and 0.2233); the Hessians
/// by differences that remain (the couplings', platforms' and passive joints') move those by 2e-9
/// between steps 1e-7 and 1e-5, and the rods' by differences moved them by 2e-7, both below
/// n eps 3.9e8 ~ 3e-5 (n a few hundred).
void count_on_tangent_space(const Problem& p, const RitzEquilibrium& r, const VecX& D, Stability& s) {
  std::vector<VariableRange> blocks;
  for (int b = 0; b < p.num_variable_blocks(); ++b)
    blocks.push_back({p.variable(b).offset, p.variable(b).size});
  const SpMat Hs = D.asDiagonal() * r.H * D.asDiagonal();
  const VecX lambda = tangent_space_eigenvalues(Hs, r.Ja * D.asDiagonal(), blocks);
  const double tolerance = static_cast<double>(lambda.size()) * std::numeric_limits<double>::epsilon() *
                           lambda.cwiseAbs().maxCoeff();
  for (int i = 0; i < lambda.size(); ++i) {
    if (lambda[i] < -tolerance)
      ++s.unstable_modes;
    else if (lambda[i] <= tolerance)
      ++s.neutral_modes;
  }
  s.verdict = verdict_of(s.unstable_modes, s.neutral_modes);
  s.margin = lambda.size() ? lambda[0] : 0.0;
}

}  // namespace

Stability ritz_stability(const RobotAssembly& assembly, const VecX& x, const std::string& why) {
  const EnergyModel energy(assembly, x);
  const Problem& p = energy.problem();
  const VecX e = energy.from_state(x);
  VecX c;
  p.evaluate_residuals(e, c);
  const Active a = active_rows(p, c);
  const RitzEquilibrium r = ritz_equilibrium(p, e, a);
  if (!(r.stationarity <= kStationary)) {
    std::ostringstream msg;
    msg << why << "; " << kNoRitzEquilibrium << " (stationarity " << r.stationarity << ")";
    return unknown_stability(msg.str());
  }
  // Every touching gap pushes (a strictly active contact: grad V = mu grad g with mu > 0, i.e. y < 0).
  for (int i : a.gaps)
    if (!(r.y[i] < -kStationary))
      return unknown_stability(why + "; a contact there carries no force (at the border of activity)");
  Stability s;
  count_on_tangent_space(p, r, coordinate_scale(p, assembly.length_scale()), s);
  s.length_scale = assembly.length_scale();
  s.energy_scale = energy.energy_scale();
  s.reason = std::string(a.gaps.empty() ? "counted" : "counted with the touching contacts held") +
             ", on the energy's Ritz form (" + why + ")";
  return s;
}

}  // namespace pcr::stability
