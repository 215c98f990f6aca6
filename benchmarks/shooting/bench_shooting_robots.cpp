// Speed and accuracy of the robot shooting solver (pcr/robots/shooting/shooting_robot_solver.hpp) on
// the Stewart-Gough scenes (/work/shared/scenes/README.md):
//  - R5a_fk_cold, R5a_ik_cold: FK at moved inputs / IK to the R5a target ((0, 0, 0.4), R_y(10 deg)),
//    each solve from the cold guess; error = platform position error [m] (FK) or max input error [m]
//    (IK) against Dormand-Prince at 1e-12;
//  - R5b_ik_path: the teleoperation path, target (0, 0.02, 0.48) + i (0, 0.001, 0.001), i = 0..100
//    and back (200 solves), orientation identity, each IK warm-started from the previous; error = max
//    input error along the path against converged Dormand-Prince 1e-12 solves; times per warm solve
//    (the first, cold, solve excluded), iterations = the most any warm solve took, solves/s = warm
//    solves / their total time.
// Residual tolerance 1e-10 (scaled) for the timed solves.
// usage: bench_shooting_robots [csv path = benchmarks/results/shooting_robots.csv]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/shooting/shooting_robot_solver.hpp"
#include "pcr/robots/urdf_loader.hpp"

using namespace pcr;

namespace {

struct Timing {
  double median = 0, min = 0, max = 0;
};

Timing summarise(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  const size_t n = t.size();
  return {n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]), t.front(), t.back()};
}

struct Method {
  std::string name, settings;
  ShootingRobotOptions options;
};

std::vector<Method> methods() {
  std::vector<Method> out;
  for (int n : {20, 40}) {
    ShootingRobotOptions o;
    o.integrator = IntegratorMethod::RK4;
    o.rk4_steps = n;
    out.push_back({"rk4", "N=" + std::to_string(n), o});
  }
  for (double tol : {1e-6, 1e-8, 1e-10}) {
    ShootingRobotOptions o;
    o.rel_tol = o.abs_tol = tol;
    char s[32];
    std::snprintf(s, sizeof s, "tol=%g", tol);
    out.push_back({"dormand_prince", s, o});
  }
  return out;
}

