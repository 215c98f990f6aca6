#include "six_rus_rows.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "common/six_rus_scene.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/kinematics.hpp"

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

const SixRusMesh kReference{6, 32, 1e-11};
const char* kMethod = "collocation-condensed-newton";

void cold_rows(BenchCsv& csv, const SixRusMesh& mesh, const RobotSolution& fk_reference,
               const RobotSolution& ik_reference) {
  const auto heavy = load_six_rus(true), massless = load_six_rus(false);
  const KinematicsOptions o = mesh_options(mesh);
  double fk_error = 0, fk_rotation = 0, ik_error = 0;
  int fk_iterations = 0, ik_iterations = 0;
  const Timing fk = time_repeated(
      [&] {
        ForwardKinematics solver(heavy, o);  // cold: a new solver object each time (assembly included)
        const RobotSolution s = solver.solve(six_rus_readme_fk_inputs());
        fk_error = (s.platforms[0].position - fk_reference.platforms[0].position).norm();
        fk_rotation =
            so3_log(s.platforms[0].rotation().transpose() * fk_reference.platforms[0].rotation()).norm();
        fk_iterations = s.summary.iterations;
        if (!s.summary.converged()) fk_error = NAN;
      },
      {5, 20, 0.0});
  const Timing ik = time_repeated(
      [&] {
        InverseKinematics solver(massless, {platform()}, o);
        const RobotSolution s = solver.solve({six_rus_readme_ik_target()});
        ik_error = (s.inputs - ik_reference.inputs).lpNorm<Eigen::Infinity>();
        ik_iterations = s.summary.iterations;
        if (!s.summary.converged()) ik_error = NAN;
      },
      {5, 20, 0.0});
  csv.row("R6_FK_cold", kMethod, settings_of(mesh), fk_error, fk, fk_iterations);
  csv.row("R6_IK_cold", kMethod, settings_of(mesh), ik_error, ik, ik_iterations);
  std::printf("R6 FK cold  %-18s error %.2e m, %.2e rad  median %.2f ms (%d it)\n", settings_of(mesh).c_str(),
              fk_error, fk_rotation, fk.median * 1e3, fk_iterations);
  std::printf("R6 IK cold  %-18s error %.2e rad          median %.2f ms (%d it)   [%s]\n",
              settings_of(mesh).c_str(), ik_error, ik.median * 1e3, ik_iterations, kTheirFigure);
}

// Warm-started IK along the helix: per pass a new solver, cold at the first point (not timed), then
// warm along the other 199 (each from the previous solution).
void helix_row(BenchCsv& csv, const SixRusMesh& mesh, const std::vector<Pose>& helix,
               const std::vector<VecX>& reference) {
  const auto heavy = load_six_rus(true);
  std::vector<double> times;
  double error = 0;
  int iterations = 0, failures = 0, jacobians = 0;
  for (int pass = 0; pass < 3; ++pass) {
    InverseKinematics ik(heavy, {platform()}, mesh_options(mesh));
    ik.solve({helix[0]});
    for (size_t k = 1; k < helix.size(); ++k) {
      const auto t0 = Clock::now();
      const RobotSolution s = ik.solve({helix[k]});
      times.push_back(seconds_since(t0));
      iterations += s.summary.iterations;
      jacobians += s.summary.jacobian_evaluations;
      if (!s.summary.converged()) ++failures;
      error = std::max(error, (s.inputs - reference[k]).lpNorm<Eigen::Infinity>());
    }
  }
  const Timing t = summarise(times);
  if (failures > 0) error = NAN;
  csv.row("R6_helix_IK_warm", kMethod, settings_of(mesh), error, t, double(iterations) / times.size());
  std::printf(
      "R6 helix warm IK %-18s max input error %.2e rad  median %.3f ms/solve, mean %.3f ms/solve, "
      "%.2f it/solve, %d fresh Jacobians in %zu solves%s\n",
      settings_of(mesh).c_str(), error, t.median * 1e3, t.mean * 1e3, double(iterations) / times.size(),
      jacobians, times.size(), failures ? "  FAILURES" : "");
}

}  // namespace

int bench_six_rus(BenchCsv& csv) {
  ForwardKinematics fk_ref(load_six_rus(true), mesh_options(kReference));
  const RobotSolution fk_reference = fk_ref.solve(six_rus_readme_fk_inputs());
  InverseKinematics ik_ref(load_six_rus(false), {platform()}, mesh_options(kReference));
  const RobotSolution ik_reference = ik_ref.solve({six_rus_readme_ik_target()});
  if (!fk_reference.summary.converged() || !ik_reference.summary.converged()) {
    std::cerr << "bench_robots: R6 reference did not converge\n";
    return 1;
  }
  const Vec3 x = fk_reference.platforms[0].position;
  const VecX& u = ik_reference.inputs;
  std::printf(
      "R6 reference (%s): FK platform (%.9f, %.9f, %.9f) m; IK inputs %.8f %.8f %.8f %.8f %.8f %.8f rad\n",
      settings_of(kReference).c_str(), x.x(), x.y(), x.z(), u[0], u[1], u[2], u[3], u[4], u[5]);
  for (const SixRusMesh& mesh : {SixRusMesh{6, 4}, SixRusMesh{6, 8}, SixRusMesh{6, 16}})
    cold_rows(csv, mesh, fk_reference, ik_reference);

  const std::vector<Pose> helix = six_rus_helix(200);
  std::vector<VecX> reference;
  InverseKinematics ik(load_six_rus(true), {platform()}, mesh_options(kReference));
  for (const Pose& p : helix) {
    const RobotSolution s = ik.solve({p});
    if (!s.summary.converged()) {
      std::cerr << "bench_robots: R6 helix reference failed at " << p.position.transpose() << "\n";
      return 1;
    }
    reference.push_back(s.inputs);
  }
  for (const SixRusMesh& mesh : {SixRusMesh{6, 4}, SixRusMesh{6, 8}, SixRusMesh{6, 16},
                                 SixRusMesh{6, 8, 1e-8}, SixRusMesh{6, 8, 1e-6}})
    helix_row(csv, mesh, helix, reference);
  return 0;
}

}  // namespace pcr::bench
