// Cost of the single-rod stability verdict (RodSolveOptions::stability_verdict, on by default): CPU time
// of a cold solve_rod with and without it, best of `repeats` runs.
// Usage: bench_rod_verdict [repeats]   (prints a Markdown table; docs/benchmarks.md)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "common/rod_scenes.hpp"
#include "rods/rod_fixtures.hpp"

namespace {

using pcr::RodFormulation;
using pcr::bench::RodScene;

/// Best wall time of `repeats` cold solves [s], with the verdict and iteration count of the last.
double best_time(const RodScene& scene, RodFormulation formulation, int elements, bool verdict, int repeats,
                 pcr::RodSolution& last) {
  pcr::RodSolveOptions o;
  o.discretization = {formulation, 5, elements};
  o.tolerance = 1e-10;
  o.max_load_steps = 40;  // as bench_all
  o.stability_verdict = verdict;
  double best = 1e30;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    last = pcr::solve_rod(scene.model, o);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  // Scenes with conservative loads (the verdict is `unknown` under dead couples: R1, R3 and the spring of
  // bench_all): R2's cantilever at a practical stiffness ratio (EA L^2 / EI = 1e8; bench_all's 1e12 is
  // beyond the verdict's range), and the R4 column (EI2 = 2 EI1) at 0.9 and 1.5 times its first critical
  // load with a small lateral load (bent, stable; bent against the load, one unstable mode).
  std::vector<RodScene> scenes = {pcr::bench::r2_elastica(1e8)};
  scenes[0].name = "R2, EA L^2/EI 1e8";
  for (double lambda : {0.9, 1.5}) {
    RodScene column;
    column.name = "R4 column " + std::to_string(lambda).substr(0, 3) + " P1";
    column.model = pcr::test::cantilever(1.0, pcr::Vec3::Constant(1e4), pcr::Vec3(1.0, 2.0, 2.0));
    const double P = lambda * M_PI * M_PI / 4.0;
    column.model.tip.force = pcr::Vec3(0.0, (lambda < 1.0 ? 0.05 : -0.05) * P, -P);
    scenes.push_back(column);
  }
  std::printf("| scene | form | E | Newton its | solve [ms] | with verdict [ms] | ratio | verdict |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const RodScene& scene : scenes) {
    for (RodFormulation formulation : {RodFormulation::Mixed, RodFormulation::Condensed}) {
      for (int elements : {4, 16, 64}) {
        pcr::RodSolution without, with;
        const double t0 = best_time(scene, formulation, elements, false, repeats, without);
        const double t1 = best_time(scene, formulation, elements, true, repeats, with);
        std::printf("| %s | %s | %d | %d | %.3f | %.3f | %.2f | %s (%d) |\n", scene.name.c_str(),
                    pcr::to_string(formulation), elements, without.summary.iterations, 1e3 * t0, 1e3 * t1,
                    t1 / t0, pcr::to_string(with.stability_verdict.verdict),
                    with.stability_verdict.unstable_modes);
      }
    }
  }
  return 0;
}
