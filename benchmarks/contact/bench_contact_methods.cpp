// The two contact solvers (docs/contact.md, "Solvers compared"): the semismooth Newton method
// (Fischer-Burmeister rows, pcr's Newton) and Ipopt in Scholtes' relaxation (contact_ipopt.hpp), on
//  - plane: a heavy steel cantilever (r = 1 mm, L = 1 m, degree 4) on a floor H below its clamp, from
//    the straight rod; error = |clamp force - 2 q l / 3| (Timoshenko beam theory with the touchdown l, the
//    reference of tests/contact), relative to 2 q l / 3;
//  - edge: the propped cantilever with an overhang (L = 0.5 m, prop at a, g / 10) of tests/contact;
//    error = |R - R_beam| / R_beam;
//  - post: models/planar_post.urdf by cold FK (new FK object per solve) at random inputs; error =
//    platform distance between the two methods' solutions [m] (no reference: both solve the same
//    discrete problem), "within 1 %": the two platforms within 1 cm.
// Mesh sweep: the nominal case per mesh (time, iterations, error). Robustness: `runs` perturbed cases
// (plane: H in [0.5, 5] mm and gravity scaled by [0.5, 2]; edge: a in [0.3, 0.48] m and gravity scaled
// by [0.5, 2]; post: inputs uniform within +-30 % of their ranges around the defaults), converged
// fraction, median time and iterations. Times are wall clock of one solve (machine load applies: compare
// the two methods' times of one run).
// Usage: bench_contact_methods [runs=20]   (prints Markdown tables; docs/benchmarks.md "Contact solvers")
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/rods/contact_ipopt.hpp"
#include "pcr/solve/newton_solver.hpp"

