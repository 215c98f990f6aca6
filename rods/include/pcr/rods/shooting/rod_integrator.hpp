#pragma once
// Integration of one rod's ODE (rod_ode.hpp) from s0 to s1: fixed-step classical RK4 or adaptive
// embedded Dormand-Prince 5(4) (Dormand & Prince 1980, "A family of embedded Runge-Kutta formulae",
// J. Comp. Appl. Math. 6; coefficients as in Hairer, Norsett & Wanner, Solving ODEs I, Table 5.2),
// optionally with the six tangent directions (variational equations) integrated on the same steps.
//
// Reusable building block for shooting: a robot-level solver integrates each rod from its base state
// with its tangents and reads the tip state and dy(L)/dz; d y(L) / d L = f(L, y(L)) (RodOde::derivative)
// gives the sensitivity to a fed length.
#include <string>
#include <vector>

#include "pcr/rods/shooting/integrator_method.hpp"
#include "pcr/rods/shooting/rod_ode.hpp"

namespace pcr {

struct IntegratorOptions {
  IntegratorMethod method = IntegratorMethod::DormandPrince;
  int rk4_steps = 100;                ///< RK4: number of equal steps over [s0, s1] (the full rod length)
  double relative_tolerance = 1e-10;  ///< Dormand-Prince: relative local error tolerance per step
  /// Dormand-Prince: absolute local error tolerance, multiplied per component by RodOde::state_scale()
  /// (L for p, 1 for q, F_c for n, M_c for m; see RodOde) so that one number serves all units.
  double absolute_tolerance = 1e-12;
  double min_step_fraction = 1e-12;  ///< smallest step = this * |s1 - s0|; below it integration fails
  int max_steps = 1000000;           ///< accepted + rejected steps before integration fails
};

/// Throws InputError naming the option if the options are unusable (non-positive steps or tolerances).
void check_integrator_options(const IntegratorOptions& options);

struct IntegrationReport {
  bool success = true;
  std::string message;  ///< why integration failed (step underflow, too many steps, non-finite state)
  int steps = 0;        ///< accepted steps
  int rejected_steps = 0;
};

/// The state at every accepted step (including s0 and s1), for dense output.
struct RodTrajectory {
  std::vector<double> s;
  std::vector<RodStateVector> y;
  void clear() {
    s.clear();
    y.clear();
  }
};

/// Integrates y from s0 to s1 >= s0 in place (y holds y(s0) on entry and y(s1) on exit).
/// Appends every accepted step to `trajectory` if given. Throws InputError for s1 < s0 or bad options.
IntegrationReport integrate_rod(const RodOde& ode, double s0, double s1, RodStateVector& y,
                                const IntegratorOptions& options, RodTrajectory* trajectory = nullptr);
/// Same with the tangents dy/dz (columns 1..6 of Y) integrated alongside; the step sizes are
/// controlled by the state (column 0) only.
IntegrationReport integrate_rod(const RodOde& ode, double s0, double s1, RodStateWithTangents& Y,
                                const IntegratorOptions& options, RodTrajectory* trajectory = nullptr);

/// Integrates on a given mesh s_0 < s_1 < ... (e.g. the steps of an earlier adaptive run, from
/// RodTrajectory::s): one step of the method per interval, no error control. With the mesh frozen,
/// y(s_end) is a smooth function of y(s_0), which Newton needs to converge to round-off (an adaptive
/// step sequence that changes between iterations adds noise of the size of the tolerance).
IntegrationReport integrate_rod_on_mesh(const RodOde& ode, const std::vector<double>& mesh, RodStateVector& y,
                                        IntegratorMethod method, RodTrajectory* trajectory = nullptr);
IntegrationReport integrate_rod_on_mesh(const RodOde& ode, const std::vector<double>& mesh,
                                        RodStateWithTangents& Y, IntegratorMethod method,
                                        RodTrajectory* trajectory = nullptr);

/// One step of the given method from (s0, y) to s0 + h, as used for dense output between stored steps
/// (for Dormand-Prince: the 5th-order solution of a single step).
RodStateVector rod_single_step(const RodOde& ode, double s0, double h, const RodStateVector& y,
                               IntegratorMethod method);

}  // namespace pcr
