#pragma once
// Frictionless contact solved by Ipopt instead of the semismooth Newton method (docs/contact.md,
// "Solvers compared"). The contact problem of rod_contact.hpp is a complementarity problem; here it is a
// mathematical program with complementarity constraints (MPCC) in Scholtes' relaxation (Scholtes,
// "Convergence properties of a regularization scheme for mathematical programs with complementarity
// constraints", SIAM J. Optim. 11 (2001) 918-936): for every contact pair with a = g / L0 and
// b = lambda L0 / F0 (the scaled gap and force of rod_contact.hpp)
//   a >= 0 (row bound),   lambda >= 0 (variable bound),   a b <= mu (row bound),
// and the other rows (the rod's equations, the force directions, the contact sections of sharp
// obstacles) stay equalities. mu is a fixed variable block of one value, so that a homotopy mu -> 0
// changes only x (same structure: Ipopt warm-starts from the previous stage's primal-dual point).
//
// Why the relaxation and not the penalty form min sum a b (Leyffer, Lopez-Calva & Nocedal, SIAM J.
// Optim. 17 (2006) 52-77): the penalty puts the complementarity into the objective, whose curvature
// (the indefinite a b) Ipopt would only see through its limited-memory quasi-Newton Hessian (pcr's rod
// blocks provide no second derivatives), and its solution depends on the penalty weight; the relaxation
// keeps every condition in the constraints, whose Jacobians are exact, and the solution of each stage is
// a point of the relaxed feasible set, within O(sqrt(mu)) of the complementarity solution where gap and
// force vanish together and within O(mu) elsewhere.
//
// Objective: 0. The equilibrium is a feasibility problem: every point satisfying the constraints is a
// solution (IpoptSolver accepts any feasible point of a problem without objective). A regularisation
// (e.g. |lambda|^2) would pull the solution of each stage inside the relaxed set towards smaller forces,
// a bias that vanishes only with mu, and it would need a weight with no physical meaning.
#include <vector>

#include "pcr/rods/rod_contact.hpp"
#include "pcr/solve/ipopt_solver.hpp"

namespace pcr {

/// How the contact conditions are solved (docs/contact.md, "Solvers compared").
enum class ContactMethod {
  Semismooth,  ///< one complementarity-function row per pair, pcr's Newton (square system)
  Ipopt,       ///< Scholtes' relaxation with inequalities, Ipopt, homotopy in mu
};
const char* to_string(ContactMethod method);

/// The product rows are S (a b - mu) <= 0 with this S, so that the rows' tolerance tol bounds a b by
/// mu + tol / S (1e-14 with tol = 1e-10). Unscaled, an open gap a would leave a spurious force
/// b ~ tol / a: 1e-7 F0 / L0 at a = 1e-3, above the 1e-8 at which read_rod_contact counts a cell as
/// carrying force (seen on the heavy cantilever on a plane: its contact interval reached the clamp).
inline constexpr double kRelaxedProductScale = 1e4;

/// Replaces the contact rows of one rod, added by add_rod_contact with ComplementarityFunction::GapOnly,
/// by their relaxed form (header): switches off `contact.blocks` (those with complementarity rows) and
/// `contact.sharp_blocks`, adds one block per switched-off block with the same rows (the gap rows bounded
/// below by 0) and one product row per pair (S (a b - mu) <= 0), bounds the multipliers lambda >= 0, and adds
/// the fixed variable mu (initial value `relaxation`). Records them in contact.relaxation and
/// contact.relaxed_blocks. Throws InputError when the rows are not GapOnly or were relaxed already.
void relax_rod_contact(Problem& problem, const CollocationRod& rod, RodContactVariables& contact,
                       double relaxation = 1e-2);

struct ContactIpoptOptions {
  /// Max-abs of the dimensionless rows (the rod's equations, the gap and product bounds), as
  /// RodSolveOptions::tolerance; Ipopt's "tol" and constraint tolerance.
  double tolerance = 1e-10;
  /// The homotopy mu_1 > mu_2 > ... of the relaxation, one Ipopt solve each, warm-started from the
  /// previous one. The last value bounds the scaled product a b of every pair.
  std::vector<double> relaxations{1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14};
  int max_iterations = 500;  ///< per stage
  int print_level = 0;       ///< Ipopt's
};

/// IpoptOptions of one stage of the homotopy.
IpoptOptions contact_ipopt_options(const ContactIpoptOptions& options);

/// Solves `problem` (with every contact relaxed by relax_rod_contact; fixed variables at the values x
/// holds) along the homotopy: sets mu of every listed contact to each relaxation in turn and solves
/// with `solver` (an IpoptSolver on `problem`, reused: warm starts). x in: start, out: the last stage's
/// point. The summary is the last stage's with the iterations and Jacobian evaluations of all stages
/// summed; it stops at the first stage that does not converge.
SolveSummary solve_contact_homotopy(const Problem& problem,
                                    const std::vector<const RodContactVariables*>& contacts,
                                    IpoptSolver& solver, const ContactIpoptOptions& options, VecX& x);

}  // namespace pcr
