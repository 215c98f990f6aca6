// bench_time_split: one workload of bench_all in a function of its own (measured_region), for a profile
// of where a solve's time goes (docs/benchmarks.md, "Time split"):
//   valgrind --tool=callgrind --toggle-collect='*measured_region*' build/release/benchmarks/bench_time_split
//       r5b_path --formulation condensed --degree 6 --elements 8 --tolerance 1e-7
//   callgrind_annotate --inclusive=yes callgrind.out.<pid>
// Workloads: r5b_path / r5b_helix (warm IK along bench_all's R5b paths, the first, cold, solve outside the
// region; with --shooting rk4|dormand_prince by pcr's shooting solver at bench_all's settings, for
// load-independent instruction ratios against collocation), r5a_fk / r5a_ik (one cold FK / IK, assembly
// included; r5a_ik also --shooting), R1 / R2 / R3 / spring (one cold solve_rod; --start stress_free for
// RodSolveOptions::shooting_start = false), fk_jump (a warm FK solve of --model FILE with the default
// KinematicsOptions from the inputs --from a,b,.. to --to c,d,..: a step of a random sweep; the solve at
// --from, which also solves the model's default equilibrium, outside the region). Prints the wall time of the
// region, the iterations and the status.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/robot_scenes.hpp"
#include "common/rod_scenes.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/robots/shooting/shooting_robot_solver.hpp"

using namespace pcr;
using namespace pcr::bench;

namespace {

struct Settings {
  std::string workload;
  RodFormulation formulation = RodFormulation::Condensed;
  int degree = 6, elements = 8, solves = 1;
  double tolerance = 1e-10;
  std::string shooting;  ///< "rk4" or "dormand_prince": the path by pcr's shooting solver instead
  int rk4_steps = 40;
  bool shooting_start = true;  ///< single rods: RodSolveOptions::shooting_start (--start stress_free: false)
  double integration_tolerance = 1e-8;
  std::string model_file;  ///< fk_jump: the model, and the inputs of the two solves
  VecX from, to;
};

VecX parse_inputs(const std::string& text) {
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    values.push_back(std::stod(text.substr(start, comma - start)));
    start = comma + 1;
  }
  return Eigen::Map<const VecX>(values.data(), static_cast<Eigen::Index>(values.size()));
}

struct Outcome {
  int iterations = 0, solves = 0;
  bool converged = true;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double seconds = 0.0;  ///< wall time of the region
  Outcome& stop() {
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return *this;
  }
};

KinematicsOptions robot_options(const Settings& s) {
  KinematicsOptions o;
  o.assembly.discretization = {s.formulation, s.degree, s.elements};
  o.assembly.use_model_hints = false;
  o.assembly.formulation_by_slenderness = false;
  o.assembly.condense_mixed_rods = false;
  o.tolerance = s.tolerance;
  return o;
}

// Warm IK solves along `path` (poses 1 .. end; pose 0 solved before, outside the region).
__attribute__((noinline)) Outcome measured_region(InverseKinematics& ik, const std::vector<Pose>& path) {
  Outcome out;
  for (size_t k = 1; k < path.size(); ++k) {
    const RobotSolution s = ik.solve({path[k]});
    out.iterations += s.summary.iterations;
    out.converged = out.converged && s.summary.converged();
    ++out.solves;
  }
  return out.stop();
}

// The same path by the shooting solver (pose 0 outside the region).
__attribute__((noinline)) Outcome measured_region(ShootingRobotSolver& solver,
                                                  const std::vector<Pose>& path) {
  Outcome out;
  for (size_t k = 1; k < path.size(); ++k) {
    const RobotSolution s = solver.ik({path[k]});
    out.iterations += s.summary.iterations;
    out.converged = out.converged && s.summary.converged();
    ++out.solves;
  }
  return out.stop();
}

/// bench_all's shooting settings: RK4 with N steps per rod, residual tolerance 1e-11, or Dormand-Prince
/// at integration tolerance T with residual tolerance clamp(1e-2 T, 1e-12, 1e-10).
ShootingRobotOptions shooting_options(const Settings& s) {
  ShootingRobotOptions o;
  if (s.shooting == "rk4") {
    o.integrator = IntegratorMethod::RK4;
    o.rk4_steps = s.rk4_steps;
    o.tolerance = 1e-11;
  } else {
    o.integration_relative_tolerance = o.integration_absolute_tolerance = s.integration_tolerance;
    o.tolerance = std::min(std::max(1e-2 * s.integration_tolerance, 1e-12), 1e-10);
  }
  return o;
}

__attribute__((noinline)) Outcome measured_region(const std::shared_ptr<const RobotModel>& model,
                                                  const KinematicsOptions& o, const VecX& inputs,
                                                  int solves) {
  Outcome out;
  for (int k = 0; k < solves; ++k) {
    ForwardKinematics fk(model, o);
    const RobotSolution s = fk.solve(inputs);
    out.iterations += s.summary.iterations;
    out.converged = out.converged && s.summary.converged();
    ++out.solves;
  }
  return out.stop();
}

__attribute__((noinline)) Outcome measured_region(const std::shared_ptr<const RobotModel>& model,
                                                  const KinematicsOptions& o, const Pose& target,
                                                  int solves) {
  Outcome out;
  for (int k = 0; k < solves; ++k) {
    InverseKinematics ik(model, {platform_target()}, o);
    const RobotSolution s = ik.solve({target});
    out.iterations += s.summary.iterations;
    out.converged = out.converged && s.summary.converged();
    ++out.solves;
  }
  return out.stop();
}

