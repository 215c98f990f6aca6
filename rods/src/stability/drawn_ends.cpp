// The end conditions of a drawn rod against those of its effective energy (rod_stability.hpp,
// docs/design.md §1 "Drawn rods"): which ends the stability verdict may test by the effective energy.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "pcr/rods/drawn_rod.hpp"
#include "pcr/rods/stability/rod_stability.hpp"

namespace pcr {

namespace {

/// Whether m = M + rho c^2 R J_rho kappa is the same multiple lambda of M in both bending directions,
/// m_i = (1 + flux_i / K_BT,eff,i) M_i (i = 1, 2; body frame, no intrinsic curvature). With the
/// homogeneous section's J_rho (drawn_rod.hpp: rho I_i = rho A E I_i / E A) both ratios are
/// 1 / (1 - rho c^2 / E) whatever the section's shape; compared to round-off.
bool equal_bending_ratios(const DrawnConstants& d) {
  const double r1 = 1.0 + d.flux_moment[0] / d.k_bt[0], r2 = 1.0 + d.flux_moment[1] / d.k_bt[1];
  return std::abs(r1 - r2) <= 1e-12 * std::max(r1, r2);
}

/// Whether the conditions of an end of this kind on the section's n, m are natural conditions of the
/// effective energy, i.e. say the same for N, M (and to first order about the state: see
/// drawn_joint_state_problem for the universal end's state conditions).
bool natural_for_effective_energy(const RodModel& model, const RodEnd& end) {
  if (end.kind == RodEndKind::Clamped) return true;
  const bool unloaded_straight = end.moment.isZero(0.0) && model.intrinsic.curvature.isZero(0.0);
  if (end.kind == RodEndKind::Spherical) return unloaded_straight;  // m = D M, D diagonal positive
  if (end.kind != RodEndKind::Universal || !unloaded_straight) return false;
  return equal_bending_ratios(drawn_constants(model, model.intrinsic.shear_extension, Vec3::Zero()));
}

}  // namespace

std::string drawn_end_problem(const RodModel& model) {
  if (model.drawing_speed == 0.0) return {};
  std::ostringstream msg;
  const RodEnd* ends[2] = {&model.base, &model.tip};
  const char* names[2] = {"base", "tip"};
  for (int k = 0; k < 2; ++k) {
    if (natural_for_effective_energy(model, *ends[k])) continue;
    msg << (msg.tellp() > 0 ? "; " : "") << "rod '" << model.name << "': drawn rod (drawing_speed "
        << model.drawing_speed << " m/s) with a " << to_string(ends[k]->kind) << " " << names[k]
        << ": its conditions on the section force or moment are not those of the effective rod's energy";
  }
  return msg.str();
}

std::string drawn_joint_state_problem(const RodModel& model, const HeldRod& rod,
                                      const JacobiStateAt& states) {
  if (model.drawing_speed == 0.0) return {};
  const DrawnConstants d = drawn_constants(model, model.intrinsic.shear_extension, model.intrinsic.curvature);
  if (!d.drawn()) return {};
  std::ostringstream msg;
  const HeldEnd* ends[2] = {&rod.base, &rod.tip};
  const char* names[2] = {"base", "tip"};
  for (int k = 0; k < 2; ++k) {
    if (ends[k]->kind != RodEndKind::Universal) continue;
    const JacobiState y = states(k == 0 ? 0.0 : rod.length);
    const Vec3 d3 = y.rotation.col(2);
    const double torsion = d3.dot(y.moment) / d.k_bt[2] + d.kappa0[2];  // u3 from M (M4)
    const double tilt = d3.dot(ends[k]->axis.normalized());             // a_body . e3
    // u3 L and d3 . a enter the difference of the two linearised end rows as relative terms (times
    // ratios of the fluxes to the stiffnesses); below the state's own accuracy (its strain mismatch
    // |du| L, held_rod.hpp) and the floor 1e-8 of the verdict's neutral tolerance (held_rod.cpp) they
    // cannot be told from zero.
    const double tolerance = std::max(1e-8, y.strain_mismatch);
    if (std::abs(torsion) * rod.length <= tolerance && std::abs(tilt) <= tolerance) continue;
    msg << (msg.tellp() > 0 ? "; " : "") << "drawn rod with a universal " << names[k]
        << " at torsion u3 L = " << torsion * rod.length << " and d3 . a = " << tilt
        << " (both must be below " << tolerance
        << "): the joint's conditions on the section moment m are not those on M of the effective rod's "
           "energy";
  }
  return msg.str();
}

}  // namespace pcr
