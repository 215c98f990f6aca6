#include "common/rod_scenes.hpp"

#include <algorithm>
#include <cmath>

#include "pcr/core/error.hpp"
#include "rods/rod_fixtures.hpp"

namespace pcr::bench {

RodScene r1_full_circle() {
  RodScene scene;
  scene.name = "R1_phi_2pi";
  scene.model = test::cantilever(1.0, Vec3(50, 50, 100), Vec3(2, 2, 2));
  const Vec3 kappa(2 * M_PI, 0, 0);
  scene.model.tip.moment = 2.0 * kappa;  // EI kappa
  scene.exact_centerline = [kappa](double s) { return test::constant_curvature_position(kappa, s); };
  return scene;
}

RodScene r2_elastica(double axial_shear_stiffness) {
  RodScene scene;
  scene.name = "R2_alpha_10";
  scene.model = test::cantilever(1.0, Vec3::Constant(axial_shear_stiffness), Vec3(1, 1, 1));
  scene.model.tip.force = Vec3(10.0, 0, 0);
  if (axial_shear_stiffness >= 1e12) {  // extensibility effect <= 1e-11 (header)
    const test::Elastica exact = test::bisshopp_drucker(10.0);
    const Vec3 tip(exact.lateral, 0.0, 1.0 - exact.axial);
    scene.exact_tip = [tip] { return tip; };
  }
  return scene;
}

RodScene r3_helix() {
  RodScene scene;
  scene.name = "R3_helix";
  const double L = 135.245580489, EI = M_PI / 4;
  scene.model = test::cantilever(L, Vec3(M_PI / 2, M_PI / 2, M_PI), Vec3(EI, EI, EI));
  const Vec3 kappa(0.086332350, 0.0, 0.034350551);
  scene.model.tip.moment = EI * kappa;
  scene.exact_centerline = [kappa](double s) { return test::constant_curvature_position(kappa, s); };
  return scene;
}

RodScene helical_spring_large_load() {
  const test::HelicalSpring spring = test::helical_spring(20.0);
  RodScene scene;
  scene.name = "spring_20deg";
  scene.model = spring.model(1e6, 2.0 * spring.radius / spring.compliance);
  scene.model.name = "helical spring";
  return scene;
}

double exact_error(const RodScene& scene, const std::function<Vec3(double)>& centerline, int points) {
  require(scene.has_exact(), "scene ", scene.name, " has no exact solution");
  const double L = scene.model.length;
  if (!scene.exact_centerline) return (centerline(L) - scene.exact_tip()).norm();
  require(points >= 2, "exact_error: points must be >= 2, got ", points);
  double worst = 0.0;
  for (int i = 0; i < points; ++i) {
    const double s = L * i / (points - 1);
    worst = std::max(worst, (centerline(s) - scene.exact_centerline(s)).norm());
  }
  return worst;
}

/// Full sweep (bench_rods, bench_all): R3 (two coils over L = 135) needs twice the elements of R1 and R2
/// for the same error. Ipopt (a general NLP solver on this square system, 10-100x slower than Newton
/// here) runs on fewer sizes, without the coarsest meshes, where it falls back to slow load stepping.
/// The primal form locks on the slender R2, R3 and spring (EA L^2 / EI = 1e14, 7e4, 4e8): there it
/// fails or converges to a locked, far too stiff rod at every size measured, each attempt costing
/// seconds, so it runs on the smaller sizes only. The spring (three coils) needs load stepping from the
/// straight rod at every size (300-500 Newton iterations, 0.3-8 s per solve at 8-128 elements with
/// Newton, 5 s with Ipopt at 16, bench_all --quick): fewer sizes, so that bench_all stays within ~10 min.
std::vector<int> collocation_element_counts(const std::string& scene, RodFormulation formulation,
                                            SolverKind solver, bool quick) {
  const bool locking = formulation == RodFormulation::Primal && scene != "R1_phi_2pi";
  const bool newton = solver == SolverKind::Newton;
  if (scene == "spring_20deg") {
    if (locking) return newton ? std::vector<int>{8} : std::vector<int>{};
    if (quick) return newton ? std::vector<int>{8, 32} : std::vector<int>{};
    return newton ? std::vector<int>{8, 16, 32, 64, 128} : std::vector<int>{16};
  }
  std::vector<int> counts;
  if (newton) {
    if (quick)
      counts = locking ? std::vector<int>{4} : std::vector<int>{4, 16, 64};
    else
      counts = locking ? std::vector<int>{2, 4, 8, 16} : std::vector<int>{2, 4, 8, 16, 32, 64, 128};
  } else {
    if (quick)
      counts = locking ? std::vector<int>{} : std::vector<int>{8};
    else
      counts = locking ? std::vector<int>{4} : std::vector<int>{4, 8, 16, 32};
  }
  if (scene == "R3_helix") {
    for (int& e : counts) e *= 2;
    if (!quick && !newton && !locking) counts.pop_back();  // 2-12 s per solve at 64
  }
  return counts;
}

}  // namespace pcr::bench
