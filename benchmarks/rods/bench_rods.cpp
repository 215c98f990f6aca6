// Run time against error of single collocation rods (DESIGN.md §2) on scenes R1 (end moment, phi = 2 pi),
// R2 (Bisshopp-Drucker, alpha = 10) and R3 (exact helix) of shared/scenes/README.md, over the degree p
// and the number of elements E, for both formulations (primal, mixed) and both solver paths (Newton,
// Ipopt). Errors: max over 201 points of |p_h(s) - p(s)| against the analytic centerline (R1, R3), or
// |p_h(L) - p(L)| against the elliptic-integral elastica tip (R2 with EA = GA = 1e14 EI / L^2: the
// extensibility moves the tip by about alpha EI / (EA L^2) = 1e-13; with bench_shooting's 1e8 it would
// be 1e-7 and hide the discretisation error below it; see tests/rods/test_convergence.cpp). Every solve is
// cold: it starts from the straight rod, as a single-rod solve does (solve_rod's own initial guess, with its
// load-stepping fallback when the direct solve fails). Timing: each setting is solved repeatedly until 0.2 s
// or 200 solves have passed (at least once); median, min and max time per solve; the error is that of the
// last solve. CSV columns as bench_shooting; iterations = Newton/Ipopt iterations summed over load steps,
// failed solves have error nan.
//   build/release/benchmarks/bench_rods [csv path = benchmarks/results/rods.csv]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "pcr/rods/rod_solve.hpp"
#include "rods/rod_fixtures.hpp"

using namespace pcr;

namespace {

struct Scene {
  std::string name;
  RodModel model;
  std::function<double(const RodSolution&)> error;
};

/// Max over 201 equally spaced points of |p_h(s) - p_exact(s)| for a rod of constant curvature kappa.
double arc_error(const RodSolution& sol, double length, const Vec3& kappa) {
  double worst = 0.0;
  for (int i = 0; i <= 200; ++i) {
    const double s = length * i / 200.0;
    worst = std::max(worst, (sol.at(s).position - test::constant_curvature_position(kappa, s)).norm());
  }
  return worst;
}

std::vector<Scene> scenes() {
  std::vector<Scene> out;
  {  // R1: EI = 2, L = 1, EA = 100, GA = 50, M = 2 pi EI / L about e1 (n = 0: a full circle for any EA, GA).
    RodModel m = test::cantilever(1.0, Vec3(50, 50, 100), Vec3(2, 2, 2));
    const Vec3 kappa(2 * M_PI, 0, 0);
    m.tip.moment = 2.0 * kappa;
    out.push_back({"R1_phi_2pi", m, [kappa](const RodSolution& sol) { return arc_error(sol, 1.0, kappa); }});
  }
  {  // R2: EI = 1, L = 1, EA = GA = 1e14, dead tip force 10 perpendicular to the axis (alpha = 10).
    RodModel m = test::cantilever(1.0, Vec3::Constant(1e14), Vec3(1, 1, 1));
    m.tip.force = Vec3(10.0, 0, 0);
    const test::Elastica exact = test::bisshopp_drucker(10.0);
    const Vec3 tip(exact.lateral, 0.0, 1.0 - exact.axial);
    out.push_back(
        {"R2_alpha_10", m, [tip](const RodSolution& sol) { return (sol.tip().position - tip).norm(); }});
  }
  {  // R3: E = 1, G = 0.5, circle of radius 1 (EI = GJ = pi/4, EA = pi, GA = pi/2), end moment EI kappa.
    const double L = 135.245580489, EI = M_PI / 4;
    RodModel m = test::cantilever(L, Vec3(M_PI / 2, M_PI / 2, M_PI), Vec3(EI, EI, EI));
    const Vec3 kappa(0.086332350, 0.0, 0.034350551);
    m.tip.moment = EI * kappa;
    out.push_back({"R3_helix", m, [kappa, L](const RodSolution& sol) { return arc_error(sol, L, kappa); }});
  }
  return out;
}

struct Timing {
  double median = 0, min = 0, max = 0;
};

/// Solves until 0.2 s or 200 solves have passed (at least one); `last` is the last solution.
Timing time_solves(const RodModel& model, const RodSolveOptions& options, RodSolution& last) {
  std::vector<double> times;
  double total = 0.0;
  while (total < 0.2 && times.size() < 200) {
    const auto t0 = std::chrono::steady_clock::now();
    last = solve_rod(model, options);
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    times.push_back(t);
    total += t;
  }
  std::sort(times.begin(), times.end());
  const size_t n = times.size();
  return {n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]), times.front(), times.back()};
}

