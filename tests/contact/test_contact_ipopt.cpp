// Contact solved by Ipopt in Scholtes' relaxation (contact_ipopt.hpp) against the semismooth Newton
// method (rod_contact.hpp) and the beam-theory references of test_contact: the relaxed rows' Jacobians
// against finite differences, a heavy cantilever on a plane and a propped cantilever on an edge.
#define BOOST_TEST_MODULE contact_ipopt
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "contact_fixtures.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/kinematics_option_names.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/rods/contact_ipopt.hpp"
#include "pcr/solve/jacobian_check.hpp"

using namespace pcr;

namespace {

const double kPi = std::acos(-1.0);
const double kArea = kPi * test::kRadius * test::kRadius;
const double kEI = kArea * test::kRadius * test::kRadius / 4.0 * test::kYoungs;  // E pi r^4 / 4
const double kGA = test::kYoungs / (2.0 * (1.0 + test::kPoisson)) * kArea;       // k G A, k = 1

Obstacle obstacle(const std::string& name, ObstacleShape shape, const Vec3& point, const Vec3& direction) {
  Obstacle o;
  o.name = name;
  o.shape = shape;
  o.position = point;
  o.direction = direction;
  return o;
}

// The rod's problem with relaxed contact rows (GapOnly, then relax_rod_contact).
struct RelaxedRod {
  Problem problem;
  RodVariables vars;
  RodContactVariables contact;
  RelaxedRod(const CollocationRod& rod, RodContactOptions options) {
    options.function = ComplementarityFunction::GapOnly;
    vars = rod.add_to_problem(problem);
    contact = add_rod_contact(problem, rod, vars, options);
    relax_rod_contact(problem, rod, contact);
  }
};

struct IpoptSolve {
  std::unique_ptr<RelaxedRod> relaxed;
  VecX x;
  SolveSummary summary;
};

// From the straight rod, the default homotopy (ContactIpoptOptions) to the Newton tolerance 1e-10.
IpoptSolve solve_by_ipopt(const CollocationRod& rod, const RodContactOptions& options) {
  IpoptSolve s;
  s.relaxed = std::make_unique<RelaxedRod>(rod, options);
  s.x = s.relaxed->problem.initial_values();
  const ContactIpoptOptions o;
  IpoptSolver solver(s.relaxed->problem, contact_ipopt_options(o));
  s.summary = solve_contact_homotopy(s.relaxed->problem, {&s.relaxed->contact}, solver, o, s.x);
  return s;
}

// Residual max-abs of the semismooth (Fischer-Burmeister) system at the Ipopt solution: the variables of
// the relaxed problem are those of the semismooth one followed by mu.
double semismooth_residual(const test::ContactSolve& semismooth, const IpoptSolve& ipopt) {
  const int n = semismooth.problem.num_variables();
  BOOST_TEST_REQUIRE(ipopt.x.size() == n + 1);
  VecX r;
  semismooth.problem.evaluate_residuals(ipopt.x.head(n), r);
  return r.lpNorm<Eigen::Infinity>();
}

// Where gap and force vanish together the relaxed product a b <= mu + tol / S leaves both up to
// sqrt(mu + tol / S); the Fischer-Burmeister value there is 2 a b / (a + b + |(a, b)|) <= sqrt(a b). With
// the last mu 1e-14, the tolerance 1e-10 of ContactIpoptOptions and S = kRelaxedProductScale: sqrt(2e-14).
const double kProductBound = 1e-14 + 1e-10 / kRelaxedProductScale;
const double kComplementarityBound = std::sqrt(kProductBound);

}  // namespace

