// bench_all, Stewart-Gough robots (common/robot_scenes.hpp):
//  - R5a_fk_cold: FK at the moved inputs, error = platform position error [m];
//  - R5a_ik_cold: IK to (0, 0, 0.4) m, R_y(10 deg), error = max input (rod length) error [m];
//    both cold: a new solver object per solve (collocation: assembly included);
//  - R5b_ik_path: IK along the teleoperation path, each solve warm-started from the previous; time per
//    warm solve (the first, cold, solve excluded), error = max input error along the path,
//    iterations = mean per warm solve;
//  - R5b_helix_path: the same along a helix of new targets (robot_scenes.hpp r5b_helix_path), no pose
//    visited twice.
// References (independent method): collocation runs against shooting (Dormand-Prince 1e-12, residual
// 1e-12), shooting runs against collocation (mixed, p = 8, 32 elements, tolerance 1e-11; at 16
// elements it already agrees with that shooting reference to 2e-11 m (platform) / 5e-11 m (inputs),
// tests/shooting_robots).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "all/all_runs.hpp"
#include "common/robot_scenes.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/shooting/shooting_robot_solver.hpp"

namespace pcr::bench {

namespace {

/// Results that the errors are measured on: platform position (FK), inputs (IK, one per path pose).
struct References {
  Vec3 fk_platform = Vec3::Zero();
  VecX ik_inputs;
  std::vector<VecX> path_inputs, helix_inputs;
  bool ok = false;
};

struct Scenes {
  std::shared_ptr<const RobotModel> r5a = load_r5a(), r5b = load_r5b();
  VecX fk_inputs;
  Pose target;
  std::vector<Pose> path, helix;
};

/// A warm-started IK path scene: its name, poses and the reference inputs at each pose.
struct PathScene {
  std::string name;
  const std::vector<Pose>& poses;
  const std::vector<VecX>& reference;
};
std::vector<PathScene> path_scenes(const Scenes& sc, const References& ref, const AllConfig& config) {
  std::vector<PathScene> scenes;
  if (config.selected("R5b_ik_path")) scenes.push_back({"R5b_ik_path", sc.path, ref.path_inputs});
  if (config.selected("R5b_helix_path")) scenes.push_back({"R5b_helix_path", sc.helix, ref.helix_inputs});
  return scenes;
}

double input_error(const VecX& a, const VecX& b) {
  return (a - b).lpNorm<Eigen::Infinity>();
}

/// IK along the path with one warm-started solver, `solve(pose)` returning a result with `summary` and
/// `inputs`; the inputs at every pose into `inputs`, or false (and a note) at the first failure.
template <typename Solve>
bool reference_path(const std::vector<Pose>& path, const std::string& label, Solve solve, Recorder& out,
                    std::vector<VecX>& inputs) {
  for (const Pose& p : path) {
    const auto s = solve(p);
    if (!s.summary.converged()) {
      out.note(label + " failed: " + s.summary.brief_report());
      return false;
    }
    inputs.push_back(s.inputs);
  }
  out.note(label + ": " + std::to_string(path.size()) + " poses");
  return true;
}

/// Warm-started solves along the path, `solve(pose)` as above: wall time and iterations of each warm
/// solve (the first, cold, one excluded), max input error against `reference` until the first failure.
struct PathRun {
  std::vector<double> times;
  double error = 0.0, iterations = 0.0;
  bool failed = false;
};
template <typename Solve>
PathRun run_path(const std::vector<Pose>& path, const std::vector<VecX>& reference, Solve solve) {
  PathRun run;
  for (size_t k = 0; k < path.size(); ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto s = solve(path[k]);
    if (k > 0) {  // warm-started solves only
      run.times.push_back(seconds_since(t0));
      run.iterations += s.summary.iterations;
    }
    run.failed = run.failed || !s.summary.converged();
    if (!run.failed) run.error = std::max(run.error, input_error(s.inputs, reference[k]));
  }
  return run;
}

void record_path(const std::string& scene, const PathRun& run, const std::string& method,
                 const std::string& settings, Recorder& out) {
  out.record(scene, method, settings, run.failed ? NAN : run.error, summarise(run.times),
             run.iterations / run.times.size(), run.failed ? "failed" : "converged");
}

KinematicsOptions collocation_options(RodFormulation formulation, int degree, int elements, SolverKind solver,
                                      double tolerance = 1e-10) {
  KinematicsOptions o;
  o.assembly.discretization = {formulation, degree, elements};
  o.assembly.use_model_hints = false;
  o.assembly.formulation_by_slenderness = false;  // exactly the formulation asked for (the slenderness
  o.assembly.condense_mixed_rods = false;         // rule would make every rod here mixed or condensed)
  o.solver = solver;
  o.tolerance = tolerance;
  return o;
}

References shooting_references(const Scenes& sc, const AllConfig& config, Recorder& out) {
  References ref;
  ShootingRobotSolver a(sc.r5a, shooting_reference_options());
  if (config.selected("R5a_fk_cold")) {
    const RobotSolution fk = a.fk(sc.fk_inputs);
    out.note("R5a FK reference (shooting, Dormand-Prince 1e-12): " + fk.summary.brief_report());
    if (!fk.summary.converged()) return ref;
    ref.fk_platform = fk.platforms[0].position;
  }
  if (config.selected("R5a_ik_cold")) {
    const RobotSolution ik = a.ik({sc.target});
    out.note("R5a IK reference (shooting, Dormand-Prince 1e-12): " + ik.summary.brief_report());
    if (!ik.summary.converged()) return ref;
    ref.ik_inputs = ik.inputs;
  }
  for (auto [scene, poses, inputs] : {std::tuple{"R5b_ik_path", &sc.path, &ref.path_inputs},
                                      std::tuple{"R5b_helix_path", &sc.helix, &ref.helix_inputs}}) {
    if (!config.selected(scene)) continue;
    ShootingRobotSolver b(sc.r5b, shooting_reference_options());
    if (!reference_path(
            *poses, std::string(scene) + " reference (shooting, Dormand-Prince 1e-12)",
            [&](const Pose& p) { return b.ik({p}); }, out, *inputs))
      return ref;
  }
  ref.ok = true;
  return ref;
}

References collocation_references(const Scenes& sc, const AllConfig& config, Recorder& out) {
  References ref;
  const KinematicsOptions o = collocation_options(RodFormulation::Mixed, 8, 32, SolverKind::Newton, 1e-11);
  if (config.selected("R5a_fk_cold")) {
    ForwardKinematics fk(sc.r5a, o);
    const RobotSolution s = fk.solve(sc.fk_inputs);
    out.note("R5a FK reference (collocation, mixed p=8 E=32): " + s.summary.brief_report());
    if (!s.summary.converged()) return ref;
    ref.fk_platform = s.platforms[0].position;
  }
  if (config.selected("R5a_ik_cold")) {
    InverseKinematics ik(sc.r5a, {platform_target()}, o);
    const RobotSolution s = ik.solve({sc.target});
    out.note("R5a IK reference (collocation, mixed p=8 E=32): " + s.summary.brief_report());
    if (!s.summary.converged()) return ref;
    ref.ik_inputs = s.inputs;
  }
  for (auto [scene, poses, inputs] : {std::tuple{"R5b_ik_path", &sc.path, &ref.path_inputs},
                                      std::tuple{"R5b_helix_path", &sc.helix, &ref.helix_inputs}}) {
    if (!config.selected(scene)) continue;
    InverseKinematics ik(sc.r5b, {platform_target()}, o);
    if (!reference_path(
            *poses, std::string(scene) + " reference (collocation, mixed p=8 E=32)",
            [&](const Pose& p) { return ik.solve({p}); }, out, *inputs))
      return ref;
  }
  ref.ok = true;
  return ref;
}

/// Cold solves: a new solver object per solve (`solve` builds it), at least 3 and 0.3 s (quick: once,
/// 0.03 s), at most 50.
Repeats cold_repeats(const AllConfig& config) {
  return config.quick ? Repeats{1, 10, 0.03} : Repeats{3, 50, 0.3};
}

/// One collocation setting on the selected scenes; `cold` repeats the cold FK/IK solves.
void collocation_setting(const Scenes& sc, const References& ref, const AllConfig& config,
                         RodFormulation formulation, SolverKind solver, int degree, int elements, bool ik,
                         bool path, Recorder& out, const Repeats& cold, int tolerance_exponent = 10) {
  const KinematicsOptions o =
      collocation_options(formulation, degree, elements, solver, std::pow(10.0, -tolerance_exponent));
  // The library's default tolerance 1e-10 is left out of the name (rows comparable with older CSVs).
  const std::string settings =
      "p=" + std::to_string(degree) + ";E=" + std::to_string(elements) +
      (tolerance_exponent == 10 ? "" : ";tol=1e-" + std::to_string(tolerance_exponent));
  const std::string form = std::string("collocation-") + to_string(formulation) + "-";
  if (config.selected("R5a_fk_cold")) {
    RobotSolution s;
    const Timing t = time_repeated(
        [&] {
          ForwardKinematics fk(sc.r5a, o);
          s = fk.solve(sc.fk_inputs);
        },
        cold);
    const double error = s.summary.converged() ? (s.platforms[0].position - ref.fk_platform).norm() : NAN;
    out.record("R5a_fk_cold", form + to_string(solver), settings, error, t, s.summary.iterations,
               to_string(s.summary.status));
  }
  if (ik && config.selected("R5a_ik_cold")) {
    RobotSolution s;
    const Timing t = time_repeated(
        [&] {
          InverseKinematics ik(sc.r5a, {platform_target()}, o);
          s = ik.solve({sc.target});
        },
        cold);
    const double error = s.summary.converged() ? input_error(s.inputs, ref.ik_inputs) : NAN;
    // IK picks its solver itself (Newton for this square system inside the bounds): name the one used.
    out.record("R5a_ik_cold", form + (s.summary.solver.empty() ? to_string(solver) : s.summary.solver),
               settings, error, t, s.summary.iterations, to_string(s.summary.status));
  }
  // The path rows measure the inputs only: no centerline samples (the axial stretch check stays).
  KinematicsOptions path_options = o;
  path_options.read_centerline = false;
  for (const PathScene& scene : path ? path_scenes(sc, ref, config) : std::vector<PathScene>{}) {
    InverseKinematics ik(sc.r5b, {platform_target()}, path_options);
    std::string used = to_string(solver);
    const PathRun run = run_path(scene.poses, scene.reference, [&](const Pose& p) {
      RobotSolution s = ik.solve({p});
      if (!s.summary.solver.empty()) used = s.summary.solver;
      return s;
    });
    record_path(scene.name, run, form + used, settings, out);
  }
}

void collocation_sweep(const Scenes& sc, const References& ref, const AllConfig& config, Recorder& out) {
  const bool quick = config.quick;
  const std::vector<int> mixed_degrees = quick ? std::vector<int>{5} : std::vector<int>{3, 4, 5, 6};
  const std::vector<int> mixed_elements = quick ? std::vector<int>{4, 8, 16} : std::vector<int>{4, 8, 16, 32};
  // The path from 8 elements: at 4 (p = 5) warm solves fail along it, each failure retried by continuation
  // (6.5 s for the 41 poses of the quick path).
  // Newton tolerance as a setting (default 1e-10, 1e-8, 1e-6), as the shooting runs tie theirs to the
  // integration tolerance: iterations past the discretisation error buy nothing. On R5b the solver's share
  // of the input error is about 1e-2 x tolerance in m (p = 6, E = 32: 1.1e-10 m at 1e-10, 1.8e-10 m at
  // 1e-8, 9.9e-9 m at 1e-6 in benchmarks/results/all.csv).
  const std::vector<int> tolerance_exponents = quick ? std::vector<int>{10} : std::vector<int>{10, 8, 6};
  for (int p : mixed_degrees)
    for (int e : mixed_elements)
      for (int t : tolerance_exponents)
        collocation_setting(sc, ref, config, RodFormulation::Mixed, SolverKind::Newton, p, e, true, e >= 8,
                            out, cold_repeats(config), t);
  // Condensed form (the default for these rods; with R5a's gravity n, m read the integral of p), the
  // same meshes and tolerances, and 1e-7 (full run): on R5b the condensed solutions at 1e-6 are up to
  // ~1e-7 m off, and 1e-7 is the loosest tolerance that keeps p = 5, E = 16 below 1e-8 m.
  std::vector<int> condensed_exponents = tolerance_exponents;
  if (!quick) condensed_exponents.push_back(7);
  for (int p : mixed_degrees)
    for (int e : mixed_elements)
      for (int t : condensed_exponents)
        collocation_setting(sc, ref, config, RodFormulation::Condensed, SolverKind::Newton, p, e, true,
                            e >= 8, out, cold_repeats(config), t);
  // Coarse meshes (condensed, full run): on the R5b helix p = 5 with 5 elements reaches 1e-7 m and
  // p = 7, 8 with 4-6 elements 1e-8 m with 10-14 control points per rod, where E = 8 needs p = 5
  // (3e-7 m) and 1e-8 m p = 6, E = 16 (22 control points); also tolerance 1e-5, where the solver's
  // share of the error (~1e-2 x tolerance in m) stays below these meshes' discretisation error.
  if (!quick)
    for (int p : {5, 6, 7, 8})
      for (int e : {4, 5, 6})
        for (int t : {5, 6, 7})
          if (p >= 7 || e > 4)  // p <= 6 on 4 elements: in the sweep above
            collocation_setting(sc, ref, config, RodFormulation::Condensed, SolverKind::Newton, p, e, true,
                                true, out, cold_repeats(config), t);
  // Ipopt path: FK only (IK chooses its solver itself), fewer sizes: 10-60x slower than Newton on rods.
  for (int e : quick ? std::vector<int>{8} : std::vector<int>{4, 8, 16})
    collocation_setting(sc, ref, config, RodFormulation::Mixed, SolverKind::Ipopt, 5, e, false, false, out,
                        cold_repeats(config));
  // Primal form: locks on these slender rods (EA L^2 / EI = 4 L^2 / r^2 ~ 1e6): one cold FK at p = 4
  // with 4 and 8 elements, full run only (a failing primal FK took 7.7 s at E = 4, a failing primal IK
  // 22 s, so IK and the path are left out).
  if (!quick)
    for (int e : {4, 8})
      collocation_setting(sc, ref, config, RodFormulation::Primal, SolverKind::Newton, 4, e, false, false,
                          out, Repeats{1, 1, 0.0});
}

void shooting_sweep(const Scenes& sc, const References& ref, const AllConfig& config, Recorder& out) {
  struct Run {
    std::string method, settings;
    ShootingRobotOptions options;
  };
  std::vector<Run> runs;
  for (int n : config.quick ? std::vector<int>{20, 80} : std::vector<int>{10, 20, 40, 80, 160}) {
    ShootingRobotOptions o;
    o.integrator = IntegratorMethod::RK4;
    o.rk4_steps = n;
    o.tolerance = 1e-11;
    runs.push_back({"shooting-rk4", "N=" + std::to_string(n), o});
  }
  for (int e : config.quick ? std::vector<int>{6, 10} : std::vector<int>{4, 6, 8, 10, 12}) {
    ShootingRobotOptions o;
    o.integration_relative_tolerance = o.integration_absolute_tolerance = std::pow(10.0, -e);
    o.tolerance =
        std::clamp(1e-2 * o.integration_relative_tolerance, 1e-12, 1e-10);  // below the integration error
    runs.push_back({"shooting-dormand_prince", "tol=1e-" + std::to_string(e), o});
  }
  for (const Run& run : runs) {
    if (config.selected("R5a_fk_cold")) {
      RobotSolution s;
      const Timing t = time_repeated(
          [&] {
            ShootingRobotSolver solver(sc.r5a, run.options);
            s = solver.fk(sc.fk_inputs);
          },
          cold_repeats(config));
      const double error = s.summary.converged() ? (s.platforms[0].position - ref.fk_platform).norm() : NAN;
      out.record("R5a_fk_cold", run.method, run.settings, error, t, s.summary.iterations,
                 to_string(s.summary.status));
    }
    if (config.selected("R5a_ik_cold")) {
      RobotSolution s;
      const Timing t = time_repeated(
          [&] {
            ShootingRobotSolver solver(sc.r5a, run.options);
            s = solver.ik({sc.target});
          },
          cold_repeats(config));
      const double error = s.summary.converged() ? input_error(s.inputs, ref.ik_inputs) : NAN;
      out.record("R5a_ik_cold", run.method, run.settings, error, t, s.summary.iterations,
                 to_string(s.summary.status));
    }
    for (const PathScene& scene : path_scenes(sc, ref, config)) {
      ShootingRobotSolver solver(sc.r5b, run.options);
      record_path(scene.name,
                  run_path(scene.poses, scene.reference, [&](const Pose& p) { return solver.ik({p}); }),
                  run.method, run.settings, out);
    }
  }
}

}  // namespace

bool run_robot_scenes(const AllConfig& config, Recorder& out) {
  if (!config.selected("R5a_fk_cold") && !config.selected("R5a_ik_cold") && !config.selected("R5b_ik_path") &&
      !config.selected("R5b_helix_path"))
    return true;
  Scenes sc;
  sc.fk_inputs = r5a_moved_inputs(*sc.r5a);
  sc.target = r5a_target();
  // The scene's path has 100 steps out and back; the quick run takes the first 20 of them.
  sc.path = r5b_path(config.quick ? 20 : 100);
  // The helix: 400 new targets (quick: 40).
  sc.helix = r5b_helix_path(config.quick ? 40 : 400);
  bool ok = true;
  const References by_shooting = shooting_references(sc, config, out);
  if (by_shooting.ok)
    collocation_sweep(sc, by_shooting, config, out);
  else
    ok = false;
  const References by_collocation = collocation_references(sc, config, out);
  if (by_collocation.ok)
    shooting_sweep(sc, by_collocation, config, out);
  else
    ok = false;
  return ok;
}

}  // namespace pcr::bench
