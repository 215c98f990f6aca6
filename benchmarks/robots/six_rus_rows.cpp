#include "six_rus_rows.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "common/robot_scenes.hpp"
#include "common/six_rus_scene.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/shooting/shooting_robot_solver.hpp"

namespace pcr::bench {
namespace {

using Clock = std::chrono::steady_clock;

// The published Python shooting code's time per IK (their README: mean 3.82 s, standard deviation
// 1.15 s over 4000 workspace samples; Python 3.8, CPU not stated). Quoted, not measured here.
constexpr const char* kTheirFigure = "their figure (README, Python shooting): 3.82 s +- 1.15 s per IK";

struct SixRusMesh {
  int degree, elements;
  double tolerance = 1e-10;
};

// The default assembly (rods mixed by slenderness and solved in the condensed form) at a given mesh.
KinematicsOptions mesh_options(const SixRusMesh& mesh) {
  KinematicsOptions o;
  o.assembly.discretization.degree = mesh.degree;
  o.assembly.discretization.elements = mesh.elements;
  o.tolerance = mesh.tolerance;
  return o;
}

std::string settings_of(const SixRusMesh& mesh) {
  char s[64];
  std::snprintf(s, sizeof s, "p=%d;E=%d", mesh.degree, mesh.elements);
  std::string text = s;
  if (mesh.tolerance != 1e-10) {
    std::snprintf(s, sizeof s, ";tol=%g", mesh.tolerance);
    text += s;
  }
  return text;
}

LinkTarget platform() {
  LinkTarget t;
  t.link = "platform";
  return t;
}

const char* kMethod = "collocation-condensed-newton";

// The shooting reference (Dormand-Prince 1e-12, tolerance 1e-12; its universal joint rows are
// independent of collocation's, test_joint_crosscheck): FK at their README FK inputs, IK to their
// README target, IK along the helix.
struct References {
  RobotSolution fk, ik;
  std::vector<VecX> helix;
};

// One cold FK and one cold IK by `solve_fk` / `solve_ik` (each builds its solver), errors against the
// references: platform position [m] and rotation [rad] (FK), max input error [rad] (IK).
struct ColdErrors {
  double fk = 0, fk_rotation = 0, ik = 0;
  int fk_iterations = 0, ik_iterations = 0;
};

void record_fk(const RobotSolution& s, const References& r, ColdErrors& e) {
  e.fk = s.summary.converged() ? (s.platforms[0].position - r.fk.platforms[0].position).norm() : NAN;
  e.fk_rotation = so3_log(s.platforms[0].rotation().transpose() * r.fk.platforms[0].rotation()).norm();
  e.fk_iterations = s.summary.iterations;
}

void record_ik(const RobotSolution& s, const References& r, ColdErrors& e) {
  e.ik = s.summary.converged() ? (s.inputs - r.ik.inputs).lpNorm<Eigen::Infinity>() : NAN;
  e.ik_iterations = s.summary.iterations;
}

void print_cold(BenchCsv& csv, const char* method, const std::string& settings, const ColdErrors& e,
                const Timing& fk, const Timing& ik) {
  csv.row("R6_FK_cold", method, settings, e.fk, fk, e.fk_iterations);
  csv.row("R6_IK_cold", method, settings, e.ik, ik, e.ik_iterations);
  std::printf("R6 FK cold  %-30s %-18s error %.2e m, %.2e rad  median %.2f ms (%d it)\n", method,
              settings.c_str(), e.fk, e.fk_rotation, fk.median * 1e3, e.fk_iterations);
  std::printf("R6 IK cold  %-30s %-18s error %.2e rad          median %.2f ms (%d it)\n", method,
              settings.c_str(), e.ik, ik.median * 1e3, e.ik_iterations);
}

// Warm IK along the helix by `solve(k)` (k >= 1, after an untimed cold solve at point 0 by `start`),
// three passes; the max input error against the reference.
template <class Start, class Solve>
void helix_passes(BenchCsv& csv, const char* method, const std::string& settings, const References& r,
                  Start start, Solve solve) {
  std::vector<double> times;
  double error = 0;
  int iterations = 0, failures = 0, jacobians = 0;
  for (int pass = 0; pass < 3; ++pass) {
    start();
    for (size_t k = 1; k < r.helix.size(); ++k) {
      const auto t0 = Clock::now();
      const RobotSolution s = solve(k);
      times.push_back(seconds_since(t0));
      iterations += s.summary.iterations;
      jacobians += s.summary.jacobian_evaluations;
      if (!s.summary.converged()) ++failures;
      error = std::max(error, (s.inputs - r.helix[k]).lpNorm<Eigen::Infinity>());
    }
  }
  const Timing t = summarise(times);
  if (failures > 0) error = NAN;
  csv.row("R6_helix_IK_warm", method, settings, error, t, double(iterations) / times.size());
  std::printf(
      "R6 helix warm IK %-30s %-18s max input error %.2e rad  median %.3f ms/solve, mean %.3f ms/solve, "
      "%.2f it/solve, %d fresh Jacobians in %zu solves%s\n",
      method, settings.c_str(), error, t.median * 1e3, t.mean * 1e3, double(iterations) / times.size(),
      jacobians, times.size(), failures ? "  FAILURES" : "");
}

void collocation_rows(BenchCsv& csv, const SixRusMesh& mesh, const References& r) {
  const auto heavy = load_six_rus(true), massless = load_six_rus(false);
  const KinematicsOptions o = mesh_options(mesh);
  ColdErrors e;
  const Timing fk = time_repeated(
      [&] { record_fk(ForwardKinematics(heavy, o).solve(six_rus_readme_fk_inputs()), r, e); }, {5, 20, 0.0});
  const Timing ik = time_repeated(
      [&] {
        record_ik(InverseKinematics(massless, {platform()}, o).solve({six_rus_readme_ik_target()}), r, e);
      },
      {5, 20, 0.0});
  print_cold(csv, kMethod, settings_of(mesh), e, fk, ik);
}

void collocation_helix(BenchCsv& csv, const SixRusMesh& mesh, const std::vector<Pose>& helix,
                       const References& r) {
  const auto heavy = load_six_rus(true);
  std::unique_ptr<InverseKinematics> ik;
  helix_passes(
      csv, kMethod, settings_of(mesh), r,
      [&] {
        ik = std::make_unique<InverseKinematics>(heavy, std::vector<LinkTarget>{platform()},
                                                 mesh_options(mesh));
        ik->solve({helix[0]});
      },
      [&](size_t k) { return ik->solve({helix[k]}); });
}

void shooting_rows(BenchCsv& csv, const ShootingMethod& m, const std::vector<Pose>& helix,
                   const References& r) {
  const auto heavy = load_six_rus(true), massless = load_six_rus(false);
  ColdErrors e;
  const Timing fk = time_repeated(
      [&] { record_fk(ShootingRobotSolver(heavy, m.options).fk(six_rus_readme_fk_inputs()), r, e); },
      {5, 20, 0.0});
  const Timing ik = time_repeated(
      [&] { record_ik(ShootingRobotSolver(massless, m.options).ik({six_rus_readme_ik_target()}), r, e); },
      {5, 20, 0.0});
  const std::string method = "shooting-" + m.name;
  print_cold(csv, method.c_str(), m.settings, e, fk, ik);
  std::unique_ptr<ShootingRobotSolver> solver;
  helix_passes(
      csv, method.c_str(), m.settings, r,
      [&] {
        solver = std::make_unique<ShootingRobotSolver>(heavy, m.options);
        solver->ik({helix[0]});
      },
      [&](size_t k) { return solver->ik({helix[k]}); });
}

// False (with a message) when a reference solve failed.
bool shooting_references(const std::vector<Pose>& helix, References& r) {
  const ShootingRobotOptions tight = shooting_reference_options();
  r.fk = ShootingRobotSolver(load_six_rus(true), tight).fk(six_rus_readme_fk_inputs());
  r.ik = ShootingRobotSolver(load_six_rus(false), tight).ik({six_rus_readme_ik_target()});
  if (!r.fk.summary.converged() || !r.ik.summary.converged()) {
    std::cerr << "bench_robots: R6 shooting reference did not converge\n";
    return false;
  }
  ShootingRobotSolver path(load_six_rus(true), tight);
  for (const Pose& p : helix) {
    const RobotSolution s = path.ik({p});
    if (!s.summary.converged()) {
      std::cerr << "bench_robots: R6 helix reference failed at " << p.position.transpose() << "\n";
      return false;
    }
    r.helix.push_back(s.inputs);
  }
  return true;
}

}  // namespace

int bench_six_rus(BenchCsv& csv) {
  const std::vector<Pose> helix = six_rus_helix(200);
  References r;
  if (!shooting_references(helix, r)) return 1;
  const Vec3 x = r.fk.platforms[0].position;
  const VecX& u = r.ik.inputs;
  std::printf(
      "R6 shooting reference (Dormand-Prince 1e-12): FK platform (%.9f, %.9f, %.9f) m; IK inputs %.8f %.8f "
      "%.8f %.8f %.8f %.8f rad; %s\n",
      x.x(), x.y(), x.z(), u[0], u[1], u[2], u[3], u[4], u[5], kTheirFigure);
  for (const SixRusMesh& mesh :
       {SixRusMesh{6, 4}, SixRusMesh{6, 8}, SixRusMesh{6, 16}, SixRusMesh{6, 32, 1e-11}})
    collocation_rows(csv, mesh, r);
  for (const SixRusMesh& mesh : {SixRusMesh{6, 4}, SixRusMesh{6, 8}, SixRusMesh{6, 16},
                                 SixRusMesh{6, 8, 1e-8}, SixRusMesh{6, 8, 1e-6}})
    collocation_helix(csv, mesh, helix, r);
  for (const ShootingMethod& m : shooting_methods({40})) shooting_rows(csv, m, helix, r);
  return 0;
}

}  // namespace pcr::bench
