// Stability verdict of single rods (RodSolution::stability_verdict, rod_stability.hpp, held_rod.hpp) on the
// clamped-free column of scene R4 under a compressive dead tip load P.
// Reference (Timoshenko & Gere, Theory of Elastic Stability, 1961, §2.1): the straight column buckles in
// the plane of bending stiffness EI_i at P_k^(i) = (2k - 1)^2 pi^2 EI_i / (4 L^2), k = 1, 2, ...; its
// number of unstable modes is the number of these loads below P (torsion and extension never buckle
// here). With finite shear and extension stiffnesses the model's loads solve P (1 + P / GA - P / EA) =
// P_k^(i) (Haringx's column with the extension correction, docs/design.md §4): with GA = EA, as here,
// they are exactly Euler's. Bent states are checked against an independent discrete energy model
// (tests/stability/discrete_rods.hpp).
#define BOOST_TEST_MODULE stability_verdict
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "pcr/math/quaternion.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "pcr/rods/stability/rod_stability.hpp"
#include "rods/rod_fixtures.hpp"
#include "stability/discrete_rods.hpp"

using namespace pcr;

namespace {

constexpr double kLength = 1.0, kEI = 1.0;
const double kP1 = M_PI * M_PI * kEI / (4.0 * kLength * kLength);

/// Column along +z clamped at the origin, K_SE = shear_extension (GA = EA), K_BT = (EI, EI2, 2 EI).
RodModel column(double EI2, double shear_extension = 1e4) {
  return test::cantilever(kLength, Vec3::Constant(shear_extension), Vec3(kEI, EI2, 2.0 * kEI));
}

/// Dead tip load: compression lambda P1, lateral forces lateral_y P along y (the weak direction) and
/// lateral_x P along x.
RodModel loaded_column(double lambda, double EI2, double lateral_y = 0.0, double lateral_x = 0.0,
                       double shear_extension = 1e4) {
  RodModel m = column(EI2, shear_extension);
  const double P = lambda * kP1;
  m.tip.force = Vec3(lateral_x * P, lateral_y * P, -P);
  return m;
}

RodSolveOptions options(RodFormulation form = RodFormulation::Mixed) {
  RodSolveOptions o;
  o.discretization = {form, 5, 8};
  o.stability_verdict = true;
  return o;
}

RodSolution solve_column(double lambda, double EI2, double lateral_y = 0.0, double lateral_x = 0.0,
                         RodFormulation form = RodFormulation::Mixed) {
  return solve_rod(loaded_column(lambda, EI2, lateral_y, lateral_x), options(form));
}

std::string verdict(const Stability& s) {
  return to_string(s.verdict);
}

/// Unstable modes of the independent discrete model (48 segments) relaxed from the solution's state.
/// Its critical loads carry its own O(h^2) error (measured on the straight column: P1 within 0.03 %),
/// so it is compared only away from them.
int discrete_unstable_modes(const RodModel& m, const RodSolution& s, int* neutral = nullptr) {
  test::DiscreteRodSpec spec;
  spec.length = m.length;
  spec.k_se = m.shear_extension_stiffness;
  spec.k_bt = m.bending_torsion_stiffness;
  spec.tip = test::DiscreteTip::Free;
  spec.tip_force = m.tip.force;
  spec.segments = 48;
  test::DiscreteRods d({spec}, {});
  d.set_rod(0, [&](double s_, Vec3& p, Mat3& R) {
    const RodState st = s.at(s_);
    p = st.position;
    R = st.rotation;
  });
  BOOST_TEST_REQUIRE(d.relax());
  const test::DiscreteRods::Inertia in = d.inertia();
  if (neutral) *neutral = in.zero;
  return in.negative;
}

}  // namespace

