#pragma once
// What the forward and inverse kinematics solves share (internal header of pcr::robots): solver options
// from KinematicsOptions, the verdict on a solution and stability monitoring.
#include <chrono>

#include "pcr/robots/kinematics.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/newton_solver.hpp"

namespace pcr::kinematics {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t);

/// The FK's default equilibrium is shared between options whose fields read here are equal: a field
/// that newton_options or ipopt_options starts to read belongs in equal_solver_options
/// (default_equilibrium.cpp).
NewtonOptions newton_options(const KinematicsOptions& o);
/// Ipopt on the full assembly (FK with SolverKind::Ipopt, IK in the full space).
IpoptOptions ipopt_options(const KinematicsOptions& o);

/// The solution read from x (x_fallback where x is not finite, with the summary marked failed: a solver
/// never hands back NaN) with `summary` (its wall time: since start).
/// A converged solution with a rod compressed to a point or inverted is marked failed too
/// (admissible_axial_stretch). with_centerline: KinematicsOptions::read_centerline. accepted: whether the
/// solution stays converged.
RobotSolution finish_solution(const RobotAssembly& assembly, const VecX& x, const VecX& x_fallback,
                              SolveSummary summary, Clock::time_point start,
                              const std::vector<std::vector<BasisDerivatives>>& sample_bases,
                              bool with_centerline, bool& accepted);

/// A converged summary whose residual exceeds the tolerance (a Newton solve stopped at the round-off of
/// its residuals, NewtonLoop step 5): residual_round_off, the bound at the state x (its assembly variables
/// first), and a note in the message; a residual beyond both is marked failed, never reported converged.
void account_for_round_off(const Problem& problem, const VecX& x, double tolerance, SolveSummary& summary);

/// Appends contact_penetration_warning (rod_contact.hpp) of s.contact_gaps, if any, to s.summary.message.
void append_contact_warning(RobotSolution& s);

/// Stability monitoring (KinematicsOptions::check_stability): the sign of det J of the FK system `fk` at
/// the converged solution x, and whether it changed since the last checked solve (last_sign, updated).
void monitor_stability(const Problem& fk, const VecX& x, int& last_sign, RobotSolution& out);

/// The stability verdict (KinematicsOptions::stability_verdict) of the converged solution whose assembly
/// variables lead x (an IK state has its target blocks after them) into out.stability_verdict.
void add_stability_verdict(const RobotAssembly& assembly, const VecX& x, RobotSolution& out);

/// The unstable modes of a `stable` or `unstable` verdict; -1 for any other (critical, unknown, not
/// checked): no definite count.
int definite_unstable_modes(const Stability& s);

}  // namespace pcr::kinematics
