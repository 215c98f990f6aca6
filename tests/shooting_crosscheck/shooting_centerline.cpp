#include "shooting_crosscheck/shooting_centerline.hpp"

#include "pcr/rods/shooting/rod_shooting.hpp"

namespace pcr::test {

ShootingCenterline shooting_centerline(const RodModel& model, const std::vector<double>& s,
                                       double tolerance) {
  ShootingOptions o;
  o.integrator = IntegratorMethod::DormandPrince;
  o.integration_relative_tolerance = o.integration_absolute_tolerance = tolerance;
  o.tolerance = 1e-12;
  const ShootingSolution sol = solve_rod_shooting(model, o);
  ShootingCenterline out;
  out.converged = sol.summary.converged();
  out.report = sol.summary.brief_report() + " " + sol.summary.message;
  if (!out.converged) return out;
  for (const ShootingState& state : sol.sample(s)) out.points.push_back(state.p);
  return out;
}

}  // namespace pcr::test
