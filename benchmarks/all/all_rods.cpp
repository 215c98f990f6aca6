// bench_all, single rods: R1, R2 (alpha = 10), R3 and the helical spring (common/rod_scenes.hpp), every
// solve cold. Error: max over 201 equally spaced s of |p_h(s) - p_ref(s)| (R2: the tip only), p_ref the
// analytic solution where one exists, else the other method at tight settings.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "all/all_runs.hpp"
#include "common/rod_scenes.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"

namespace pcr::bench {

namespace {

using Centerline = std::function<Vec3(double)>;
using ErrorOf = std::function<double(const Centerline&)>;

constexpr int kPoints = 201;

/// Error against p_ref sampled at kPoints equally spaced s: max |p_h(s_i) - p_ref(s_i)|.
ErrorOf sampled_error(double length, const std::vector<Vec3>& reference) {
  return [length, reference](const Centerline& p) {
    double worst = 0.0;
    for (int i = 0; i < kPoints; ++i)
      worst = std::max(worst, (p(length * i / (kPoints - 1)) - reference[i]).norm());
    return worst;
  };
}

std::vector<double> sample_points(double length) {
  std::vector<double> s;
  for (int i = 0; i < kPoints; ++i) s.push_back(length * i / (kPoints - 1));
  return s;
}

/// Tight shooting: the reference of collocation runs where no analytic solution exists.
bool shooting_reference(const RodScene& scene, std::vector<Vec3>& points, Recorder& out) {
  ShootingOptions o;
  o.integration_relative_tolerance = o.integration_absolute_tolerance = 1e-12;
  o.tolerance = 1e-12;
  const ShootingSolution sol = solve_rod_shooting(scene.model, o);
  out.note(scene.name + " reference (shooting, Dormand-Prince 1e-12): " + sol.summary.brief_report());
  if (!sol.summary.converged()) return false;
  for (const ShootingState& state : sol.sample(sample_points(scene.model.length))) points.push_back(state.p);
  return true;
}

/// Tight collocation: the reference of shooting runs where no analytic solution exists. Mixed form,
/// p = 8, 96 elements, tolerance 1e-12: on the spring within 7.9e-12 L of Dormand-Prince 1e-12
/// (tests/shooting_crosscheck).
bool collocation_reference(const RodScene& scene, std::vector<Vec3>& points, Recorder& out) {
  RodSolveOptions o;
  o.discretization = {RodFormulation::Mixed, 8, 96};
  o.tolerance = 1e-12;
  const RodSolution sol = solve_rod(scene.model, o);
  out.note(scene.name + " reference (collocation, mixed p=8 E=96): " + sol.summary.brief_report());
  if (!sol.summary.converged()) return false;
  for (double s : sample_points(scene.model.length)) points.push_back(sol.at(s).position);
  return true;
}

void collocation_sweep(const RodScene& scene, const ErrorOf& error_of, const AllConfig& config,
                       Recorder& out) {
  const std::vector<int> degrees = config.quick ? std::vector<int>{3, 5} : std::vector<int>{2, 3, 4, 5, 6};
  for (SolverKind solver : {SolverKind::Newton, SolverKind::Ipopt}) {
    for (RodFormulation formulation :
         {RodFormulation::Mixed, RodFormulation::Condensed, RodFormulation::Primal}) {
      // The condensed form with Newton only (Ipopt gains nothing from the smaller system: bench_all's
      // mixed Ipopt rows are 10-100x slower than Newton).
      if (formulation == RodFormulation::Condensed && solver == SolverKind::Ipopt) continue;
      const std::string method =
          std::string("collocation-") + to_string(formulation) + "-" + to_string(solver);
      for (int degree : degrees) {
        for (int elements : collocation_element_counts(scene.name, formulation, solver, config.quick)) {
          RodSolveOptions o;
          o.discretization = {formulation, degree, elements};
          o.solver = solver;
          o.tolerance = 1e-10;
          o.max_load_steps = 40;  // successful mixed-form solves took <= 20 steps (bench_rods)
          // The solve alone, as shooting's: the stability verdict is an extra output (its cost is in
          // docs/benchmarks.md, "Stability verdict of single rods").
          o.stability_verdict = false;
          RodSolution sol;
          const Timing t = time_repeated([&] { sol = solve_rod(scene.model, o); }, config.repeats());
          const double error =
              sol.summary.converged() ? error_of([&sol](double s) { return sol.at(s).position; }) : NAN;
          out.record(scene.name, method, "p=" + std::to_string(degree) + ";E=" + std::to_string(elements),
                     error, t, sol.summary.iterations, to_string(sol.summary.status));
        }
      }
    }
  }
}

void shooting_sweep(const RodScene& scene, const ErrorOf& error_of, const AllConfig& config, Recorder& out) {
  struct Run {
    std::string method, settings;
    ShootingOptions options;
  };
  std::vector<Run> runs;
  const std::vector<int> steps = config.quick ? std::vector<int>{10, 40, 160, 640}
                                              : std::vector<int>{10, 20, 40, 80, 160, 320, 640, 1000};
  for (int n : steps) {
    ShootingOptions o;
    o.integrator = IntegratorMethod::RK4;
    o.rk4_steps = n;
    o.tolerance = 1e-12;
    runs.push_back({"shooting-rk4", "N=" + std::to_string(n), o});
  }
  const std::vector<int> exponents =
      config.quick ? std::vector<int>{3, 6, 9, 12} : std::vector<int>{3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  for (int e : exponents) {
    ShootingOptions o;
    o.integration_relative_tolerance = o.integration_absolute_tolerance = std::pow(10.0, -e);
    o.tolerance = std::max(
        1e-12, 1e-2 * o.integration_relative_tolerance);  // below the integration error (bench_shooting)
    runs.push_back({"shooting-dormand_prince", "tol=1e-" + std::to_string(e), o});
  }
  for (Run& run : runs) {
    // Timed as the error's solve: with its trajectory (the default), the shape a user reads the
    // centerline from, as collocation's timed solve includes its control points.
    const ShootingSolution sol = solve_rod_shooting(scene.model, run.options);
    const double error = sol.summary.converged() ? error_of([&sol](double s) { return sol.at(s).p; }) : NAN;
    Repeats repeats = config.repeats();
    repeats.min_count = std::max(repeats.min_count, 5);
    repeats.max_count = 2000;  // fast solves: more repeats for a steady median
    const Timing t = time_repeated([&] { solve_rod_shooting(scene.model, run.options); }, repeats);
    out.record(scene.name, run.method, run.settings, error, t, sol.summary.iterations,
               to_string(sol.summary.status));
  }
}

}  // namespace

bool run_rod_scenes(const AllConfig& config, Recorder& out) {
  bool ok = true;
  // R2 with EA = GA = 1e14 EI / L^2: the inextensible elastica is then exact to 1e-13 (rod_scenes.hpp).
  for (const RodScene& scene :
       {r1_full_circle(), r2_elastica(1e14), r3_helix(), helical_spring_large_load()}) {
    if (!config.selected(scene.name)) continue;
    if (scene.has_exact()) {
      const ErrorOf exact = [&scene](const Centerline& p) { return exact_error(scene, p, kPoints); };
      out.note(scene.name + ": errors against the analytic solution");
      collocation_sweep(scene, exact, config, out);
      shooting_sweep(scene, exact, config, out);
      continue;
    }
    std::vector<Vec3> by_shooting, by_collocation;
    if (shooting_reference(scene, by_shooting, out))
      collocation_sweep(scene, sampled_error(scene.model.length, by_shooting), config, out);
    else
      ok = false;
    if (collocation_reference(scene, by_collocation, out))
      shooting_sweep(scene, sampled_error(scene.model.length, by_collocation), config, out);
    else
      ok = false;
  }
  return ok;
}

}  // namespace pcr::bench
