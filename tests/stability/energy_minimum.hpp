#pragma once
// Energy minimisations next to an equilibrium (the tests' check of contact verdicts): Ipopt on the
// energy's Ritz form with the gap constraints (robots/src/kinematics/energy_model.hpp); and the same
// equilibrium on a refined mesh (the check of verdicts against the discretisation).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "kinematics/coarse_continuation.hpp"
#include "kinematics/energy_model.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/newton_solver.hpp"

namespace pcr::test {

/// Ipopt from the equilibrium x moved by `size` off its symmetry planes (EnergyModel::perturbed): the
/// minimiser's energy [J], and its first platform's position in `platform`.
inline double energy_minimised_from(const RobotAssembly& a, const VecX& x, double size, Vec3& platform) {
  const kinematics::EnergyModel energy(a, x);
  VecX e = energy.perturbed(energy.from_state(x), size);
  IpoptOptions o;
  o.tol = 1e-10;
  o.constraint_tolerance = 1e-10;
  o.warm_start = false;
  IpoptSolver ipopt(energy.problem(), o);
  BOOST_TEST_REQUIRE(ipopt.solve(e).converged());
  VecX xs = x;
  energy.to_state(e, xs);
  platform = a.platform_pose(xs, 0).position;
  return energy.energy(e);
}

/// The energy's Ritz form at the collocation state x [J].
inline double energy_at(const RobotAssembly& a, const VecX& x) {
  const kinematics::EnergyModel energy(a, x);
  return energy.energy(energy.from_state(x));
}

/// Checks that x is not a minimum of the energy: the minimisation started 1e-4 L0 off it reaches an energy
/// lower than x's by more than 1e-3 of it, far beyond the two discretisations' difference (5e-7
/// relative, energy_fallback.cpp). `where` names the state in the message.
inline void check_energy_descends_from(const RobotAssembly& a, const VecX& x, const std::string& where) {
  const double V = energy_at(a, x);
  Vec3 platform;
  const double lower = energy_minimised_from(a, x, 1e-4, platform);
  BOOST_TEST_MESSAGE(where << ": V " << V << " J, minimised " << lower << " J");
  BOOST_TEST(lower < V - 1e-3 * std::abs(V), where);
}

/// The equilibrium x of `from` carried to the assembly `to` of the same model on another mesh (MeshTransfer:
/// the same curves; rods with obstacles must keep their knots) and solved there by Newton.
inline VecX carried_to(const RobotAssembly& from, const VecX& x, const RobotAssembly& to) {
  const kinematics::MeshTransfer transfer(from, to);
  BOOST_TEST_REQUIRE(transfer.valid());
  VecX xf = transfer.apply(x);
  NewtonSolver newton(to.problem());
  BOOST_TEST_REQUIRE(newton.solve(xf, 30).converged());
  return xf;
}

}  // namespace pcr::test