ShootingRobotOptions reference_options() {
  ShootingRobotOptions o;
  o.rel_tol = o.abs_tol = 1e-12;
  o.residual_tolerance = 1e-12;
  return o;
}

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<Pose> teleop_path() {
  std::vector<Pose> path;
  for (int i = 0; i <= 100; ++i) {
    Pose p;
    p.position = Vec3(0, 0.02 + 0.001 * i, 0.48 + 0.001 * i);
    path.push_back(p);
  }
  for (int i = 99; i >= 1; --i) path.push_back(path[i]);  // back, 200 solves in all
  return path;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "benchmarks/results/shooting_robots.csv";
  std::ofstream csv(csv_path);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", csv_path.c_str());
    return 1;
  }
  csv << "scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations\n";
  std::printf("%-12s %-15s %-10s %10s %12s %10s %10s %5s %s\n", "scene", "method", "settings", "error",
              "median [ms]", "min [ms]", "max [ms]", "it", "solves/s");
  auto row = [&](const std::string& scene, const Method& m, double error, const Timing& t, int iterations,
                 double rate) {
    csv << scene << ',' << m.name << ',' << m.settings << ',' << error << ',' << t.median << ',' << t.min
        << ',' << t.max << ',' << iterations << '\n';
    std::printf("%-12s %-15s %-10s %10.2e %12.3f %10.3f %10.3f %5d %.0f\n", scene.c_str(), m.name.c_str(),
                m.settings.c_str(), error, 1e3 * t.median, 1e3 * t.min, 1e3 * t.max, iterations, rate);
    std::fflush(stdout);
  };

  const std::string dir = PCR_MODEL_DIR;
  const auto r5a = std::make_shared<const RobotModel>(load_robot_model(dir + "/stewart_gough.urdf"));
  const auto r5b = std::make_shared<const RobotModel>(load_robot_model(dir + "/stewart_gough_teleop.urdf"));

  // R5a references.
  VecX u = r5a->default_input_values();
  const double pattern[] = {1.0, -0.6, 0.35, -0.8, 0.5, -0.2};
  for (int i = 0; i < u.size(); ++i) u[i] += 0.005 * pattern[i];
  Pose target;
  target.position = Vec3(0, 0, 0.4);
  target.orientation = quat_from_rotation(rotation_y(10.0 * M_PI / 180.0));
  ShootingRobotSolver ref_a(r5a, reference_options());
  const ShootingRobotResult fk_ref = ref_a.fk(u);
  const ShootingRobotResult ik_ref = ref_a.ik({target});
  if (!fk_ref.summary.converged() || !ik_ref.summary.converged()) {
    std::fprintf(stderr, "R5a reference failed\n");
    return 1;
  }
  const int repeats = 21;
  for (const Method& m : methods()) {
    ShootingRobotSolver solver(r5a, m.options);
    std::vector<double> t;
    double error = 0.0;
    int iterations = 0;
    for (int k = 0; k < repeats; ++k) {
      solver.reset();
      const auto t0 = std::chrono::steady_clock::now();
      const ShootingRobotResult s = solver.fk(u);
      t.push_back(seconds(t0));
      error =
          s.summary.converged() ? (s.platforms[0].position - fk_ref.platforms[0].position).norm() : INFINITY;
      iterations = s.summary.iterations;
    }
    const Timing tm = summarise(t);
    row("R5a_fk_cold", m, error, tm, iterations, 1.0 / tm.median);
  }
  for (const Method& m : methods()) {
    ShootingRobotSolver solver(r5a, m.options);
    std::vector<double> t;
    double error = 0.0;
    int iterations = 0;
    for (int k = 0; k < repeats; ++k) {
      solver.reset();
      const auto t0 = std::chrono::steady_clock::now();
      const ShootingRobotResult s = solver.ik({target});
      t.push_back(seconds(t0));
      error = s.summary.converged() ? (s.inputs - ik_ref.inputs).lpNorm<Eigen::Infinity>() : INFINITY;
      iterations = s.summary.iterations;
    }
    const Timing tm = summarise(t);
    row("R5a_ik_cold", m, error, tm, iterations, 1.0 / tm.median);
  }

  // R5b path: converged references, then warm-started runs (the first solve of each run is cold).
  const std::vector<Pose> path = teleop_path();
  std::vector<VecX> reference;
  {
    ShootingRobotSolver ref_b(r5b, reference_options());
    for (const Pose& p : path) {
      const ShootingRobotResult s = ref_b.ik({p});
      if (!s.summary.converged()) {
        std::fprintf(stderr, "R5b reference failed at (%g, %g, %g)\n", p.position.x(), p.position.y(),
                     p.position.z());
        return 1;
      }
      reference.push_back(s.inputs);
    }
  }
  for (const Method& m : methods()) {
    ShootingRobotSolver solver(r5b, m.options);
    std::vector<double> t;
    double error = 0.0;
    int iterations = 0;
    double total = 0.0;
    for (size_t i = 0; i < path.size(); ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      const ShootingRobotResult s = solver.ik({path[i]});
      const double dt = seconds(t0);
      if (i > 0) {  // warm-started solves only
        t.push_back(dt);
        total += dt;
      }
      error = std::max(
          error, s.summary.converged() ? (s.inputs - reference[i]).lpNorm<Eigen::Infinity>() : INFINITY);
      if (i > 0) iterations = std::max(iterations, s.summary.iterations);
    }
    row("R5b_ik_path", m, error, summarise(t), iterations, static_cast<double>(t.size()) / total);
  }
  return 0;
}