// Straight column: the count changes at each critical load within 0.5 % (the bound), elliptic
// section EI2 = 2 EI1 (loads P1, 2 P1, 9 P1: simple modes) and circular (P1, 9 P1, 25 P1: double).
BOOST_AUTO_TEST_CASE(straight_column_counts_change_at_the_euler_loads) {
  struct Threshold {
    double EI2, lambda;
    int below, above;
  };
  const Threshold thresholds[] = {{2.0, 1.0, 0, 1}, {2.0, 2.0, 1, 2}, {2.0, 9.0, 2, 3},
                                  {1.0, 1.0, 0, 2}, {1.0, 9.0, 2, 4}, {1.0, 25.0, 4, 6}};
  for (const Threshold& t : thresholds) {
    for (int side = 0; side < 2; ++side) {
      const double lambda = t.lambda * (side == 0 ? 0.995 : 1.005);
      const RodSolution s = solve_column(lambda, t.EI2);
      BOOST_TEST_REQUIRE(s.summary.converged(), s.summary.brief_report());
      BOOST_TEST(std::abs(s.tip().position.y()) <= 1e-12);  // the straight branch
      const int expected = side == 0 ? t.below : t.above;
      BOOST_TEST(s.stability_verdict.unstable_modes == expected, "EI2 " << t.EI2 << ", P / P1 " << lambda);
      BOOST_TEST(verdict(s.stability_verdict) == (expected == 0 ? "stable" : "unstable"));
      BOOST_TEST(s.stability_verdict.neutral_modes == 0);
    }
  }
}

// Also with the primal form's state (n from the constitutive law).
BOOST_AUTO_TEST_CASE(primal_form_counts_as_well) {
  BOOST_TEST(solve_column(0.995, 2.0, 0, 0, RodFormulation::Primal).stability_verdict.unstable_modes == 0);
  BOOST_TEST(solve_column(1.005, 2.0, 0, 0, RodFormulation::Primal).stability_verdict.unstable_modes == 1);
  BOOST_TEST(solve_column(2.01, 2.0, 0, 0, RodFormulation::Condensed).stability_verdict.unstable_modes == 2);
}

// A steel rod (r = 1 mm, L = 0.4 m, CrossSection::circle: kGA = 2.4e5 N, EA = 6.3e5 N): the model's
// critical loads differ from Euler's by at most 1.5e-4 up to the third (docs/design.md §4), well inside
// the 0.5 % asserted.
BOOST_AUTO_TEST_CASE(steel_column_counts_at_the_euler_loads) {
  RodModel m = test::cantilever(0.4, Vec3::Zero(), Vec3::Zero());
  m.set_material_and_section(Material::from_poisson_ratio(200e9, 0.3, 8000), CrossSection::circle(1e-3));
  const double EI = m.bending_torsion_stiffness[0];
  const int expected_below[] = {0, 2, 4}, expected_above[] = {2, 4, 6};
  for (int k = 1; k <= 3; ++k) {
    const double Pk = (2 * k - 1) * (2 * k - 1) * M_PI * M_PI * EI / (4 * 0.4 * 0.4);
    for (int side = 0; side < 2; ++side) {
      m.tip.force = Vec3(0, 0, -Pk * (side == 0 ? 0.995 : 1.005));
      const RodSolution s = solve_rod(m, options());
      BOOST_TEST_REQUIRE(s.summary.converged());
      BOOST_TEST(
          s.stability_verdict.unstable_modes == (side == 0 ? expected_below[k - 1] : expected_above[k - 1]),
          "P" << k << " side " << side);
    }
  }
}

// Margin below P1: the smallest eigenvalue of the tip stiffness, against the beam-column's (Timoshenko
// & Gere §1.11; inextensible: GA = EA = 1e8 makes shear and extension 1e-8 effects). In-plane tip
// compliance, k = sqrt(P / EI): C = [[(tan kL - kL) / (k^3 EI), (1 - cos kL) / (k^2 EI cos kL)],
// [(1 - cos kL) / (k^2 EI cos kL), tan kL / (k EI)]] (deflection, rotation per force, moment). In the
// dimensionless form (dp / L, dtheta; energy / M, M = max(K_BT) / L = 2 EI / L) the margin is
// lambda_min(C^-1) L / (2 EI) (the strong plane, torsion and extension are stiffer).
BOOST_AUTO_TEST_CASE(margin_is_the_beam_column_tip_stiffness) {
  for (double lambda : {0.5, 0.9, 0.99}) {
    const RodSolution s = solve_rod(loaded_column(lambda, 2.0, 0, 0, 1e8), options());
    BOOST_TEST_REQUIRE(s.summary.converged());
    const double k = std::sqrt(lambda * kP1 / kEI), kL = k * kLength;
    Eigen::Matrix2d C;
    C << (std::tan(kL) - kL) / (k * k * k * kEI), (1 - std::cos(kL)) / (k * k * kEI * std::cos(kL)),
        (1 - std::cos(kL)) / (k * k * kEI * std::cos(kL)), std::tan(kL) / (k * kEI);
    const double expected =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(C.inverse()).eigenvalues()[0] * kLength / (2.0 * kEI);
    // 1e-5 relative: the integration error (segments refined until their stiffness is symmetric to 1e-6)
    // and the collocation's (8 elements of degree 5 reproduce the straight state exactly).
    BOOST_TEST(s.stability_verdict.margin == expected, boost::test_tools::tolerance(1e-5));
    BOOST_TEST(verdict(s.stability_verdict) == "stable");
  }
}