/// Element counts. R3 (two coils over L = 135) needs twice the elements of R1 and R2 for the same error.
/// Ipopt (a general NLP solver on this square system, 10-100x slower than Newton here) runs on fewer
/// sizes, without the coarsest meshes, where it falls back to slow load stepping. The primal form
/// locks on the slender R2 and R3 (EA L^2 / EI = 1e14 and 7e4): there it fails or converges to a
/// locked, far too stiff rod at every size measured, each attempt costing seconds, so it runs on the
/// smaller sizes only. All this keeps a full run within about 5 minutes.
std::vector<int> element_counts(const std::string& scene, RodFormulation formulation, SolverKind solver) {
  const bool locking = formulation == RodFormulation::Primal && scene != "R1_phi_2pi";
  std::vector<int> counts;
  if (solver == SolverKind::Newton)
    counts = locking ? std::vector<int>{2, 4, 8, 16} : std::vector<int>{2, 4, 8, 16, 32, 64, 128};
  else
    counts = locking ? std::vector<int>{4} : std::vector<int>{4, 8, 16, 32};
  if (scene == "R3_helix") {
    for (int& e : counts) e *= 2;
    if (solver == SolverKind::Ipopt && !locking) counts.pop_back();  // 8, 16, 32: 2-12 s per solve at 64
  }
  return counts;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "benchmarks/results/rods.csv";
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  std::ofstream csv(path);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    return 1;
  }
  csv << "scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations\n";
  std::printf("%-12s %-26s %-10s %10s %12s %5s %5s %s\n", "scene", "method", "settings", "error",
              "median [ms]", "iter", "steps", "status");
  for (const Scene& scene : scenes()) {
    for (SolverKind solver : {SolverKind::Newton, SolverKind::Ipopt}) {
      for (RodFormulation formulation : {RodFormulation::Mixed, RodFormulation::Primal}) {
        const std::string method =
            std::string("collocation-") + to_string(formulation) + "-" + to_string(solver);
        for (int degree = 2; degree <= 6; ++degree) {
          for (int elements : element_counts(scene.name, formulation, solver)) {
            RodSolveOptions o;
            o.discretization = {formulation, degree, elements};
            o.solver = solver;
            o.tolerance = 1e-10;
            o.max_load_steps =
                40;  // successful mixed-form solves took <= 20 steps; more only delays failures
            RodSolution sol;
            const Timing t = time_solves(scene.model, o, sol);
            const double error = sol.summary.converged() ? scene.error(sol) : NAN;
            const std::string settings = "p=" + std::to_string(degree) + ";E=" + std::to_string(elements);
            csv << scene.name << ',' << method << ',' << settings << ',' << error << ',' << t.median << ','
                << t.min << ',' << t.max << ',' << sol.summary.iterations << '\n';
            std::printf("%-12s %-26s %-10s %10.2e %12.4f %5d %5d %s\n", scene.name.c_str(), method.c_str(),
                        settings.c_str(), error, 1e3 * t.median, sol.summary.iterations, sol.load_steps,
                        to_string(sol.summary.status));
            std::fflush(stdout);
          }
        }
      }
    }
  }
  std::printf("wrote %s\n", path.c_str());
  return 0;
}
