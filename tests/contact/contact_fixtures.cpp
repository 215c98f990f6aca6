#include "contact_fixtures.hpp"

#include <chrono>
#include <cmath>

#include "pcr/solve/newton_solver.hpp"

namespace pcr::test {

double heavy_cantilever_touchdown(double H, double q, double EI, double kGA) {
  double l = std::pow(72.0 * EI * H / q, 0.25);
  for (int i = 0; i < 50; ++i) {
    const double f = q * std::pow(l, 4) / (72 * EI) + q * l * l / (6 * kGA) - H;
    const double df = q * std::pow(l, 3) / (18 * EI) + q * l / (3 * kGA);
    l -= f / df;
  }
  return l;
}

RodModel steel_cantilever(double length, const Vec3& gravity, const Vec3& tip_force) {
  RodModel m;
  m.name = "beam";
  m.length = length;
  m.set_material_and_section(Material::from_poisson_ratio(kYoungs, kPoisson, kDensity),
                             CrossSection::circle(kRadius));
  m.loads.gravity = gravity;
  m.base.kind = RodEndKind::Clamped;
  m.base.orientation = Quat(std::sqrt(0.5), 0.0, std::sqrt(0.5), 0.0);  // R_y(pi/2): d3 = +x
  m.tip.kind = RodEndKind::Free;
  m.tip.force = tip_force;
  return m;
}

RodDiscretization contact_discretization(int degree, int elements) {
  RodDiscretization d{RodFormulation::Mixed, degree, elements};
  d.contact_forces = true;
  return d;
}

std::unique_ptr<ContactSolve> solve_rod(const CollocationRod& rod, const RodContactOptions* options,
                                        int load_steps) {
  std::unique_ptr<ContactSolve> s;
  VecX x;
  const auto start = std::chrono::steady_clock::now();
  int iterations = 0;
  for (int step = 1; step <= load_steps; ++step) {
    s = std::make_unique<ContactSolve>();
    s->vars = rod.add_to_problem(s->problem, {}, static_cast<double>(step) / load_steps);
    if (options != nullptr) s->contact = add_rod_contact(s->problem, rod, s->vars, *options);
    s->x = step == 1 ? s->problem.initial_values() : x;
    NewtonOptions newton_options;
    newton_options.max_iterations = 100;
    NewtonSolver newton(s->problem, newton_options);
    s->summary = newton.solve(s->x);
    iterations += s->summary.iterations;
    if (!s->summary.converged()) break;
    x = s->x;
  }
  s->summary.iterations = iterations;
  s->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace pcr::test