// One warm FK solve (the one at its last inputs made before, outside the region).
__attribute__((noinline)) Outcome measured_region(ForwardKinematics& fk, const VecX& inputs) {
  Outcome out;
  const RobotSolution s = fk.solve(inputs);
  out.iterations = s.summary.iterations;
  out.converged = s.summary.converged();
  out.solves = 1;
  return out.stop();
}

// Cold IK by the shooting solver (a new solver per solve, as bench_all).
__attribute__((noinline)) Outcome measured_region(const std::shared_ptr<const RobotModel>& model,
                                                  const Settings& settings, const Pose& target) {
  Outcome out;
  for (int k = 0; k < settings.solves; ++k) {
    ShootingRobotSolver solver(model, shooting_options(settings));
    const RobotSolution s = solver.ik({target});
    out.iterations += s.summary.iterations;
    out.converged = out.converged && s.summary.converged();
    ++out.solves;
  }
  return out.stop();
}

__attribute__((noinline)) Outcome measured_region(const RodModel& model, const RodSolveOptions& o,
                                                  int solves) {
  Outcome out;
  for (int k = 0; k < solves; ++k) {
    const RodSolution s = solve_rod(model, o);
    out.iterations += s.summary.iterations;
    out.converged = out.converged && s.summary.converged();
    ++out.solves;
  }
  return out.stop();
}

Outcome run(const Settings& s) {
  if (s.workload == "r5b_path" || s.workload == "r5b_helix") {
    const std::vector<Pose> path = s.workload == "r5b_path" ? r5b_path(100) : r5b_helix_path(400);
    if (!s.shooting.empty()) {
      ShootingRobotSolver solver(load_r5b(), shooting_options(s));
      solver.ik({path[0]});
      return measured_region(solver, path);
    }
    KinematicsOptions o = robot_options(s);
    o.read_centerline = false;  // as bench_all's path rows
    InverseKinematics ik(load_r5b(), {platform_target()}, o);
    ik.solve({path[0]});
    return measured_region(ik, path);
  }
  if (s.workload == "fk_jump") {
    ForwardKinematics fk(std::make_shared<const RobotModel>(load_robot_model(s.model_file)), KinematicsOptions{});
    if (!fk.solve(s.from).summary.converged()) std::fprintf(stderr, "bench_time_split: the --from solve failed\n");
    return measured_region(fk, s.to);
  }
  if (s.workload == "r5a_fk") {
    const std::shared_ptr<const RobotModel> model = load_r5a();
    return measured_region(model, robot_options(s), r5a_moved_inputs(*model), s.solves);
  }
  if (s.workload == "r5a_ik" && !s.shooting.empty()) return measured_region(load_r5a(), s, r5a_target());
  if (s.workload == "r5a_ik") return measured_region(load_r5a(), robot_options(s), r5a_target(), s.solves);
  for (const RodScene& scene :
       {r1_full_circle(), r2_elastica(1e14), r3_helix(), helical_spring_large_load()}) {
    if (scene.name.rfind(s.workload, 0) != 0) continue;
    RodSolveOptions o;
    o.discretization = {s.formulation, s.degree, s.elements};
    o.tolerance = s.tolerance;
    o.max_load_steps = 40;  // as bench_all
    o.shooting_start = s.shooting_start;
    return measured_region(scene.model, o, s.solves);
  }
  std::fprintf(stderr, "bench_time_split: unknown workload '%s'\n", s.workload.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(
        stderr,
        "usage: bench_time_split r5b_path|r5b_helix|r5a_fk|r5a_ik|R1|R2|R3|spring|fk_jump [--formulation "
        "mixed|condensed|primal] [--degree P] [--elements E] [--tolerance T] [--solves N] [--shooting "
        "rk4|dormand_prince [--rk4-steps N] [--integration-tolerance T]] [--start shooting|stress_free] "
        "[--model FILE --from a,b,.. --to c,d,..]\n");
    return 2;
  }
  Settings s;
  s.workload = argv[1];
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--formulation")
      s.formulation = value == "mixed"    ? RodFormulation::Mixed
                      : value == "primal" ? RodFormulation::Primal
                                          : RodFormulation::Condensed;
    else if (key == "--degree")
      s.degree = std::stoi(value);
    else if (key == "--elements")
      s.elements = std::stoi(value);
    else if (key == "--tolerance")
      s.tolerance = std::stod(value);
    else if (key == "--solves")
      s.solves = std::stoi(value);
    else if (key == "--shooting")
      s.shooting = value;
    else if (key == "--rk4-steps")
      s.rk4_steps = std::stoi(value);
    else if (key == "--integration-tolerance")
      s.integration_tolerance = std::stod(value);
    else if (key == "--start")
      s.shooting_start = value != "stress_free";
    else if (key == "--model")
      s.model_file = value;
    else if (key == "--from")
      s.from = parse_inputs(value);
    else if (key == "--to")
      s.to = parse_inputs(value);
  }
  const Outcome out = run(s);
  if (s.shooting.empty())
    std::printf("%s %s p=%d E=%d tol=%g", s.workload.c_str(), to_string(s.formulation), s.degree, s.elements,
                s.tolerance);
  else
    std::printf("%s shooting %s N=%d integration tol=%g", s.workload.c_str(), s.shooting.c_str(), s.rk4_steps,
                s.integration_tolerance);
  std::printf(": %d solves, %d iterations, %s, %.3f ms per solve\n", out.solves, out.iterations,
              out.converged ? "converged" : "FAILED", 1e3 * out.seconds / std::max(1, out.solves));
  return out.converged ? 0 : 1;
}
