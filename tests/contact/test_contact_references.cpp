// Contact cases with closed-form references from beam theory, computed here independently of pcr:
//  - a heavy cantilever lying on a rigid plane (touchdown length, clamp reactions, deflection);
//  - a cantilever wrapped on a rigid cylinder by a tip load (contact arc, clamp moment, tip deflection);
// and the two complementarity functions compared on the first.
// Steel, r = 1 mm (contact_fixtures.hpp). Discretisation: degree 4; the collocated densities resolve an
// interval end to one cell L (tau_{j+1} - tau_j) (rod_contact.hpp), so ends are compared to one cell and
// resultants and displacements to the cell's share of them.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "contact_fixtures.hpp"
#include "pcr/core/error.hpp"

using namespace pcr;

namespace {

const double kPi = std::acos(-1.0);
const double kEI = kPi * 1e-12 / 4.0 * test::kYoungs;                            // E pi r^4 / 4
const double kGA = test::kYoungs / (2.0 * (1.0 + test::kPoisson)) * kPi * 1e-6;  // k G A, k = 1
const double kWeight = test::kDensity * kPi * 1e-6 * 9.81;                       // q = rho A g [N/m]

Obstacle floor_at(double z) {
  Obstacle o;
  o.name = "floor";
  o.shape = ObstacleShape::HalfSpace;
  o.position = Vec3(0, 0, z);
  o.direction = Vec3::UnitZ();
  return o;
}

// Largest cell L (tau_{j+1} - tau_j) of the rod.
double largest_cell(const CollocationRod& rod) {
  const std::vector<double> tau = rod.knots().greville();
  double h = 0.0;
  for (size_t j = 0; j + 1 < tau.size(); ++j) h = std::max(h, tau[j + 1] - tau[j]);
  return h * rod.model().length;
}

// Heavy cantilever on a plane (clamp at height H above the centerline's resting level), Timoshenko beam
// (test::heavy_cantilever_touchdown).
double touchdown_length(double H) {
  return test::heavy_cantilever_touchdown(H, kWeight, kEI, kGA);
}

struct PlaneCase {
  double H = 1e-3, L = 1.0;
  int elements = 64;
  CollocationRod rod;
  std::unique_ptr<test::ContactSolve> solve;
  explicit PlaneCase(ComplementarityFunction f, int load_steps = 1, int e = 64)
      : elements(e),
        rod(test::steel_cantilever(L, Vec3(0, 0, -9.81), Vec3::Zero()), test::contact_discretization(4, e)) {
    RodContactOptions options{{floor_at(-H - test::kRadius)}, test::kRadius, f};
    solve = test::solve_rod(rod, &options, load_steps);
  }
};

// The Fischer-Burmeister solve of the plane case, shared by the tests (solved once).
const PlaneCase& plane_case() {
  static const PlaneCase c(ComplementarityFunction::FischerBurmeister);
  return c;
}

}  // namespace