namespace {

using namespace pcr;

const double kPi = std::acos(-1.0);
const double kE = 200e9, kNu = 0.3, kRho = 7850.0, kR = 1e-3;
const double kArea = kPi * kR * kR, kEI = kE * kArea * kR * kR / 4.0, kGA = kE / (2 * (1 + kNu)) * kArea;

RodModel cantilever(double length, double g) {
  RodModel m;
  m.name = "beam";
  m.length = length;
  m.set_material_and_section(Material::from_poisson_ratio(kE, kNu, kRho), CrossSection::circle(kR));
  m.loads.gravity = Vec3(0, 0, -g);
  m.base.kind = RodEndKind::Clamped;
  m.base.orientation = Quat(std::sqrt(0.5), 0.0, std::sqrt(0.5), 0.0);  // tangent +x
  m.tip.kind = RodEndKind::Free;
  return m;
}

Obstacle obstacle(ObstacleShape shape, const Vec3& point, const Vec3& direction) {
  Obstacle o;
  o.name = "obstacle";
  o.shape = shape;
  o.position = point;
  o.direction = direction;
  return o;
}

struct Run {
  bool converged = false;
  double seconds = 0.0, error = NAN;
  int iterations = 0;
};

// One cold solve of the rod with the obstacle by `method`, from the straight rod; error(x, rod, vars).
Run solve(const CollocationRod& rod, const Obstacle& o, ContactMethod method,
          const std::function<double(const CollocationRod&, const RodVariables&, const VecX&)>& error) {
  const auto start = std::chrono::steady_clock::now();
  Problem problem;
  const RodVariables vars = rod.add_to_problem(problem);
  RodContactOptions options{{o}, kR};
  if (method == ContactMethod::Ipopt) options.function = ComplementarityFunction::GapOnly;
  RodContactVariables contact = add_rod_contact(problem, rod, vars, options);
  VecX x;
  SolveSummary s;
  if (method == ContactMethod::Ipopt) {
    relax_rod_contact(problem, rod, contact);
    x = problem.initial_values();
    const ContactIpoptOptions co;
    IpoptSolver solver(problem, contact_ipopt_options(co));
    s = solve_contact_homotopy(problem, {&contact}, solver, co, x);
  } else {
    x = problem.initial_values();
    NewtonOptions no;
    no.max_iterations = 100;  // as tests/contact
    NewtonSolver newton(problem, no);
    s = newton.solve(x);
  }
  Run r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.converged = s.converged();
  r.iterations = s.iterations;
  if (r.converged) r.error = error(rod, vars, x);
  return r;
}

// Plane: clamp force against 2 q l / 3 with q l^4 / (72 EI) + q l^2 / (6 kGA) = H.
Run plane(int elements, double H, double g, ContactMethod method) {
  const double q = kRho * kArea * g;
  double l = std::pow(72.0 * kEI * H / q, 0.25);
  for (int i = 0; i < 50; ++i)
    l -= (q * std::pow(l, 4) / (72 * kEI) + q * l * l / (6 * kGA) - H) /
         (q * std::pow(l, 3) / (18 * kEI) + q * l / (3 * kGA));
  RodDiscretization d{RodFormulation::Mixed, 4, elements};
  d.contact_forces = true;
  const CollocationRod rod(cantilever(1.0, g), d);
  return solve(rod, obstacle(ObstacleShape::HalfSpace, Vec3(0, 0, -H - kR), Vec3::UnitZ()), method,
               [&](const CollocationRod& r, const RodVariables& v, const VecX& x) {
                 return std::abs(-r.state_at(x, v, 0.0).force.z() / (2 * q * l / 3) - 1.0);
               });
}

// Edge: the prop's reaction R against w_q(a) / (a^3 / (3 EI) + a / kGA) (tests/contact).
Run edge(int elements, double a, double g, ContactMethod method) {
  const double L = 0.5, q = kRho * kArea * g;
  const double wq = q * a * a * (6 * L * L - 4 * L * a + a * a) / (24 * kEI) + q * (L * a - a * a / 2) / kGA;
  const double R = wq / (std::pow(a, 3) / (3 * kEI) + a / kGA);
  RodDiscretization d{RodFormulation::Mixed, 4, elements};
  d.contact_forces = true;
  const CollocationRod rod(cantilever(L, g), d);
  return solve(rod, obstacle(ObstacleShape::Edge, Vec3(a, 0, -kR), Vec3::UnitY()), method,
               [&](const CollocationRod& r, const RodVariables& v, const VecX& x) {
                 // Clamp force + R = q L (the rod carries the whole force): R from the clamp.
                 return std::abs((q * L + r.state_at(x, v, 0.0).force.z()) / R - 1.0);
               });
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Summary {
  int converged = 0, runs = 0, right = 0;  // right: converged within 1 % of the reference
  std::vector<double> seconds, iterations, errors;
  void add(const Run& r) {
    ++runs;
    if (!r.converged) return;
    ++converged;
    if (std::isfinite(r.error) && r.error <= 1e-2) ++right;
    seconds.push_back(r.seconds);
    iterations.push_back(r.iterations);
    errors.push_back(r.error);
  }
};

void print_robustness(const char* scene, const char* method, const Summary& s) {
  std::printf("| %s | %s | %d/%d | %d | %.1f ms | %.0f | %.1e |\n", scene, method, s.converged, s.runs,
              s.right, 1e3 * median(s.seconds), median(s.iterations),
              s.errors.empty() ? NAN : *std::max_element(s.errors.begin(), s.errors.end()));
}

// planar_post FK at the given inputs with a new FK object: (run, platform position).
std::pair<Run, Vec3> post(const std::shared_ptr<const RobotModel>& model, const VecX& inputs,
                          ContactMethod method) {
  KinematicsOptions o;
  o.assembly.contact_method = method;
  const auto start = std::chrono::steady_clock::now();
  ForwardKinematics fk(model, o);
  const RobotSolution s = fk.solve(inputs);
  Run r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.converged = s.summary.converged();
  r.iterations = s.summary.iterations;
  return {r, r.converged ? s.platforms[0].position : Vec3::Constant(NAN)};
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
  const ContactMethod methods[] = {ContactMethod::Semismooth, ContactMethod::Ipopt};
  std::printf("Mesh sweep (nominal cases: plane H = 1 mm, g = 9.81; edge a = 0.4 m, g = 0.981)\n\n");
  std::printf("| scene | E | semismooth time | its | error | ipopt time | its | error | time ratio |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (int elements : {16, 32, 64}) {
    for (int scene = 0; scene < 2; ++scene) {
      Run r[2];
      for (int m = 0; m < 2; ++m)
        r[m] = scene == 0 ? plane(elements, 1e-3, 9.81, methods[m]) : edge(elements, 0.4, 0.981, methods[m]);
      std::printf("| %s | %d | %.1f ms | %d%s | %.1e | %.1f ms | %d%s | %.1e | %.2f |\n",
                  scene == 0 ? "plane" : "edge", elements, 1e3 * r[0].seconds, r[0].iterations,
                  r[0].converged ? "" : " (failed)", r[0].error, 1e3 * r[1].seconds, r[1].iterations,
                  r[1].converged ? "" : " (failed)", r[1].error, r[1].seconds / r[0].seconds);
      std::fflush(stdout);
    }
  }
  std::printf(
      "\nRobustness (%d perturbed cases each, 32 elements; error: the largest relative error of the "
      "converged runs; within 1 %%: converged runs with an error below 1e-2)\n\n| scene | method | converged "
      "| within 1 %% | median time | median its | max error |\n"
      "|---|---|---|---|---|---|---|\n",
      runs);
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::array<double, 2>> plane_cases, edge_cases;
  for (int i = 0; i < runs; ++i) {
    plane_cases.push_back({0.5e-3 + 4.5e-3 * unit(rng), 9.81 * (0.5 + 1.5 * unit(rng))});
    edge_cases.push_back({0.3 + 0.18 * unit(rng), 0.981 * (0.5 + 1.5 * unit(rng))});
  }
  for (int m = 0; m < 2; ++m) {
    Summary s;
    for (const auto& c : plane_cases) s.add(plane(32, c[0], c[1], methods[m]));
    print_robustness("plane", to_string(methods[m]), s);
    std::fflush(stdout);
  }
  for (int m = 0; m < 2; ++m) {
    Summary s;
    for (const auto& c : edge_cases) s.add(edge(32, c[0], c[1], methods[m]));
    print_robustness("edge", to_string(methods[m]), s);
    std::fflush(stdout);
  }
  const auto model =
      std::make_shared<const RobotModel>(load_robot_model(std::string(PCR_MODEL_DIR) + "/planar_post.urdf"));
  const VecX u0 = model->default_input_values();
  Summary post_summary[2];
  double largest_difference = 0.0;
  for (int i = 0; i < runs; ++i) {
    VecX u = u0;
    for (int k = 0; k < u.size(); ++k) {
      const ActuationInput& in = model->inputs()[k];
      const double span =
          std::isfinite(in.upper - in.lower) ? in.upper - in.lower : 2 * std::max(std::abs(u0[k]), 1e-2);
      u[k] = std::clamp(u0[k] + 0.3 * span * (unit(rng) - 0.5), in.lower, in.upper);
    }
    auto a = post(model, u, methods[0]), b = post(model, u, methods[1]);
    if (a.first.converged && b.first.converged) a.first.error = b.first.error = (a.second - b.second).norm();
    post_summary[0].add(a.first);
    post_summary[1].add(b.first);
    if (a.first.converged && b.first.converged)
      largest_difference = std::max(largest_difference, (a.second - b.second).norm());
  }
  for (int m = 0; m < 2; ++m) print_robustness("post (FK)", to_string(methods[m]), post_summary[m]);
  std::printf("\npost: largest platform distance between the two methods (both converged): %.2e m\n",
              largest_difference);
  return 0;
}
