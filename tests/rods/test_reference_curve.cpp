// Reference curves given as NURBS: arc length, Frenet frame and intrinsic strains, and a rod that is
// stress-free in that shape.
#define BOOST_TEST_MODULE reference_curve
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "pcr/core/error.hpp"
#include "pcr/rods/reference_curve.hpp"
#include "pcr/rods/rod_solve.hpp"

using namespace pcr;

namespace {

// Quarter circle of radius R in the x-y plane as an exact rational quadratic (The NURBS Book §7.3).
SplineCurve quarter_circle(double R) {
  MatX points(3, 3);
  points << R, R, 0, 0, R, R, 0, 0, 0;
  VecX weights(3);
  weights << 1.0, std::sqrt(0.5), 1.0;
  return SplineCurve(KnotVector(2, {0, 0, 0, 1, 1, 1}), points, weights);
}

}  // namespace

BOOST_AUTO_TEST_CASE(quarter_circle_length_frame_and_curvature) {
  const double R = 0.3;
  const ReferenceCurve c(quarter_circle(R));
  // Gauss-Legendre arc length of a smooth integrand: round-off level (1e-14 relative).
  BOOST_TEST(std::abs(c.length() - M_PI * R / 2) < 1e-14);
  for (double f : {0.0, 0.1, 0.37, 0.5, 0.81, 1.0}) {
    const double s = f * c.length(), angle = s / R;
    // Arc-length inversion: the point at s is at angle s / R on the circle (1e-13 m).
    BOOST_TEST((c.position_at(s) - Vec3(R * std::cos(angle), R * std::sin(angle), 0)).norm() < 1e-13);
    Vec3 eps0, kappa0;
    c.strains_at(s, eps0, kappa0);
    BOOST_TEST(eps0.norm() == 0.0);
    BOOST_TEST((kappa0 - Vec3(0, 1 / R, 0)).norm() < 1e-12 / R);  // k = 1/R, torsion 0
    const Mat3 F = c.frame_at(s);
    BOOST_TEST((F.col(2) - Vec3(-std::sin(angle), std::cos(angle), 0)).norm() < 1e-13);  // tangent
    BOOST_TEST((F.transpose() * F - Mat3::Identity()).norm() < 1e-14);
  }
}

BOOST_AUTO_TEST_CASE(unloaded_rod_keeps_its_reference_shape) {
  const double R = 0.3;
  const ReferenceCurve c(quarter_circle(R));
  RodModel m;
  m.name = "arc";
  m.shear_extension_stiffness = Vec3(1e4, 1e4, 2e4);
  m.bending_torsion_stiffness = Vec3(1.0, 1.0, 0.8);
  m.base.kind = RodEndKind::Clamped;
  m.tip.kind = RodEndKind::Free;
  c.apply_to(m);
  RodSolveOptions o;
  o.discretization = {RodFormulation::Mixed, 5, 16};
  const RodSolution sol = solve_rod(m, o);  // starts straight along the base frame
  BOOST_REQUIRE_MESSAGE(sol.summary.converged(), sol.summary.brief_report());
  double error = 0.0;
  for (int i = 0; i <= 50; ++i) {
    const double s = c.length() * i / 50.0;
    error = std::max(error, (sol.at(s).position - c.position_at(s)).norm());
  }
  // No load: the exact solution is the reference arc with n = m = 0. Measured max distance with mixed
  // p = 5: 4.7e-5, 1.4e-6, 3.1e-8, 5.9e-10 m for 4, 8, 16, 32 elements (order ~5.5, the same as
  // with the constant curvature (0, 1/R, 0) given directly); bound 10x the 16-element value.
  BOOST_TEST(error < 3e-7, "max distance to the reference arc " << error);
  BOOST_TEST(sol.base().force.norm() < 1e-8);
}

BOOST_AUTO_TEST_CASE(straight_or_planar_inputs_are_rejected) {
  MatX line(3, 3);
  line << 0, 0.5, 1, 0, 0, 0, 0, 0, 0;
  BOOST_CHECK_THROW(ReferenceCurve(SplineCurve(KnotVector(2, {0, 0, 0, 1, 1, 1}), line)), InputError);
  MatX planar(2, 3);
  planar << 0, 1, 1, 0, 0, 1;
  try {
    ReferenceCurve c(SplineCurve(KnotVector(2, {0, 0, 0, 1, 1, 1}), planar));
    BOOST_FAIL("2-D curve accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("dimension 2") != std::string::npos, e.what());
  }
}
