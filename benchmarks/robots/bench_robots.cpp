// Run time against error of the collocation robot solver (issue "benchmarks"):
//  - R5a (models/stewart_gough.urdf): cold FK at the default inputs and cold IK to the scene target;
//  - R5b (models/stewart_gough_teleop.urdf): warm-started IK along the teleoperation path (from
//    (0, 0.02, 0.48) m in 100 steps of (0, 0.001, 0.001) m and back), solves per second.
// Error: max over the inputs (IK) or platform position (FK) against a reference computed in the same
// run with 32 elements of degree 5 (converged to < 1e-9 m, see README). CSV columns as the other
// benchmarks: scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations.
// usage: bench_robots [out.csv]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"

using namespace pcr;
using Clock = std::chrono::steady_clock;

namespace {

struct Timing {
  double median = 0, min = 0, max = 0;
};

Timing summarise(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  return {t[t.size() / 2], t.front(), t.back()};
}

KinematicsOptions options(int degree, int elements, double tolerance = 1e-10) {
  KinematicsOptions o;
  o.assembly.discretization = {RodFormulation::Mixed, degree, elements};
  o.tolerance = tolerance;
  return o;
}

std::vector<Pose> teleop_path() {
  std::vector<Pose> path;
  Pose p;
  p.position = Vec3(0.0, 0.02, 0.48);
  for (int k = 0; k <= 100; ++k) {
    path.push_back(p);
    p.position += Vec3(0.0, 0.001, 0.001);
  }
  for (int k = 99; k >= 0; --k) path.push_back(path[k]);
  return path;
}

LinkTarget platform_target() {
  LinkTarget t;
  t.link = "platform";
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string csv_path = argc > 1 ? argv[1] : "benchmarks/results/robots.csv";
  std::ofstream csv(csv_path);
  if (!csv) {
    std::cerr << "bench_robots: cannot write " << csv_path << "\n";
    return 2;
  }
  csv << "scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations\n";
  const std::string models = PCR_MODEL_DIR;
  const auto r5a = std::make_shared<const RobotModel>(load_robot_model(models + "/stewart_gough.urdf"));
  const auto r5b = std::make_shared<const RobotModel>(load_robot_model(models + "/stewart_gough_teleop.urdf"));
  const int elements[] = {2, 4, 8, 16};

  // R5a IK target: (0, 0, 0.4) m, R_y(10 deg).
  Pose target;
  target.position = Vec3(0, 0, 0.4);
  target.orientation = quat_from_rotation(rotation_y(10.0 * M_PI / 180.0));
  InverseKinematics ik_ref(r5a, {platform_target()}, options(5, 32, 1e-11));
  const RobotSolution ik_reference = ik_ref.solve({target});
  ForwardKinematics fk_ref(r5a, options(5, 32, 1e-11));
  const RobotSolution fk_reference = fk_ref.solve(r5a->default_input_values());
  if (!ik_reference.summary.converged() || !fk_reference.summary.converged()) {
    std::cerr << "bench_robots: reference did not converge\n";
    return 1;
  }
  for (int E : elements) {
    for (const char* problem : {"FK", "IK"}) {
      std::vector<double> times;
      double error = 0;
      int iterations = 0;
      for (int rep = 0; rep < 5; ++rep) {  // cold: a new solver object each time (assembly included)
        const auto t0 = Clock::now();
        RobotSolution s;
        if (std::string(problem) == "FK") {
          ForwardKinematics fk(r5a, options(5, E));
          s = fk.solve(r5a->default_input_values());
          error = (s.platforms[0].position - fk_reference.platforms[0].position).norm();
        } else {
          InverseKinematics ik(r5a, {platform_target()}, options(5, E));
          s = ik.solve({target});
          error = (s.inputs - ik_reference.inputs).lpNorm<Eigen::Infinity>();
        }
        times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
        iterations = s.summary.iterations;
        if (!s.summary.converged()) error = INFINITY;
      }
      const Timing t = summarise(times);
      csv << "R5a_" << problem << "_cold,collocation-mixed-newton,p=5;E=" << E << "," << error << "," << t.median << ","
          << t.min << "," << t.max << "," << iterations << "\n";
      std::printf("R5a %s cold  p=5 E=%2d  error %.2e m  median %.2f ms\n", problem, E, error, t.median * 1e3);
    }
  }

  // R5b teleoperation: reference inputs along the path at 32 elements, then timed warm solves.
  const std::vector<Pose> path = teleop_path();
  std::vector<VecX> reference;
  {
    InverseKinematics ik(r5b, {platform_target()}, options(5, 32, 1e-11));
    for (const Pose& p : path) {
      const RobotSolution s = ik.solve({p});
      if (!s.summary.converged()) {
        std::cerr << "bench_robots: R5b reference failed at " << p.position.transpose() << "\n";
        return 1;
      }
      reference.push_back(s.inputs);
    }
  }
  for (int E : elements) {
    InverseKinematics ik(r5b, {platform_target()}, options(5, E));
    ik.solve({path[0]});  // start of the path (cold), not timed
    std::vector<double> times;
    double error = 0;
    int iterations = 0, failures = 0;
    for (int pass = 0; pass < 3; ++pass) {
      for (size_t k = 1; k < path.size(); ++k) {
        const auto t0 = Clock::now();
        const RobotSolution s = ik.solve({path[k]});
        times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
        iterations += s.summary.iterations;
        if (!s.summary.converged()) ++failures;
        error = std::max(error, (s.inputs - reference[k]).lpNorm<Eigen::Infinity>());
      }
    }
    const Timing t = summarise(times);
    if (failures > 0) error = INFINITY;
    csv << "R5b_teleop_IK_warm,collocation-mixed-newton,p=5;E=" << E << "," << error << "," << t.median << "," << t.min
        << "," << t.max << "," << double(iterations) / times.size() << "\n";
    std::printf("R5b warm IK p=5 E=%2d  max input error %.2e m  median %.3f ms/solve (%.0f solves/s), %.2f it/solve%s\n",
                E, error, t.median * 1e3, 1.0 / t.median, double(iterations) / times.size(),
                failures ? "  FAILURES" : "");
  }
  std::cout << "wrote " << csv_path << "\n";
  return 0;
}
