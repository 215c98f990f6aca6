// Speed and accuracy of the robot shooting solver (pcr/robots/shooting/shooting_robot_solver.hpp) on
// the Stewart-Gough scenes (docs/benchmarks.md, Scenes):
//  - R5a_fk_cold, R5a_ik_cold: FK at moved inputs / IK to the R5a target ((0, 0, 0.4), R_y(10 deg)),
//    each solve from the cold guess; error = platform position error [m] (FK) or max input error [m]
//    (IK) against Dormand-Prince at 1e-12;
//  - R5b_ik_path: the teleoperation path, target (0, 0.02, 0.48) + i (0, 0.001, 0.001), i = 0..100
//    and back (201 solves), orientation identity, each IK warm-started from the previous; error = max
//    input error along the path against converged Dormand-Prince 1e-12 solves; times per warm solve
//    (the first, cold, solve excluded), iterations = the most any warm solve took, solves/s = warm
//    solves / their total time.
// Residual tolerance 1e-10 (scaled) for the timed solves. Scenes: benchmarks/common/robot_scenes.hpp.
// usage: bench_shooting_robots [csv path = benchmarks/results/shooting_robots.csv]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "common/bench_csv.hpp"
#include "common/robot_scenes.hpp"
#include "pcr/robots/shooting/shooting_robot_solver.hpp"

using namespace pcr;
using namespace pcr::bench;

namespace {

// One result line: on stdout and in the CSV.
struct ResultTable {
  BenchCsv& csv;
  void header() const {
    std::printf("%-12s %-15s %-10s %10s %12s %10s %10s %5s %s\n", "scene", "method", "settings", "error",
                "median [ms]", "min [ms]", "max [ms]", "it", "solves/s");
  }
  void row(const std::string& scene, const ShootingMethod& m, double error, const Timing& t, int iterations,
           double rate) const {
    csv.row(scene, m.name, m.settings, error, t, iterations);
    std::printf("%-12s %-15s %-10s %10.2e %12.3f %10.3f %10.3f %5d %.0f\n", scene.c_str(), m.name.c_str(),
                m.settings.c_str(), error, 1e3 * t.median, 1e3 * t.min, 1e3 * t.max, iterations, rate);
    std::fflush(stdout);
  }
};

// Cold R5a solves of every method: `solve(solver, iterations)` returns the error of one solve.
template <class Solve>
void cold_rows(const ResultTable& table, const std::shared_ptr<const RobotModel>& r5a, const char* scene,
               Solve solve) {
  const Repeats repeats{21, 21, 0.0};
  for (const ShootingMethod& m : shooting_methods({20, 40})) {
    ShootingRobotSolver solver(r5a, m.options);
    double error = 0.0;
    int iterations = 0;
    const Timing tm = time_repeated(
        [&] {
          solver.reset();
          error = solve(solver, iterations);
        },
        repeats);
    table.row(scene, m, error, tm, iterations, 1.0 / tm.median);
  }
}

// R5a cold FK and IK against Dormand-Prince 1e-12 references. False if a reference failed.
bool run_r5a_cold(const ResultTable& table) {
  const auto r5a = load_r5a();
  const VecX u = r5a_moved_inputs(*r5a);
  const Pose target = r5a_target();
  ShootingRobotSolver ref_a(r5a, bench::shooting_reference_options());
  const RobotSolution fk_ref = ref_a.fk(u);
  const RobotSolution ik_ref = ref_a.ik({target});
  if (!fk_ref.summary.converged() || !ik_ref.summary.converged()) {
    std::fprintf(stderr, "R5a reference failed\n");
    return false;
  }
  cold_rows(table, r5a, "R5a_fk_cold", [&](ShootingRobotSolver& solver, int& iterations) {
    const RobotSolution s = solver.fk(u);
    iterations = s.summary.iterations;
    return s.summary.converged() ? (s.platforms[0].position - fk_ref.platforms[0].position).norm() : NAN;
  });
  cold_rows(table, r5a, "R5a_ik_cold", [&](ShootingRobotSolver& solver, int& iterations) {
    const RobotSolution s = solver.ik({target});
    iterations = s.summary.iterations;
    return s.summary.converged() ? (s.inputs - ik_ref.inputs).lpNorm<Eigen::Infinity>() : NAN;
  });
  return true;
}

// Converged Dormand-Prince 1e-12 IK inputs along the R5b path; empty if a point failed.
std::vector<VecX> r5b_reference(const std::shared_ptr<const RobotModel>& r5b, const std::vector<Pose>& path) {
  std::vector<VecX> reference;
  ShootingRobotSolver ref_b(r5b, bench::shooting_reference_options());
  for (const Pose& p : path) {
    const RobotSolution s = ref_b.ik({p});
    if (!s.summary.converged()) {
      std::fprintf(stderr, "R5b reference failed at (%g, %g, %g)\n", p.position.x(), p.position.y(),
                   p.position.z());
      return {};
    }
    reference.push_back(s.inputs);
  }
  return reference;
}

// The R5b path, warm-started runs of every method (the first solve of each run is cold and not timed).
bool run_r5b_path(const ResultTable& table) {
  const auto r5b = load_r5b();
  const std::vector<Pose> path = r5b_path();
  const std::vector<VecX> reference = r5b_reference(r5b, path);
  if (reference.empty()) return false;
  for (const ShootingMethod& m : shooting_methods({20, 40})) {
    ShootingRobotSolver solver(r5b, m.options);
    std::vector<double> t;
    double error = 0.0, total = 0.0;
    int iterations = 0;
    for (size_t i = 0; i < path.size(); ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const RobotSolution s = solver.ik({path[i]});
      const double dt = seconds_since(t0);
      if (i > 0) {  // warm-started solves only
        t.push_back(dt);
        total += dt;
        iterations = std::max(iterations, s.summary.iterations);
      }
      error = std::max(
          error, s.summary.converged() ? (s.inputs - reference[i]).lpNorm<Eigen::Infinity>() : INFINITY);
    }
    table.row("R5b_ik_path", m, error, summarise(t), iterations, static_cast<double>(t.size()) / total);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  BenchCsv csv(argc > 1 ? argv[1] : "benchmarks/results/shooting_robots.csv");
  if (!csv.ok()) {
    std::fprintf(stderr, "cannot write %s\n", csv.path().c_str());
    return 1;
  }
  const ResultTable table{csv};
  table.header();
  return run_r5a_cold(table) && run_r5b_path(table) ? 0 : 1;
}
