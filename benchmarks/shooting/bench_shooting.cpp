// Run time against error of the single-rod shooting reference (RK4 with N steps, Dormand-Prince 5(4)
// with tolerance tol) on scenes R1 (end moment, phi = 2 pi), R2 (Bisshopp-Drucker, alpha = 10) and
// R3 (exact helix). Errors: max-abs centerline error against the analytic solution (R1, R3, at 101
// points) or the tip position error against a tight Dormand-Prince reference (R2, tol 1e-13).
// Every solve is cold (the solver's default start: the unloaded rod, zero base wrench) and does not
// store the trajectory.
// usage: bench_shooting [csv path = benchmarks/results/shooting.csv]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "pcr/math/so3.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"

using namespace pcr;

namespace {

struct Scene {
  std::string name;
  RodModel model;
  std::function<double(const ShootingSolution&)> error;
};

RodModel cantilever(double length, const Vec3& bending_torsion, const Vec3& shear_extension) {
  RodModel rod;
  rod.length = length;
  rod.bending_torsion_stiffness = bending_torsion;
  rod.shear_extension_stiffness = shear_extension;
  rod.base.kind = RodEndKind::Clamped;
  rod.tip.kind = RodEndKind::Free;
  return rod;
}

double centerline_error(const ShootingSolution& sol, double length,
                        const std::function<Vec3(double)>& exact) {
  double worst = 0.0;
  for (int i = 0; i <= 100; ++i) {
    const double s = length * i / 100.0;
    worst = std::max(worst, (sol.at(s).p - exact(s)).cwiseAbs().maxCoeff());
  }
  return worst;
}

std::vector<Scene> scenes() {
  std::vector<Scene> out;
  {  // R1: EI = 2, L = 1, EA = 100, GA = 50, M = 2 pi EI / L about e1: a full circle.
    RodModel rod = cantilever(1.0, Vec3(2, 2, 2), Vec3(50, 50, 100));
    const double k = 2 * M_PI;
    rod.tip.moment = Vec3(k * 2.0, 0, 0);
    out.push_back({"R1_phi_2pi", rod, [k](const ShootingSolution& sol) {
                     return centerline_error(sol, 1.0, [k](double s) {
                       return Vec3(0.0, -(1.0 - std::cos(k * s)) / k, std::sin(k * s) / k);
                     });
                   }});
  }
  {  // R2: EI = 1, L = 1, EA = GA = 1e8, P = 10 (alpha = 10); error against a tight reference.
    RodModel rod = cantilever(1.0, Vec3(1, 1, 1), Vec3::Constant(1e8));
    rod.tip.force = Vec3(10.0, 0, 0);
    ShootingOptions tight;
    tight.rel_tol = 1e-13;
    tight.abs_tol = 1e-15;
    tight.residual_tolerance = 1e-13;
    const ShootingSolution ref = solve_rod_shooting(rod, tight);
    if (!ref.summary.converged())
      std::fprintf(stderr, "R2 reference: %s\n", ref.summary.brief_report().c_str());
    const Vec3 tip = ref.tip.p;
    out.push_back({"R2_alpha_10", rod,
                   [tip](const ShootingSolution& sol) { return (sol.tip.p - tip).cwiseAbs().maxCoeff(); }});
  }
  {  // R3: E = 1, G = 0.5, circle r = 1, dead end moment EI kappa: helix of radius 10, pitch 25.
    RodModel rod;
    rod.length = 135.245580489;
    rod.set_material_and_section(Material{1.0, 0.5, 0.0}, CrossSection::circle(1.0));
    rod.base.kind = RodEndKind::Clamped;
    rod.tip.kind = RodEndKind::Free;
    const Vec3 kappa(0.086332350, 0.0, 0.034350551);
    rod.tip.moment = rod.bending_torsion_stiffness[0] * kappa;
    const double L = rod.length;
    out.push_back({"R3_helix", rod, [kappa, L](const ShootingSolution& sol) {
                     return centerline_error(sol, L, [kappa](double s) {
                       // int_0^s exp(t hat(kappa)) e3 dt by Rodrigues' formula.
                       const double k = kappa.norm();
                       const Mat3 A = hat(kappa / k);
                       return Vec3((s * Mat3::Identity() + (1.0 - std::cos(k * s)) / k * A +
                                    (s - std::sin(k * s) / k) * A * A) *
                                   Vec3::UnitZ());
                     });
                   }});
  }
  return out;
}

struct Timing {
  double median = 0, min = 0, max = 0;
};

Timing time_solves(const RodModel& model, const ShootingOptions& options) {
  std::vector<double> times;
  double total = 0.0;
  // At least 5 solves and 0.2 s, at most 2000 solves.
  while ((times.size() < 5 || total < 0.2) && times.size() < 2000) {
    const auto t0 = std::chrono::steady_clock::now();
    const ShootingSolution sol = solve_rod_shooting(model, options);
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    times.push_back(t);
    total += t;
  }
  std::sort(times.begin(), times.end());
  const size_t n = times.size();
  Timing timing;
  timing.median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  timing.min = times.front();
  timing.max = times.back();
  return timing;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "benchmarks/results/shooting.csv";
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  std::ofstream csv(path);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    return 1;
  }
  csv << "scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations\n";
  std::printf("%-12s %-15s %-10s %10s %12s %6s %s\n", "scene", "method", "settings", "error", "median [ms]",
              "iter", "status");
  for (const Scene& scene : scenes()) {
    std::vector<ShootingOptions> runs;
    std::vector<std::string> settings;
    for (int N : {10, 20, 40, 80, 160, 320, 640, 1000}) {
      ShootingOptions o;
      o.integrator = IntegratorMethod::RK4;
      o.rk4_steps = N;
      o.residual_tolerance = 1e-12;
      runs.push_back(o);
      settings.push_back("N=" + std::to_string(N));
    }
    for (int e = 3; e <= 12; ++e) {
      ShootingOptions o;
      o.integrator = IntegratorMethod::DormandPrince;
      o.rel_tol = o.abs_tol = std::pow(10.0, -e);
      // Newton stops well below the integration error (and above its step-size noise).
      o.residual_tolerance = std::max(1e-12, 1e-2 * o.rel_tol);
      runs.push_back(o);
      settings.push_back("tol=1e-" + std::to_string(e));
    }
    for (size_t i = 0; i < runs.size(); ++i) {
      ShootingOptions o = runs[i];
      const ShootingSolution sol = solve_rod_shooting(scene.model, o);
      const double error = sol.summary.converged() ? scene.error(sol) : NAN;
      o.store_trajectory = false;
      const Timing t = time_solves(scene.model, o);
      const char* method = o.integrator == IntegratorMethod::RK4 ? "rk4" : "dormand_prince";
      csv << scene.name << ',' << method << ',' << settings[i] << ',' << error << ',' << t.median << ','
          << t.min << ',' << t.max << ',' << sol.summary.iterations << '\n';
      std::printf("%-12s %-15s %-10s %10.2e %12.4f %6d %s\n", scene.name.c_str(), method, settings[i].c_str(),
                  error, 1e3 * t.median, sol.summary.iterations, to_string(sol.summary.status));
      std::fflush(stdout);
    }
  }
  std::printf("wrote %s\n", path.c_str());
  return 0;
}