// Post-buckled (load stepping with a weak-plane imperfection, as test_kinematics' column): stable, as
// the elastica's first branch (Timoshenko & Gere §2.7); the near-straight state Newton reaches against
// the imperfection at 1.5 P1: one unstable mode. The independent discrete model says the same.
BOOST_AUTO_TEST_CASE(post_buckled_column_is_stable_and_the_near_straight_one_is_not) {
  const double elastica = test::clamped_free_elastica_deflection(1.05) * kLength;
  const RodSolution buckled = solve_column(1.05, 2.0, 0.05);
  BOOST_TEST_REQUIRE(buckled.summary.converged(), buckled.summary.brief_report());
  BOOST_TEST(buckled.tip().position.y() >= elastica);  // on the bent branch
  BOOST_TEST(verdict(buckled.stability_verdict) == "stable");
  BOOST_TEST(buckled.stability_verdict.margin > 0.0);
  BOOST_TEST(discrete_unstable_modes(loaded_column(1.05, 2.0, 0.05), buckled) == 0);

  const RodSolution against = solve_column(1.5, 2.0, 0.05);
  BOOST_TEST_REQUIRE(against.summary.converged(), against.summary.brief_report());
  BOOST_TEST(against.tip().position.y() < 0.0);
  BOOST_TEST(std::abs(against.tip().position.y()) <= 0.5 * elastica);
  BOOST_TEST(against.stability_verdict.unstable_modes == 1);
  BOOST_TEST(discrete_unstable_modes(loaded_column(1.5, 2.0, 0.05), against) == 1);

  // Bent along the strong direction x (its critical load is 2 P1): above P1 the weak plane is unstable.
  const RodSolution strong = solve_column(1.05, 2.0, 0.0, 0.05);
  BOOST_TEST_REQUIRE(strong.summary.converged());
  BOOST_TEST(strong.tip().position.x() > 0.0);
  BOOST_TEST(strong.stability_verdict.unstable_modes == 1);
  BOOST_TEST(discrete_unstable_modes(loaded_column(1.05, 2.0, 0.0, 0.05), strong) == 1);
}

/// Solutions along increasing loads, each solve started from the previous state (load stepping within the
/// first, from the unloaded rod).
std::vector<RodSolution> follow_branch(const std::vector<double>& lambdas, double EI2, double lateral_y) {
  std::vector<RodSolution> out;
  for (double lambda : lambdas) {
    const RodModel m = loaded_column(lambda, EI2, lateral_y);
    if (out.empty()) {
      out.push_back(solve_rod(m, options()));
    } else {
      const RodSolution& last = out.back();
      const VecX start = last.x.head(last.rod->configuration_size());
      out.push_back(solve_rod(m, options(), &start));
    }
    BOOST_TEST_REQUIRE(out.back().summary.converged(), "P / P1 = " << lambda);
  }
  return out;
}

// Along the bent branch up to 2.2 P1 (tip deflection beyond 0.38 L): still stable at EI2 = 2 EI1, while
// the straight column there has two unstable modes (above).
BOOST_AUTO_TEST_CASE(post_buckled_branch_stays_stable) {
  const std::vector<double> lambdas = {1.05, 1.2, 1.5, 1.8, 2.2};
  const std::vector<RodSolution> branch = follow_branch(lambdas, 2.0, 0.05);
  for (size_t k = 0; k < lambdas.size(); ++k) {
    const RodSolution& s = branch[k];
    BOOST_TEST(s.tip().position.y() > 0.38 * kLength);
    BOOST_TEST(verdict(s.stability_verdict) == "stable",
               "P / P1 = " << lambdas[k] << ": " << s.stability_verdict.unstable_modes);
    BOOST_TEST(discrete_unstable_modes(loaded_column(lambdas[k], 2.0, 0.05), s) == 0);
  }
}

