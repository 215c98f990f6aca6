// Rollers with the adhesion law (no slip; rod_contact.hpp, docs/contact.md "Rollers").
#define BOOST_TEST_MODULE contact_adhesion
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>

#include "contact_fixtures.hpp"
#include "pcr/solve/jacobian_check.hpp"

using namespace pcr;

namespace {

const double kPi = std::acos(-1.0);
const double kArea = kPi * test::kRadius * test::kRadius;
const double kEA = test::kYoungs * kArea;
const double kEI = kArea * test::kRadius * test::kRadius / 4.0 * test::kYoungs;
const double kGA = test::kYoungs / (2.0 * (1.0 + test::kPoisson)) * kArea;

Obstacle adhesive_roller(const Vec3& centre, double radius, double stuck, double angle) {
  Obstacle o;
  o.name = "roller";
  o.shape = ObstacleShape::Roller;
  o.position = centre;
  o.direction = Vec3::UnitY();
  o.radius = radius;
  o.length = 0.02;
  o.law = RollerLaw::Adhesion;
  o.stuck_section = stuck;
  o.angle = angle;
  return o;
}

}  // namespace

BOOST_AUTO_TEST_CASE(explore) {
  const double a = 0.4, L = a * (1 + 1 / std::sqrt(6.0)), g = 0.01, Rr = 1e-5, P = 1e-3, rc = 1e-5;
  for (int elements : {32, 64})
  for (double theta : {0.0, -5e-6}) {
    for (int law = 0; law < 2; ++law) {
      const CollocationRod rod(test::steel_cantilever(L, Vec3(0, 0, -g), Vec3(P, 0, 0)),
                               test::contact_discretization(4, elements));
      Obstacle o = adhesive_roller(Vec3(a, 0, -rc - Rr), Rr, a, theta);
      if (law == 0) {
        o.shape = ObstacleShape::Cylinder;
        o.law = RollerLaw::Slip;
        o.point_contact = true;
      }
      RodContactOptions options{{o}, rc};
      const auto s = test::solve_rod(rod, &options);
      BOOST_TEST_REQUIRE(s->summary.converged(), s->summary.message);
      const auto c = read_rod_contact(rod, s->vars, s->contact, s->x);
      const RodState mid = rod.state_at(s->x, s->vars, a / 2), base = rod.state_at(s->x, s->vars, 0.0);
      std::printf("%d law %d theta %g: it %d N(a/2) %.10g clamp %.10g force %.10g %.10g tang %.10g at %.10g slope %.3g\n",
                  elements, law, theta, s->summary.iterations, mid.force.x(), base.force.x(), c[0].force.x(), c[0].force.z(),
                  c[0].tangential_force, c[0].intervals.empty() ? -1.0 : c[0].intervals[0].centroid,
                  rod.state_at(s->x, s->vars, a).rotation(2, 2));
    }
  }
}
