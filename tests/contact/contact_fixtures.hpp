#pragma once
// Shared set-ups of the contact tests: a steel cantilever (E = 200 GPa, nu = 0.3, rho = 7850 kg/m^3,
// radius 1 mm, shear coefficient 1) clamped at the origin with its tangent along +x, and a rod solve with
// contact rows (rod_contact.hpp) by pcr's Newton.
#include <memory>

#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/rod_contact.hpp"
#include "pcr/solve/problem.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr::test {

inline constexpr double kYoungs = 200e9, kPoisson = 0.3, kDensity = 7850.0, kRadius = 1e-3;

/// Clamped at the origin, tangent +x, free tip; gravity and tip force as given.
RodModel steel_cantilever(double length, const Vec3& gravity, const Vec3& tip_force);

/// Touchdown length l [m] of a heavy cantilever (weight q [N/m], bending stiffness EI, shear stiffness kGA)
/// lying on a plane H below its clamp, Timoshenko beam: touchdown at l with w(l) = -H, w'(l) = 0,
/// M(l) = 0, a point reaction q l / 3 there and the distributed reaction q beyond; clamp force 2 q l / 3,
/// clamp moment q l^2 / 6 (elementary superposition with the touchdown conditions, as in pipe-laying
/// analyses: Mattheij & Rienstra, "On an off-shore pipe laying problem", 1987). l solves
/// q l^4 / (72 EI) + q l^2 / (6 kGA) = H, here by Newton from the Euler-Bernoulli value.
double heavy_cantilever_touchdown(double H, double q, double EI, double kGA);

/// The mixed midpoint discretisation with contact forces (degree, elements).
RodDiscretization contact_discretization(int degree, int elements);

struct ContactSolve {
  Problem problem;
  RodVariables vars;
  RodContactVariables contact;  ///< empty without obstacles
  VecX x;
  SolveSummary summary;
  double seconds = 0.0;
};

/// Builds the rod's problem (with contact rows when `options` has obstacles) and solves it from the
/// straight initial guess by Newton (tolerance 1e-10, at most 100 iterations), in load_steps equal steps
/// of the load factor (loads and intrinsic strains), each started from the last; iterations and time
/// of all steps.
std::unique_ptr<ContactSolve> solve_rod(const CollocationRod& rod, const RodContactOptions* options,
                                        int load_steps = 1);

}  // namespace pcr::test