// Circular section: with the imperfection (a dead lateral load, no symmetry left) the bent column is
// stable. Without it, the bent column turned about the load line through the clamp is again an
// equilibrium: one exact zero eigenvalue, reported as critical with neutral_modes = 1 (the second-order
// test cannot decide); the discrete model has it too (one zero, no negative eigenvalue).
BOOST_AUTO_TEST_CASE(round_post_buckled_column_has_a_neutral_mode) {
  const std::vector<RodSolution> branch = follow_branch({1.05, 1.3}, 1.0, 0.05);
  const RodSolution& imperfect = branch.back();
  BOOST_TEST(verdict(imperfect.stability_verdict) == "stable");
  BOOST_TEST(discrete_unstable_modes(loaded_column(1.3, 1.0, 0.05), imperfect) == 0);
  // The perfect column from the imperfect state: Newton stays on the bent branch.
  const RodModel perfect = loaded_column(1.3, 1.0);
  const VecX start = imperfect.x.head(imperfect.rod->configuration_size());
  const RodSolution s = solve_rod(perfect, options(), &start);
  BOOST_TEST_REQUIRE(s.summary.converged());
  BOOST_TEST(s.tip().position.head<2>().norm() > 0.38 * kLength);
  BOOST_TEST(verdict(s.stability_verdict) == "critical",
             s.stability_verdict.margin << " " << s.stability_verdict.asymmetry);
  BOOST_TEST(s.stability_verdict.unstable_modes == 0);
  BOOST_TEST(s.stability_verdict.neutral_modes == 1);
  BOOST_TEST(std::abs(s.stability_verdict.margin) <= 1e-6);
  int zero = 0;
  BOOST_TEST(discrete_unstable_modes(perfect, s, &zero) == 0);
  BOOST_TEST(zero == 1);
}

// Other held ends: clamped base, tip held at z = L (1 - eps) on the axis (a straight column compressed by
// P = EA eps; EA = GA = 1e8 EI / L^2, so that extension and shear shift the loads by ~1e-7). Spherical
// tip: the clamped-pinned column, first critical load x^2 EI / L^2 with x = 4.4934 the first positive root
// of tan x = x (Timoshenko & Gere §2.3); collar tip (position and tangent held, twist free): the
// clamped-clamped column, 4 pi^2 EI / L^2 (§2.3). Counts below and above 0.5 % of the weak plane's load:
// elliptic (EI2 = 2 EI1; the strong plane's load is twice as high) 0 -> 1, circular 0 -> 2.
BOOST_AUTO_TEST_CASE(held_tip_columns_count_at_their_euler_loads) {
  const double clamped_pinned = 4.493409457909064 * 4.493409457909064, clamped_clamped = 4.0 * M_PI * M_PI;
  const double EA = 1e8;
  for (RodEndKind tip : {RodEndKind::Spherical, RodEndKind::Collar}) {
    const double Pcr =
        (tip == RodEndKind::Spherical ? clamped_pinned : clamped_clamped) * kEI / (kLength * kLength);
    for (double EI2 : {2.0, 1.0}) {
      for (int side = 0; side < 2; ++side) {
        RodModel m = column(EI2, EA);
        m.tip.kind = tip;
        const double P = Pcr * (side == 0 ? 0.995 : 1.005);
        m.tip.position = Vec3(0, 0, kLength * (1.0 - P / EA));
        const RodSolution s = solve_rod(m, options());
        BOOST_TEST_REQUIRE(s.summary.converged());
        BOOST_TEST(s.tip().force.z() == -P, boost::test_tools::tolerance(1e-6));  // the straight column
        const int expected = side == 0 ? 0 : (EI2 == 1.0 ? 2 : 1);
        BOOST_TEST(s.stability_verdict.unstable_modes == expected,
                   to_string(tip) << " EI2 " << EI2 << " P / Pcr " << P / Pcr);
      }
    }
  }
}