BOOST_AUTO_TEST_CASE(relaxed_contact_jacobians_match_finite_differences) {
  // The relaxed blocks (gap rows, product rows, mu column) of distributed obstacles (plane, sphere) and a
  // sharp edge, at a perturbed state with positive multipliers and a contact section inside a cell (the
  // kinks of the shares lie at the midpoints, beyond the difference step 1e-6 from u_c = 0.331).
  const CollocationRod rod(test::steel_cantilever(0.3, Vec3(0, 0, -9.81), Vec3(0, 0, -0.01)),
                           test::contact_discretization(4, 6));
  Obstacle ball = obstacle("ball", ObstacleShape::Sphere, Vec3(0.2, 0, -0.03), Vec3::UnitZ());
  ball.radius = 0.02;
  RodContactOptions options{
      {obstacle("floor", ObstacleShape::HalfSpace, Vec3(0, 0, -0.01), Vec3::UnitZ()), ball,
       obstacle("edge", ObstacleShape::Edge, Vec3(0.1, 0, -0.003), Vec3::UnitY())},
      test::kRadius};
  RelaxedRod r(rod, options);
  BOOST_TEST(r.contact.relaxed_blocks.size() == r.contact.blocks.size() + 1);
  VecX x = r.problem.initial_values();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * unit(rng);
  for (int offset : r.contact.multiplier_offsets)
    for (int k = 0; k < 2; ++k) x[offset + k] = 0.5 + 0.4 * unit(rng);
  const int sharp = r.contact.sharp_offsets[0];
  x[sharp] = 0.331, x[sharp + 1] = 0.7;
  x[r.problem.variable(r.contact.relaxation).offset] = 1e-3;
  const JacobianCheckResult check = check_problem_jacobian(r.problem, x);
  BOOST_TEST(check.passed, check.to_string());
  // The bounds: gap rows >= 0, product rows <= 0, multipliers >= 0.
  const VecX lower = r.problem.row_lower(), upper = r.problem.row_upper();
  const int row = r.problem.row_offset(r.contact.relaxed_blocks[0]);  // 3 balance rows, 2 gaps, 2 products
  BOOST_TEST(lower[row + 3] == 0.0);
  BOOST_TEST(std::isinf(upper[row + 3]));
  BOOST_TEST(upper[row + 5] == 0.0);
  BOOST_TEST(std::isinf(lower[row + 5]));
  BOOST_TEST(r.problem.variable(r.contact.multipliers[0]).lower.minCoeff() == 0.0);
}

namespace {

const double kWeight = test::kDensity * kArea * 9.81;  // q = rho A g [N/m]

// Touchdown length l of a heavy cantilever on a plane H below its clamp (test_contact's
// heavy_cantilever_on_a_plane reference).
double touchdown_length(double H) {
  return test::heavy_cantilever_touchdown(H, kWeight, kEI, kGA);
}

}  // namespace

