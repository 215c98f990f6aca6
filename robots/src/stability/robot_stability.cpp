// robot_stability (robot_stability.hpp): the rods' counts with their links held plus the negative
// eigenvalues of the border's (platforms' and passive joints') reduced stiffness.
#include "pcr/robots/robot_stability.hpp"

#include <algorithm>
#include <sstream>
#include <string>

#include "../kinematics/energy_model.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "robot_stability_parts.hpp"

namespace pcr {

namespace {

/// K in a balanced scaling D K D (D positive diagonal): a congruence, so its symmetric part has the same
/// count of negative eigenvalues as K's (Sylvester). First D = diag(|K_ii|^-1/2) (as for the rods' segment
/// stiffnesses), which leaves a positive definite K with unit diagonal and every entry within 1; where an
/// entry still exceeds 1 (an indefinite K whose diagonal is small beside its coupling, e.g. a universal
/// joint whose rod lies along its first axis: turning that axis twists a rod free to spin at its other
/// end), rows and columns are scaled down by the square root of their largest entry until none exceeds 1
/// (Ruiz's equilibration), so that the asymmetry below is relative to the entries it is an error of.
MatX balanced(const MatX& K) {
  VecX d(K.rows());
  for (int i = 0; i < K.rows(); ++i)
    d[i] = std::abs(K(i, i)) > 0.0 ? 1.0 / std::sqrt(std::abs(K(i, i))) : 1.0;
  MatX Ks = d.asDiagonal() * K * d.asDiagonal();
  for (int pass = 0; pass < 50; ++pass) {
    const VecX largest =
        Ks.cwiseAbs().rowwise().maxCoeff().cwiseMax(Ks.cwiseAbs().colwise().maxCoeff().transpose());
    if (largest.size() == 0 || largest.maxCoeff() <= 1.0 + 1e-9) break;
    const VecX shrink = largest.cwiseMax(1.0).cwiseSqrt().cwiseInverse();
    Ks = shrink.asDiagonal() * Ks * shrink.asDiagonal();
  }
  return Ks;
}

/// Relative asymmetry of K: max |Ks - Ks^T| of the balanced Ks.
double scaled_asymmetry(const MatX& Ks) {
  return (Ks - Ks.transpose()).cwiseAbs().maxCoeff();
}

/// A conservative model's K_red is symmetric but for the discretisation error of the collocation (and the
/// residual of the solve); beyond this the state is not an accurate equilibrium.
constexpr double kMaxAsymmetry = 1e-4;
/// Between kMaxAsymmetry and this, the count is kept where no error of the asymmetry's size can change
/// it: every eigenvalue of the symmetrised balanced K_hat (the scaling in which the asymmetry
/// is measured) farther than n x asymmetry from zero (Weyl: a symmetric
/// perturbation E of an n x n matrix moves each eigenvalue by at most |E|_2 <= n max|E_ij|), the
/// asymmetry taken as the size of the discretisation error it is the antisymmetric part of (passive_hinge,
/// strongly compressed and bent at 8 elements per rod: 1.1e-4 - 5.1e-4; at the first such state 1.1e-4
/// at 8 elements, 3.4e-7 at 16, 5.9e-9 at 32, docs/benchmarks.md "Random FK sweeps").
constexpr double kMaxClearAsymmetry = 1e-3;

/// The reason the count of K_hat (Ks: balanced) is not trusted, or "".
std::string asymmetry_failure(double asymmetry, const MatX& Ks) {
  if (asymmetry <= kMaxAsymmetry) return "";
  const VecX lambda = symmetric_eigen(0.5 * (Ks + Ks.transpose())).values;
  const double n = static_cast<double>(lambda.size());
  const bool clear = lambda.size() == 0 || lambda.cwiseAbs().minCoeff() > n * asymmetry;
  if (asymmetry <= kMaxClearAsymmetry && clear) return "";
  std::ostringstream msg;
  msg << stability::kAsymmetricBorder << ": relative asymmetry " << asymmetry << " > "
      << (asymmetry > kMaxClearAsymmetry ? kMaxClearAsymmetry : kMaxAsymmetry);
  if (asymmetry <= kMaxClearAsymmetry)
    msg << " with an eigenvalue within " << n << " x that of zero (" << lambda.cwiseAbs().minCoeff() << ")";
  return msg.str();
}

/// Where the split into held rods and border does not apply (why: a rod touching an obstacle, or at a
/// conjugate point with its links held): the count of the whole robot on the energy's Ritz form
/// (ritz_stability), where the energy describes the model.
Stability whole_count(const RobotAssembly& assembly, const VecX& x, const std::string& why) {
  const std::string refusal = kinematics::energy_model_refusal(assembly.model());
  if (!refusal.empty())
    return unknown_stability(why +
                             ": it is counted on the energy's Ritz form, which does not describe this " +
                             "model (" + refusal + ")");
  return stability::ritz_stability(assembly, x, why);
}

/// Adds the border's count and margin to s (stability::count_border), with the scales; false with s
/// Unknown on failure.
bool add_border(const RobotAssembly& assembly, const VecX& x, Stability& s) {
  const BorderStiffness border = robot_border_stiffness(assembly, x);
  if (!border.ok) {
    s = unknown_stability(border.failure);
    return false;
  }
  if (!stability::count_border(border.stiffness, s)) return false;
  s.length_scale = assembly.length_scale();
  s.energy_scale = assembly.moment_scale();
  return true;
}

}  // namespace

bool stability::count_border(const MatX& K, Stability& s) {
  const MatX scaled = balanced(K);
  const double asymmetry = scaled_asymmetry(scaled);
  s.asymmetry = std::max(s.asymmetry, asymmetry);
  const std::string failure = asymmetry_failure(asymmetry, scaled);
  if (!failure.empty()) {
    s = unknown_stability(failure);
    return false;
  }
  // The count on the symmetrised K_hat, in the scaling its asymmetry is measured in (the same inertia as
  // K's symmetric part: a congruence); the tolerance as for the rods' scaled segment stiffnesses.
  const double tolerance = std::max(1e-8, 10.0 * asymmetry);
  const VecX scaled_lambda = symmetric_eigenvalues(0.5 * (scaled + scaled.transpose()));
  for (int i = 0; i < scaled_lambda.size(); ++i) {
    if (scaled_lambda[i] < -tolerance)
      ++s.border_unstable_modes;
    else if (scaled_lambda[i] <= tolerance)
      ++s.neutral_modes;
  }
  // The margin: the smallest eigenvalue of the dimensionless K (bending stiffnesses O(1)).
  s.margin = symmetric_eigenvalues(0.5 * (K + K.transpose()))[0];
  return true;
}

Stability robot_stability(const RobotAssembly& assembly, const VecX& x) {
  const std::string failure = stability::robot_assumption_failure(assembly.model());
  if (!failure.empty()) return unknown_stability(failure);
  const std::string touching = stability::touching_contact(assembly, x);
  if (!touching.empty()) return whole_count(assembly, x, touching);
  Stability s;
  double rod_margin = INFINITY;
  HeldRodIndex weakest;
  for (int i = 0; i < assembly.num_rods(); ++i) {
    const HeldRodIndex rod = stability::held_rod_in_robot(assembly, x, i);
    const std::string& name = assembly.model().rods()[i].name;
    if (!rod.ok) return unknown_stability("rod '" + name + "': " + rod.failure);
    if (rod.neutral_modes > 0)  // A singular: Haynsworth's split does not apply; the whole count does
      return whole_count(assembly, x, "rod '" + name + "' is at a conjugate point with its links held");
    s.rod_unstable_modes.push_back(rod.unstable_modes);
    s.asymmetry = std::max(s.asymmetry, rod.asymmetry);
    if (rod.margin < rod_margin) weakest = rod;
    rod_margin = std::min(rod_margin, rod.margin);
  }
  if (assembly.model().platforms().empty() && assembly.model().passive_joints().empty()) {
    s.margin = assembly.num_rods() > 0 ? rod_margin : 0.0;
    s.length_scale = weakest.length_scale;
    s.energy_scale = weakest.energy_scale;
  } else if (!add_border(assembly, x, s))
    return s;
  s.unstable_modes = s.border_unstable_modes;
  for (int n : s.rod_unstable_modes) s.unstable_modes += n;
  s.verdict = verdict_of(s.unstable_modes, s.neutral_modes);
  if (s.verdict == StabilityVerdict::Critical)
    s.reason =
        "zero eigenvalue of the reduced stiffness of the platforms and passive joints: a fold or bifurcation "
        "point, or a symmetry";
  return s;
}

}  // namespace pcr