// Joint tips on the same clamped column (tip position held at z = L (1 - eps), P = EA eps). Revolute tip,
// pin axis x = d1: the column bends about d1 (stiffness EI1 = EI) with its tip pinned, clamped-pinned
// 20.19 EI1 / L^2, and about d2 (EI2) with its tip rotation held, clamped-clamped 4 pi^2 EI2 / L^2
// (Timoshenko & Gere §2.3). Universal tip (axes x and y = unit(z x x), end_axes.hpp): pinned about both,
// 20.19 EI1 / L^2 and 20.19 EI2 / L^2. Counts at 0.995 and 1.005 x 20.19 EI / L^2: revolute 0 -> 1 for
// both sections (the next load is 4 pi^2 EI2 / L^2 >= 39.5 EI / L^2); universal 0 -> 1 elliptic (EI2 = 2
// EI: the second load is twice the first) and 0 -> 2 circular (a double load). Both ends hold the twist.
BOOST_AUTO_TEST_CASE(joint_tip_columns_count_at_their_euler_loads) {
  const double clamped_pinned = 4.493409457909064 * 4.493409457909064;
  const double EA = 1e8;
  for (RodEndKind tip : {RodEndKind::Revolute, RodEndKind::Universal}) {
    for (double EI2 : {2.0, 1.0}) {
      for (int side = 0; side < 2; ++side) {
        RodModel m = column(EI2, EA);
        m.tip.kind = tip;
        m.tip.axis = Vec3::UnitX();
        const double P = clamped_pinned * kEI / (kLength * kLength) * (side == 0 ? 0.995 : 1.005);
        m.tip.position = Vec3(0, 0, kLength * (1.0 - P / EA));
        const RodSolution s = solve_rod(m, options());
        BOOST_TEST_REQUIRE(s.summary.converged());
        BOOST_TEST(s.tip().force.z() == -P, boost::test_tools::tolerance(1e-6));  // the straight column
        const int above = tip == RodEndKind::Universal && EI2 == 1.0 ? 2 : 1;
        BOOST_TEST(s.stability_verdict.unstable_modes == (side == 0 ? 0 : above),
                   to_string(tip) << " EI2 " << EI2 << " P / Pcr " << P / (clamped_pinned * kEI));
      }
    }
  }
}

// The shooting solution's verdict (rod_stability(model, ShootingSolution)) counts as the collocation's.
BOOST_AUTO_TEST_CASE(shooting_solution_counts_as_well) {
  struct Case {
    double lambda, EI2;
    int expected;
  };
  for (const Case& c : {Case{0.995, 2.0, 0}, Case{1.005, 2.0, 1}, Case{1.005, 1.0, 2}, Case{2.01, 2.0, 2}}) {
    const RodModel m = loaded_column(c.lambda, c.EI2);
    const ShootingSolution s = solve_rod_shooting(m);
    BOOST_TEST_REQUIRE(s.summary.converged());
    const Stability v = rod_stability(m, s);
    BOOST_TEST(v.unstable_modes == c.expected, "P / P1 " << c.lambda << " EI2 " << c.EI2);
  }
}

// A dead couple at a free end has no potential on SO(3) (docs/design.md §4): unknown, with the reason.
BOOST_AUTO_TEST_CASE(dead_couple_gives_unknown) {
  RodModel m = loaded_column(0.5, 2.0);
  m.tip.moment = Vec3(0.0, 0.0, 0.1);
  const RodSolution s = solve_rod(m, options());
  BOOST_TEST_REQUIRE(s.summary.converged());
  BOOST_TEST(verdict(s.stability_verdict) == "unknown");
  BOOST_TEST(s.stability_verdict.reason.find("dead couple") != std::string::npos, s.stability_verdict.reason);
}

