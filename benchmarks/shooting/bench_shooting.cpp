// Run time against error of the single-rod shooting reference (RK4 with N steps, Dormand-Prince 5(4)
// with tolerance tol) on scenes R1 (end moment, phi = 2 pi), R2 (Bisshopp-Drucker, alpha = 10) and
// R3 (exact helix) (benchmarks/common/rod_scenes.hpp). Errors: max-abs centerline error against the analytic
// solution (R1, R3, at 101 points) or the tip position error against a tight Dormand-Prince reference (R2,
// tol 1e-13). Every solve is cold (the solver's default start: the unloaded rod, zero base wrench) and does
// not store the trajectory. usage: bench_shooting [csv path = benchmarks/results/shooting.csv]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "common/bench_csv.hpp"
#include "common/rod_scenes.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"

using namespace pcr;
using namespace pcr::bench;

namespace {

/// Max-abs component of p_h(s) - p(s) at 101 equally spaced s, or of p_h(L) - tip.
using ErrorFn = std::function<double(const ShootingSolution&)>;

ErrorFn centerline_error(const RodScene& scene) {
  const double L = scene.model.length;
  const std::function<Vec3(double)> exact = scene.exact_centerline;
  return [L, exact](const ShootingSolution& sol) {
    double worst = 0.0;
    for (int i = 0; i <= 100; ++i) {
      const double s = L * i / 100.0;
      worst = std::max(worst, (sol.at(s).p - exact(s)).cwiseAbs().maxCoeff());
    }
    return worst;
  };
}

/// R2 with EA = GA = 1e8: error against a tight Dormand-Prince reference (tol 1e-13) of the same model.
ErrorFn tip_error_against_tight_reference(const RodScene& scene) {
  ShootingOptions tight;
  tight.integration_relative_tolerance = 1e-13;
  tight.integration_absolute_tolerance = 1e-15;
  tight.tolerance = 1e-13;
  const ShootingSolution ref = solve_rod_shooting(scene.model, tight);
  if (!ref.summary.converged())
    std::fprintf(stderr, "R2 reference: %s\n", ref.summary.brief_report().c_str());
  const Vec3 tip = ref.tip.p;
  return [tip](const ShootingSolution& sol) { return (sol.tip.p - tip).cwiseAbs().maxCoeff(); };
}

}  // namespace

int main(int argc, char** argv) {
  BenchCsv csv(argc > 1 ? argv[1] : "benchmarks/results/shooting.csv");
  if (!csv.ok()) {
    std::fprintf(stderr, "cannot write %s\n", csv.path().c_str());
    return 1;
  }
  std::printf("%-12s %-15s %-10s %10s %12s %6s %s\n", "scene", "method", "settings", "error", "median [ms]",
              "iter", "status");
  const RodScene r1 = r1_full_circle(), r2 = r2_elastica(1e8), r3 = r3_helix();
  const std::vector<std::pair<const RodScene*, ErrorFn>> scenes = {
      {&r1, centerline_error(r1)}, {&r2, tip_error_against_tight_reference(r2)}, {&r3, centerline_error(r3)}};
  for (const auto& [scene, error_of] : scenes) {
    std::vector<ShootingOptions> runs;
    std::vector<std::string> settings;
    for (int N : {10, 20, 40, 80, 160, 320, 640, 1000}) {
      ShootingOptions o;
      o.integrator = IntegratorMethod::RK4;
      o.rk4_steps = N;
      o.tolerance = 1e-12;
      runs.push_back(o);
      settings.push_back("N=" + std::to_string(N));
    }
    for (int e = 3; e <= 12; ++e) {
      ShootingOptions o;
      o.integrator = IntegratorMethod::DormandPrince;
      o.integration_relative_tolerance = o.integration_absolute_tolerance = std::pow(10.0, -e);
      // Newton stops well below the integration error (and above its step-size noise).
      o.tolerance = std::max(1e-12, 1e-2 * o.integration_relative_tolerance);
      runs.push_back(o);
      settings.push_back("tol=1e-" + std::to_string(e));
    }
    for (size_t i = 0; i < runs.size(); ++i) {
      ShootingOptions o = runs[i];
      const ShootingSolution sol = solve_rod_shooting(scene->model, o);
      const double error = sol.summary.converged() ? error_of(sol) : NAN;
      o.store_trajectory = false;
      // At least 5 solves and 0.2 s, at most 2000 solves.
      const Timing t = time_repeated([&] { solve_rod_shooting(scene->model, o); }, {5, 2000, 0.2});
      const char* method = o.integrator == IntegratorMethod::RK4 ? "rk4" : "dormand_prince";
      csv.row(scene->name, method, settings[i], error, t, sol.summary.iterations);
      std::printf("%-12s %-15s %-10s %10.2e %12.4f %6d %s\n", scene->name.c_str(), method,
                  settings[i].c_str(), error, 1e3 * t.median, sol.summary.iterations,
                  to_string(sol.summary.status));
      std::fflush(stdout);
    }
  }
  std::printf("wrote %s\n", csv.path().c_str());
  return 0;
}