BOOST_AUTO_TEST_CASE(heavy_cantilever_on_a_plane) {
  const PlaneCase& c = plane_case();
  BOOST_TEST_REQUIRE(c.solve->summary.converged(), c.solve->summary.message);
  const double l = touchdown_length(c.H), q = kWeight, h = largest_cell(c.rod);
  const std::vector<ObstacleContact> contact =
      read_rod_contact(c.rod, c.solve->vars, c.solve->contact, c.solve->x);
  BOOST_TEST_REQUIRE(contact.size() == 1u);
  BOOST_TEST_REQUIRE(contact[0].intervals.size() == 1u);
  const ContactInterval& in = contact[0].intervals[0];
  BOOST_TEST_MESSAGE("plane: touchdown " << in.s_begin << " (reference " << l << ", cell " << h << "), end "
                                         << in.s_end << ", resultant " << in.force.transpose());
  // Interval: from the touchdown to the free end. The point reaction q l / 3 at the touchdown is spread
  // over the cell that holds it and its neighbour (rod_contact.hpp): two cells.
  BOOST_TEST(std::abs(in.s_begin - l) <= 2 * h);
  BOOST_TEST(in.s_end == c.L, boost::test_tools::tolerance(1e-12));
  // Clamp reactions (the wrench of the rod on its clamp is -n(0), -m(0)): the touchdown position enters
  // them as 2 q l / 3 and q l^2 / 6, so the two cells of touchdown error allow 4 q h / 3 and 2 q l h / 3.
  const RodState base = c.rod.state_at(c.solve->x, c.solve->vars, 0.0);
  BOOST_TEST_MESSAGE("plane: clamp force " << base.force.z() << " (reference " << 2 * q * l / 3
                                           << "), moment " << base.moment.y() << " (reference "
                                           << q * l * l / 6 << ")");
  BOOST_TEST(std::abs(-base.force.z() - 2 * q * l / 3) <= 4 * q * h / 3);
  BOOST_TEST(std::abs(std::abs(base.moment.y()) - q * l * l / 6) <= 2 * q * l * h / 3);
  // Equilibrium of the whole rod: clamp force + contact resultant = weight, to the midpoint quadrature of
  // the densities (their sum over cells; the point reaction q l / 3 lies in one cell: within q h).
  BOOST_TEST(std::abs(-base.force.z() + in.force.z() - q * c.L) <= q * h);
  // The flat part lies on the plane (gap 0 to the solver tolerance 1e-10 L) and carries q per length.
  const RodState tip = c.rod.state_at(c.solve->x, c.solve->vars, c.L);
  BOOST_TEST(std::abs(tip.position.z() + c.H) <= 1e-9);
  // Between the midpoints, where the gap is not enforced, the centerline may dip into the plane by about
  // w''' h^3 / 48 with the jump of w''' = q l / (3 EI) at the touchdown (a cubic through zero gaps one cell
  // apart); bound: 3 times that.
  BOOST_TEST(contact[0].min_gap >= -q * l / (3 * kEI) * h * h * h / 16);
  // Deflection at l / 2, Euler-Bernoulli: w(x) = -q x^4 / (24 EI) + q l x^3 / (9 EI) - q l^2 x^2 / (12 EI),
  // w(l / 2) = -(11 / 16) H for l = (72 EI H / q)^(1/4); with the Timoshenko l the shear sag (q l^2 / (6 kGA)
  // = 2e-5 H) is left out of the reference. w depends on the touchdown only through l, with
  // d w(l / 2) / d l = -q l^3 / (36 EI) = -2 H / l at fixed x; the touchdown is resolved to two cells
  // (above): 2 H / l * 2 h = 0.134 H, bound 0.15 H.
  const RodState mid = c.rod.state_at(c.solve->x, c.solve->vars, l / 2);
  const double x = mid.position.x(), w_ref = -q * std::pow(x, 4) / (24 * kEI) +
                                             q * l * std::pow(x, 3) / (9 * kEI) -
                                             q * l * l * x * x / (12 * kEI);
  BOOST_TEST_MESSAGE("plane: w(l/2) " << mid.position.z() << " (reference " << w_ref << ")");
  BOOST_TEST(std::abs(mid.position.z() - w_ref) <= 0.15 * c.H);
}