// A cantilever under a transverse dead tip load of 10 EI / L^2 (bench_all's R2) is stable: the first
// branch of the elastica (Timoshenko & Gere §2.7), the independent discrete model agrees. The verdict is
// the same on every mesh and form for practical stiffness ratios (EA L^2 / EI = 1e8 here); a nearly
// inextensible rod (1e12, where the segment stiffnesses lose their digits and the count scattered
// between 0 and 2 over the meshes) gets `unknown` with the reason instead of a wrong count.
BOOST_AUTO_TEST_CASE(transverse_tip_load_is_stable_and_stiff_rods_are_unknown) {
  for (double stiffness : {1e8, 1e12}) {
    RodModel m = test::cantilever(kLength, Vec3::Constant(stiffness), Vec3(kEI, kEI, kEI));
    m.tip.force = Vec3(10.0 * kEI / (kLength * kLength), 0.0, 0.0);
    for (RodFormulation form : {RodFormulation::Mixed, RodFormulation::Condensed}) {
      for (int elements : {4, 16, 64}) {
        RodSolveOptions o = options(form);
        o.discretization.elements = elements;
        const RodSolution s = solve_rod(m, o);
        BOOST_TEST_REQUIRE(s.summary.converged(), s.summary.brief_report());
        if (stiffness == 1e8) {
          BOOST_TEST(verdict(s.stability_verdict) == "stable", to_string(form) << " E " << elements);
          if (elements == 16 && form == RodFormulation::Mixed) BOOST_TEST(discrete_unstable_modes(m, s) == 0);
        } else {
          BOOST_TEST(verdict(s.stability_verdict) == "unknown", to_string(form) << " E " << elements);
          BOOST_TEST(s.stability_verdict.reason.find("inextensible") != std::string::npos,
                     s.stability_verdict.reason);
        }
      }
    }
  }
}

// jacobi_states takes the integrals of the basis functions up to s, which the condensed form's moment
// m(s) reads when the rod carries distributed loads, in closed form (degree p + 1 B-splines,
// rod_stability.cpp); CollocationRod::state_at takes them by Gauss quadrature on every span below s (itself
// checked against closed forms in test_basis). On a loaded rod in an arbitrary configuration (not an
// equilibrium: the moment then depends on every control point through the integral) both give the same
// rotation, force and moment at any s. Tolerance: round-off of sums of O(1) terms (forces and moments of
// order 1 here), 1e-12 relative.
BOOST_AUTO_TEST_CASE(jacobi_states_take_the_rod_states_of_a_loaded_condensed_rod) {
  RodModel m = test::cantilever(0.8, Vec3(1e5, 1e5, 2e5), Vec3(1.0, 1.5, 0.8));
  m.mass_per_length = 0.7;
  m.loads.gravity = Vec3(0.0, 0.0, -9.81);
  m.loads.force_per_length = Vec3(0.3, -0.2, 0.0);
  for (int elements : {3, 8}) {
    const CollocationRod rod(m, RodDiscretization{RodFormulation::Condensed, 5, elements});
    BOOST_REQUIRE(rod.condensed_with_loads());
    Problem problem;
    const RodVariables vars = rod.add_to_problem(problem);
    VecX x = problem.initial_values();
    // Bend and stretch the straight configuration, and give the wrench non-zero values.
    for (int j = 0; j < rod.num_control_points(); ++j) {
      const int o = vars.control_point_offset + j * rod.control_point_size();
      const double u = static_cast<double>(j) / (rod.num_control_points() - 1);
      x.segment<3>(o) += Vec3(0.2 * u * u, -0.1 * std::sin(3.0 * u), 0.05 * u);
      x.segment<4>(o + 3) += Eigen::Vector4d(0.0, 0.1 * u, -0.2 * u * u, 0.05);
    }
    x.segment<6>(vars.wrench_offset) << 0.4, -0.3, 1.2, 0.05, 0.02, -0.1;
    const JacobiStateAt states = jacobi_states(rod, x, vars);
    for (double s : {0.0, 0.013, 0.1, 0.27, 0.4, 0.5, 0.61, 0.799, 0.8}) {
      const RodState expected = rod.state_at(x, vars, s);
      const JacobiState y = states(s);
      BOOST_TEST((y.moment - expected.moment).norm() <= 1e-12 * (1.0 + expected.moment.norm()),
                 "E = " << elements << ", s = " << s);
      BOOST_TEST((y.force - expected.force).norm() <= 1e-12 * (1.0 + expected.force.norm()),
                 "E = " << elements << ", s = " << s);
      BOOST_TEST((y.rotation - expected.rotation).norm() <= 1e-14, "E = " << elements << ", s = " << s);
    }
  }
}
