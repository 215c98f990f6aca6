// Run time against error of single collocation rods (docs/design.md §2) on scenes R1 (end moment, phi = 2
// pi), R2 (Bisshopp-Drucker, alpha = 10) and R3 (exact helix) of docs/benchmarks.md (Scenes), over the degree
// p and the number of elements E, for both formulations (primal, mixed) and both solver paths (Newton,
// Ipopt); scenes in benchmarks/common/rod_scenes.hpp. Errors (exact_error there): max over 201 points of
// |p_h(s) - p(s)| against the analytic centerline (R1, R3), or
// |p_h(L) - p(L)| against the elliptic-integral elastica tip (R2 with EA = GA = 1e14 EI / L^2: the
// extensibility moves the tip by about alpha EI / (EA L^2) = 1e-13; with bench_shooting's 1e8 it would
// be 1e-7 and hide the discretisation error below it; see tests/rods/test_convergence.cpp). Every solve is
// cold: it starts from the straight rod, as a single-rod solve does (solve_rod's own initial guess, with its
// load-stepping fallback when the direct solve fails). Timing: each setting is solved repeatedly until 0.2 s
// or 200 solves have passed (at least once); median, min and max time per solve; the error is that of the
// last solve. CSV columns as bench_shooting; iterations = Newton/Ipopt iterations summed over load steps,
// failed solves have error nan.
//   build/release/benchmarks/bench_rods [csv path = benchmarks/results/rods.csv]
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/bench_csv.hpp"
#include "common/rod_scenes.hpp"

using namespace pcr;
using namespace pcr::bench;

int main(int argc, char** argv) {
  BenchCsv csv(argc > 1 ? argv[1] : "benchmarks/results/rods.csv");
  if (!csv.ok()) {
    std::fprintf(stderr, "cannot write %s\n", csv.path().c_str());
    return 1;
  }
  std::printf("%-12s %-26s %-10s %10s %12s %5s %5s %s\n", "scene", "method", "settings", "error",
              "median [ms]", "iter", "steps", "status");
  for (const RodScene& scene : {r1_full_circle(), r2_elastica(1e14), r3_helix()}) {
    for (SolverKind solver : {SolverKind::Newton, SolverKind::Ipopt}) {
      for (RodFormulation formulation : {RodFormulation::Mixed, RodFormulation::Primal}) {
        const std::string method =
            std::string("collocation-") + to_string(formulation) + "-" + to_string(solver);
        for (int degree = 2; degree <= 6; ++degree) {
          for (int elements : collocation_element_counts(scene.name, formulation, solver)) {
            RodSolveOptions o;
            o.discretization = {formulation, degree, elements};
            o.solver = solver;
            o.tolerance = 1e-10;
            o.max_load_steps =
                40;  // successful mixed-form solves took <= 20 steps; more only delays failures
            RodSolution sol;
            const Timing t = time_repeated([&] { sol = solve_rod(scene.model, o); }, {1, 200, 0.2});
            const double error = sol.summary.converged()
                                     ? exact_error(scene, [&](double s) { return sol.at(s).position; })
                                     : NAN;
            const std::string settings = "p=" + std::to_string(degree) + ";E=" + std::to_string(elements);
            csv.row(scene.name, method, settings, error, t, sol.summary.iterations);
            std::printf("%-12s %-26s %-10s %10.2e %12.4f %5d %5d %s\n", scene.name.c_str(), method.c_str(),
                        settings.c_str(), error, 1e3 * t.median, sol.summary.iterations, sol.load_steps,
                        to_string(sol.summary.status));
            std::fflush(stdout);
          }
        }
      }
    }
  }
  std::printf("wrote %s\n", csv.path().c_str());
  return 0;
}
