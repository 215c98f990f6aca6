#pragma once
// The single-rod scenes of the benchmarks (docs/benchmarks.md (Scenes) R1, R2, R3 and the Weeger et al.
// 2017 helical spring), with their analytic solutions where one exists, and the element counts the
// collocation sweeps use on them.
#include <functional>
#include <string>
#include <vector>

#include "pcr/rods/rod_model.hpp"
#include "pcr/rods/rod_solve.hpp"

namespace pcr::bench {

struct RodScene {
  std::string name;
  RodModel model;
  /// Exact centerline p(s) on [0, L] (R1, R3); empty when only the tip (R2) or nothing is known.
  std::function<Vec3(double)> exact_centerline;
  /// Exact tip position (R2); empty when unknown or when exact_centerline gives it.
  std::function<Vec3()> exact_tip;
  bool has_exact() const { return exact_centerline || exact_tip; }
};

/// R1: EI = 2, L = 1, EA = 100, GA = 50, end moment 2 pi EI / L about e1: a full circle (n = 0 for
/// any EA, GA), p(s) = (0, -(1 - cos ks) / k, sin(ks) / k), k = 2 pi.
RodScene r1_full_circle();
/// R2: EI = 1, L = 1, EA = GA = axial_shear_stiffness, dead tip force 10 along e1 (alpha = 10). The
/// exact tip is the inextensible elastica (Bisshopp & Drucker 1945), only offered when the stiffness
/// is >= 1e12: the extensibility moves the tip by about alpha EI / (EA L^2), so at 1e14 by 1e-13.
RodScene r2_elastica(double axial_shear_stiffness);
/// R3: E = 1, G = 0.5, circle of radius 1 (EI = GJ = pi/4), L = 135.2, end moment EI kappa: the exact
/// helix of radius 10, pitch 25, two coils.
RodScene r3_helix();
/// Helical spring (Weeger et al. 2017 §7; tests/rods/rod_fixtures.hpp): stress-free helix, radius
/// 0.01, pitch angle 20 deg, 3 coils, axial/shear stiffness 1e6 EI / R^2, pulled along its axis by
/// F = 2 R / compliance (linear-theory extension of twice the coil radius). No exact solution.
RodScene helical_spring_large_load();

/// Error of a computed centerline p_h(s) against the exact solution: max over `points` equally spaced
/// s in [0, L] of |p_h(s) - p(s)| (exact_centerline), or |p_h(L) - p(L)| (exact_tip only).
/// Throws InputError when the scene has no exact solution.
double exact_error(const RodScene& scene, const std::function<Vec3(double)>& centerline, int points = 201);

/// Collocation element counts for `scene` (names above) by formulation and solver path; `quick` is
/// the reduced smoke-run set.
std::vector<int> collocation_element_counts(const std::string& scene, RodFormulation formulation,
                                            SolverKind solver, bool quick = false);

}  // namespace pcr::bench
