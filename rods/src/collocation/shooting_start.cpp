// A cold collocation solve from the stress-free shape needs many Newton iterations where the loaded rod
// is far from it (10 for R1's full circle, 16 for R3's helix: the quaternions must turn through large
// angles with full Newton steps). A coarse shooting solve costs a few integrations of 6 unknowns and
// lands within about its integration error of the equilibrium; the collocation Newton then converges
// quadratically from there. The collocation result is still the solution of the
// collocation equations at the solve's tolerance: the start changes the iteration count only.
#include "shooting_start.hpp"

#include "mesh_tables.hpp"

#include "pcr/core/error.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"

namespace pcr::collocation {
namespace {

constexpr int kCoarseSteps = 4, kShapeSteps = 16;

// Two fixed-step RK4 passes. A shape within about 1e-4 L of the equilibrium (16 steps on R1, R2, R3)
// starts the collocation Newton in its quadratic range (2 iterations there); what sets that is the
// sampled trajectory's accuracy, not the base state's: the base state of a 6-step solve, integrated
// once more with 16 steps, starts the collocation as well as the 16-step solve did (the same collocation
// iterations on R1, R2, R3 and the spring). So the iterations from rest run on few steps (kCoarseSteps:
// 4, each iteration's 13 x 7 variational integration the dearest part of the start; against 6 steps
// 5-8 % fewer instructions per cold solve on R1, R2 and R3, where R2 takes 5 collocation iterations
// instead of 3; 3 steps would save 3-4 % more but leave the two coils of R3 to 3 steps), and the shape is one
// integration of their base state on more (shape_pass), with no shooting iteration of its own: a shooting
// solve on the finer steps from that base state took 0 iterations on R1 and R3 and 1 on R2, whose one (13 x 7
// variational integrations) cost more than the collocation Newton's extra iterations from the unconverged
// shape (R2, p = 4, E = 2 and p = 5, E = 8: 3 iterations, 20 % fewer instructions per cold solve; R1, R3 and
// the spring 2-5 % fewer: no solver set-up). How many steps: where the shape lies within the collocation's
// own discretisation error of its solution, one Newton iteration reaches the tolerance, and that error falls
// with the element count E: 16 + E steps (kShapeSteps + E) take R1 (p = 6, E = 16 and 32) and R3 (p = 5, E =
// 64; p = 6, E = 128) to one collocation iteration instead of two (E and 32 + E steps do too on R1 E = 32 and
// R3; 16 do not; 24 do not on R1 E = 16, 48 not on R3 E = 64), for a pass that costs a few per cent of the
// solve. At most 8 shooting iterations (R1, R2, R3 take 4-7): a model whose shooting needs more (the
// pre-curved spring: 16) falls back to the stress-free start, which serves it well (5 iterations).
//
// Before the quadratic range the steps are capped (ShootingOptions::max_step), and each removes a
// roughly constant amount d of the residual: |r| then needs about |r| / d more steps. A step that
// removes less than 1/8 of |r| thus foretells more than the 8 allowed, and the start is given up at
// once (the stall test with a window of one iteration). The scaled |r|_2 falls by a factor of at most
// 0.69 (R1), 0.81 (R2) and 0.83 (R3) per iteration with 16 steps, all converging; on the spring by about
// 0.94 in the first (it would need 16), so the spring's start costs one shooting iteration.
ShootingOptions coarse_shooting() {
  ShootingOptions o;
  o.integrator = IntegratorMethod::RK4;
  o.rk4_steps = kCoarseSteps;
  o.tolerance = 1e-6;
  o.max_iterations = 8;
  o.stall_window = 1;
  o.stall_ratio = 1.0 - 1.0 / o.max_iterations;
  o.load_stepping = false;  // a hard problem: the collocation's own load stepping decides
  o.store_trajectory = false;
  return o;
}

// The shape pass: `base` integrated once by RK4 over `steps` equal steps with the abscissae `s` (ascending,
// from 0 to L) added to the mesh, so that the states there are integration nodes. Empty if the
// integration fails.
std::vector<ShootingState> shape_pass(const RodModel& model, const ShootingState& base,
                                      const std::vector<double>& s, int steps) {
  const double L = model.length, merge = 1e-9 * L;  // nodes closer than this are one node
  std::vector<double> mesh;
  std::vector<size_t> node_of(s.size());
  mesh.reserve(steps + s.size() + 1);
  size_t next = 0;
  for (int k = 0; k <= steps; ++k) {
    const double uniform = L * k / steps;
    for (; next < s.size() && s[next] <= uniform + merge; ++next) {
      if (mesh.empty() || s[next] > mesh.back() + merge) mesh.push_back(s[next]);
      node_of[next] = mesh.size() - 1;
    }
    if (uniform > mesh.back() + merge) mesh.push_back(uniform);
  }
  const RodOde ode(model);
  RodStateVector y = base.to_vector();
  RodTrajectory trajectory;
  const IntegrationReport report = integrate_rod_on_mesh(ode, mesh, y, IntegratorMethod::RK4, &trajectory);
  if (!report.success || trajectory.y.size() != mesh.size()) return {};
  std::vector<ShootingState> states;
  states.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i)
    states.push_back(ShootingState::from_vector(trajectory.y[node_of[i]]));
  return states;
}

}  // namespace