BOOST_AUTO_TEST_CASE(cantilever_wrapped_on_a_cylinder) {
  // Clamped tangent to the top of a rigid cylinder (axis y, centerline radius rho = R_c + r = 10.001 m),
  // tip dead load P downwards. Linear theory (notes in the header): on the contact arc [0, a] the
  // curvature is 1 / rho, the moment EI / rho and the shear force 0; a = L - EI / (P rho), a point force
  // P at s = a; tip deflection a^2 / (2 rho) + a (L - a) / rho + P (L - a)^3 / (3 EI) + P (L - a) / kGA
  // (Singh, "Planar equilibria of an elastic rod wrapped around a circular capstan", J. Elasticity 151
  // (2022) 321-346, for the arc-and-point-force structure of frictionless wrapping).
  const double L = 0.2, P = 0.2, rho = 10.001, r = test::kRadius;
  const CollocationRod rod(test::steel_cantilever(L, Vec3::Zero(), Vec3(0, 0, -P)),
                           test::contact_discretization(4, 64));
  Obstacle cylinder;
  cylinder.name = "drum";
  cylinder.shape = ObstacleShape::Cylinder;
  cylinder.position = Vec3(0, 0, -rho);
  cylinder.direction = Vec3::UnitY();
  cylinder.radius = rho - r;
  RodContactOptions options{{cylinder}, r};
  const auto s = test::solve_rod(rod, &options);
  BOOST_TEST_REQUIRE(s->summary.converged(), s->summary.message);
  const double a = L - kEI / (P * rho), h = largest_cell(rod), phi = a / rho;
  const std::vector<ObstacleContact> c = read_rod_contact(rod, s->vars, s->contact, s->x);
  BOOST_TEST_REQUIRE(c[0].intervals.size() == 1u);
  const ContactInterval& in = c[0].intervals[0];
  BOOST_TEST_MESSAGE("cylinder: arc [" << in.s_begin << ", " << in.s_end << "] (reference a = " << a
                                       << ", cell " << h << "), resultant " << in.force.transpose());
  BOOST_TEST(in.s_begin <= h);  // from the clamp (the first cell may carry no force: rod_contact.hpp)
  // The linear a differs from the elastica's by O(phi^2) a (8.6e-6 m here, phi = 0.012), far below a cell.
  BOOST_TEST(std::abs(in.s_end - a) <= h + 2 * phi * phi * a);
  // Clamp on the arc: moment EI / rho, no shear force (vertical part of n(0)); the contact resultant then
  // balances the load, P, to the quadrature of the densities (the point force at s = a in one cell: P h / L).
  const RodState base = rod.state_at(s->x, s->vars, 0.0);
  BOOST_TEST_MESSAGE("cylinder: clamp moment " << base.moment.transpose() << " (reference " << kEI / rho
                                               << "), clamp force " << base.force.transpose());
  BOOST_TEST(std::abs(base.moment.norm() - kEI / rho) <= kEI / rho * h / L);
  BOOST_TEST(std::abs(in.force.z() - P) <= P * h / L);
  // Tip deflection: stationary in a (its derivative (L - a) / rho - P (L - a)^2 / EI vanishes at the
  // reference a), so the cell error enters at second order; the linear theory's geometric error is
  // O(theta^2) with the tip rotation theta = a / rho + P (L - a)^2 / (2 EI) = 0.016: 4 theta^2 relative.
  const double delta =
      a * a / (2 * rho) + a * (L - a) / rho + P * std::pow(L - a, 3) / (3 * kEI) + P * (L - a) / kGA;
  const double theta = a / rho + P * (L - a) * (L - a) / (2 * kEI);
  const RodState tip = rod.state_at(s->x, s->vars, L);
  BOOST_TEST_MESSAGE("cylinder: tip deflection " << -tip.position.z() << " (reference " << delta << ")");
  BOOST_TEST(std::abs(-tip.position.z() - delta) <= 4 * theta * theta * delta);
  BOOST_TEST(c[0].min_gap >= -1e-9);
}

BOOST_AUTO_TEST_CASE(fischer_burmeister_and_min_rows_share_their_solution) {
  // Both complementarity functions encode the same discrete conditions: the Fischer-Burmeister solution
  // satisfies the min rows, |min(a, b)| <= |phi_FB(a, b)| / (2 - sqrt 2) (Tseng, J. Optim. Theory Appl. 89
  // (1996) 17-37), so to 1.71 times the Newton tolerance 1e-10 (the other rows are the same). As solvers
  // they differ: from the straight rod (a free sag of 0.2 m against a floor 1 mm below) pcr's Newton
  // converges with the Fischer-Burmeister rows, while with the min rows its line search on |r| stalls at
  // a kink, also in 16 load steps (reported here, not asserted; time is for benchmarks).
  const PlaneCase& fb = plane_case();
  PlaneCase min_cold(ComplementarityFunction::Min);
  BOOST_TEST_REQUIRE(fb.solve->summary.converged());
  BOOST_TEST_MESSAGE("plane, 64 elements, from the straight rod: Fischer-Burmeister "
                     << fb.solve->summary.iterations << " iterations " << fb.solve->seconds << " s; min "
                     << (min_cold.solve->summary.converged() ? "converged" : "failed") << " after "
                     << min_cold.solve->summary.iterations << " iterations " << min_cold.solve->seconds
                     << " s");
  VecX r;
  min_cold.solve->problem.evaluate_residuals(fb.solve->x, r);
  BOOST_TEST(r.lpNorm<Eigen::Infinity>() <= 1e-10 / (2.0 - std::sqrt(2.0)));
}