BOOST_AUTO_TEST_CASE(heavy_cantilever_on_a_plane_by_both_methods) {
  // test_contact's case (1 m steel rod, floor 1 mm below the clamp, from the straight rod whose free sag
  // would be 0.2 m) with 16 elements of degree 4: both methods meet the beam-theory bounds of that test,
  // and the Ipopt solution solves the semismooth system to the relaxation's bound (the semismooth Newton
  // method fails on this case with 32 elements: bench_contact_methods).
  const double H = 1e-3, L = 1.0, q = kWeight, h = L / 16, l = touchdown_length(H);
  const CollocationRod rod(test::steel_cantilever(L, Vec3(0, 0, -9.81), Vec3::Zero()),
                           test::contact_discretization(4, 16));
  Obstacle floor = obstacle("floor", ObstacleShape::HalfSpace, Vec3(0, 0, -H - test::kRadius), Vec3::UnitZ());
  const RodContactOptions options{{floor}, test::kRadius};
  const auto semismooth = test::solve_rod(rod, &options);
  const IpoptSolve ipopt = solve_by_ipopt(rod, options);
  BOOST_TEST_REQUIRE(semismooth->summary.converged(), semismooth->summary.message);
  BOOST_TEST_REQUIRE(ipopt.summary.converged(), ipopt.summary.message);
  BOOST_TEST_MESSAGE("plane, 16 elements: semismooth " << semismooth->summary.iterations << " iterations "
                                                       << semismooth->seconds << " s; ipopt "
                                                       << ipopt.summary.iterations << " iterations "
                                                       << ipopt.summary.wall_time_seconds << " s");
  BOOST_TEST(semismooth_residual(*semismooth, ipopt) <= kComplementarityBound);
  for (int m = 0; m < 2; ++m) {
    const VecX& x = m == 0 ? semismooth->x : ipopt.x;
    const RodVariables& vars = m == 0 ? semismooth->vars : ipopt.relaxed->vars;
    const RodContactVariables& contact = m == 0 ? semismooth->contact : ipopt.relaxed->contact;
    const std::vector<ObstacleContact> c = read_rod_contact(rod, vars, contact, x);
    BOOST_TEST_REQUIRE(c[0].intervals.size() == 1u);
    const ContactInterval& in = c[0].intervals[0];
    const RodState base = rod.state_at(x, vars, 0.0);
    BOOST_TEST_MESSAGE((m == 0 ? "semismooth" : "ipopt")
                       << ": touchdown " << in.s_begin << " (reference " << l << "), clamp force "
                       << base.force.z() << ", moment " << base.moment.y());
    // The bounds of test_contact (touchdown to two cells, clamp reactions to their share of them, the
    // flat part on the plane to the solver tolerance).
    BOOST_TEST(std::abs(in.s_begin - l) <= 2 * h);
    BOOST_TEST(std::abs(-base.force.z() - 2 * q * l / 3) <= 4 * q * h / 3);
    BOOST_TEST(std::abs(std::abs(base.moment.y()) - q * l * l / 6) <= 2 * q * l * h / 3);
    BOOST_TEST(std::abs(-base.force.z() + in.force.z() - q * L) <= q * h);
    // The flat part lies on the plane: the midpoints carrying at least half the weight touch it to the
    // solver tolerance (1e-10 L; Ipopt: L kProductBound / b with b = q L0 / F0 = 1.5, far below).
    for (size_t j = 0; j < c[0].densities.size(); ++j)
      if (c[0].densities[j] >= 0.5 * q) BOOST_TEST(std::abs(c[0].gaps[j]) <= 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(propped_cantilever_on_an_edge_by_both_methods) {
  // test_contact_edges' propped cantilever with an overhang (Timoshenko beam theory, superposition: the
  // prop R cancels the deflection of the cantilever under q at x = a), 16 elements of degree 4: both
  // methods within that test's bound (h / a)^2 R, the rod carrying the whole force.
  const double L = 0.5, a = 0.4, g = 0.981, q = test::kDensity * kArea * g, h = L / 16;
  const double wq = q * a * a * (6 * L * L - 4 * L * a + a * a) / (24 * kEI) + q * (L * a - a * a / 2) / kGA;
  const double R = wq / (std::pow(a, 3) / (3 * kEI) + a / kGA);
  const CollocationRod rod(test::steel_cantilever(L, Vec3(0, 0, -g), Vec3::Zero()),
                           test::contact_discretization(4, 16));
  const RodContactOptions options{
      {obstacle("edge", ObstacleShape::Edge, Vec3(a, 0, -test::kRadius), Vec3::UnitY())}, test::kRadius};
  const auto semismooth = test::solve_rod(rod, &options);
  const IpoptSolve ipopt = solve_by_ipopt(rod, options);
  BOOST_TEST_REQUIRE(semismooth->summary.converged(), semismooth->summary.message);
  BOOST_TEST_REQUIRE(ipopt.summary.converged(), ipopt.summary.message);
  BOOST_TEST_MESSAGE("edge, 16 elements: semismooth "
                     << semismooth->summary.iterations << " iterations " << semismooth->seconds
                     << " s; ipopt " << ipopt.summary.iterations << " iterations "
                     << ipopt.summary.wall_time_seconds << " s, " << ipopt.summary.message);
  BOOST_TEST(semismooth_residual(*semismooth, ipopt) <= kComplementarityBound);
  double forces[2];
  for (int m = 0; m < 2; ++m) {
    const VecX& x = m == 0 ? semismooth->x : ipopt.x;
    const RodVariables& vars = m == 0 ? semismooth->vars : ipopt.relaxed->vars;
    const RodContactVariables& contact = m == 0 ? semismooth->contact : ipopt.relaxed->contact;
    const std::vector<ObstacleContact> c = read_rod_contact(rod, vars, contact, x);
    BOOST_TEST_REQUIRE(c[0].intervals.size() == 1u);
    const ContactInterval& point = c[0].intervals[0];
    const RodState base = rod.state_at(x, vars, 0.0);
    forces[m] = point.force.z();
    BOOST_TEST_MESSAGE((m == 0 ? "semismooth" : "ipopt")
                       << ": R " << point.force.z() << " (reference " << R << ") at s = " << point.centroid);
    BOOST_TEST(std::abs(point.force.z() - R) <= R * (h / a) * (h / a));
    BOOST_TEST(std::abs(base.moment.y() - (q * L * L / 2 - R * a)) <= R * a * (h / a) * (h / a));
    BOOST_TEST(std::abs(-base.force.z() + point.force.z() - q * L) <= 1e-9 * kEI / (L * L));
  }
  // R = k (w_q(a) - gap) with the stiffness k = 1 / (a^3 / (3 EI) + a / kGA) of the cantilever at the prop:
  // the reactions differ by k times the gaps the two solutions leave. Ipopt: a b <= kProductBound with
  // b = R L0 / F0, so gap <= L0 kProductBound / b; semismooth: |phi_FB| <= tol gives a gap up to
  // tol / (2 - sqrt 2) L0 (Tseng's bound, test_contact).
  const double L0 = rod.length_scale(), b = R * L0 / rod.force_scale(),
               k = 1.0 / (std::pow(a, 3) / (3 * kEI) + a / kGA);
  const double gaps = L0 * kProductBound / b + L0 * 1e-10 / (2.0 - std::sqrt(2.0));
  BOOST_TEST_MESSAGE("reaction difference " << forces[1] - forces[0] << " N, bound " << k * gaps << " N");
  BOOST_TEST(std::abs(forces[1] - forces[0]) <= k * gaps);
}

BOOST_AUTO_TEST_CASE(planar_post_by_both_methods) {
  // models/planar_post.urdf (a pre-curved rod of a planar robot lying on a round post, 24 elements) by
  // FK at the default inputs with contact_method semismooth and ipopt (the word option of the pcr tool).
  const auto model = std::make_shared<const RobotModel>(load_robot_model(PCR_MODEL_DIR "/planar_post.urdf"));
  RobotSolution solutions[2];
  for (int m = 0; m < 2; ++m) {
    KinematicsOptions o;
    set_kinematics_option(o, "contact_method", m == 0 ? "semismooth" : "ipopt");
    BOOST_TEST((o.assembly.contact_method == ContactMethod::Ipopt) == (m == 1));
    ForwardKinematics fk(model, o);
    solutions[m] = fk.solve(model->default_input_values());
    BOOST_TEST_REQUIRE(solutions[m].summary.converged(), solutions[m].summary.message);
    BOOST_TEST_MESSAGE((m == 0 ? "semismooth: " : "ipopt: ") << solutions[m].summary.brief_report());
  }
  Vec3 force[2] = {Vec3::Zero(), Vec3::Zero()};
  for (int m = 0; m < 2; ++m)
    for (const ObstacleContact& c : solutions[m].contacts) force[m] += c.force;
  const double dx = (solutions[1].platforms[0].position - solutions[0].platforms[0].position).norm();
  BOOST_TEST_MESSAGE("platform distance " << dx << " m, contact force " << force[0].transpose() << " / "
                                          << force[1].transpose() << " N");
  BOOST_TEST(force[0].norm() > 0.1);  // the rod lies on the post (0.146 N, docs/contact.md)
  // Same discrete problem: the solutions differ by what the two stopping rules leave, the gaps of the
  // active pairs (below L0 (mu + tol) / b, the test above) times the robot's compliance.
  BOOST_TEST(dx <= 1e-6);
  BOOST_TEST((force[1] - force[0]).norm() <= 1e-6 * force[0].norm());
  // Inverse kinematics needs the square system of the semismooth rows.
  KinematicsOptions o;
  o.assembly.contact_method = ContactMethod::Ipopt;
  LinkTarget target;
  target.link = "platform";
  target.mode = LinkTarget::Mode::Position;
  target.pose = solutions[0].platforms[0];
  try {
    InverseKinematics ik(model, {target}, o);
    BOOST_ERROR("inverse kinematics accepted contact_method ipopt");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("contact_method ipopt") != std::string::npos, e.what());
  }
}