std::optional<VecX> shooting_start(const CollocationRod& rod) {
  const RodModel& model = rod.model();
  if (model.drawing_speed != 0.0) return std::nullopt;  // the unknowns are the effective N, M there
  const ShootingSolution coarse = solve_rod_shooting(model, coarse_shooting());
  if (!coarse.summary.converged()) return std::nullopt;
  const std::shared_ptr<const MeshTables> mesh =
      mesh_tables(rod.discretization().degree, rod.discretization().elements);
  const std::vector<double>& tau = mesh->greville;
  std::vector<double> s(tau.size());
  for (size_t i = 0; i < tau.size(); ++i) s[i] = tau[i] * model.length;
  const std::vector<ShootingState> states =
      shape_pass(model, coarse.base, s, kShapeSteps + rod.discretization().elements);
  if (states.size() != s.size()) return std::nullopt;
  const PointLayout& layout = rod.point_layout();
  const int n = rod.num_control_points(), cp = rod.control_point_size();
  MatX values = MatX::Zero(n, cp);
  Quat q_previous = states[0].q;
  for (int i = 0; i < n; ++i) {
    Quat q = states[i].q.normalized();
    if (q.dot(q_previous) < 0.0) q = -q;  // continuous sign along the rod
    q_previous = q;
    values.block<1, 3>(i, layout.p) = states[i].p.transpose();
    values.block<1, 4>(i, layout.q) = q.transpose();
    if (layout.n >= 0) values.block<1, 3>(i, layout.n) = states[i].n.transpose();
    if (layout.m >= 0) values.block<1, 3>(i, layout.m) = states[i].m.transpose();
  }
  // Control points interpolating these values at the Greville abscissae (the running integrals T of
  // the condensed form with loads are set from P by add_to_problem).
  MatX points;
  if (!interpolate_at_greville(*mesh, values, points)) return std::nullopt;
  VecX x = VecX::Zero(rod.configuration_size());
  for (int i = 0; i < n; ++i) x.segment(i * cp, cp) = points.row(i).transpose();
  if (rod.discretization().formulation == RodFormulation::Condensed) {
    // n(s) = n - f s and m(s) = h - (p(s) - c) x n(s) - ... (collocation_rod.hpp) at s = 0.
    const ShootingState& base = states[0];
    x.segment<3>(n * cp) = base.n;
    x.segment<3>(n * cp + 3) = base.m + (base.p - rod.moment_point()).cross(base.n);
  }
  if (!x.allFinite()) return std::nullopt;
  return x;
}

}  // namespace pcr::collocation
