// The energy-minimisation FK strategy (robots/src/kinematics/energy_fallback.hpp, internal) with contact:
// the obstacles' gap rows against finite differences, planar_post inputs in contact with its post that
// every other strategy fails on, the pitchfork descended along its unstable mode, planar_rollers' jammed
// minimum left for a stable equilibrium, and the refusal of a contact at one section.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "kinematics/energy_fallback.hpp"
#include "kinematics/energy_model.hpp"
#include "kinematics/energy_terms.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pcr/rods/rod_contact.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "robot_fixtures.hpp"
#include "stability/energy_fallback_fixtures.hpp"
#include "stability/energy_minimum.hpp"

using namespace pcr;
using namespace pcr::kinematics;
using test::block_values;
using test::default_state;
using test::Fk;
using test::load_model;

namespace {

/// Checks a converged result x at the inputs without the code that found it: the residual within the
/// solver's tolerance, the inputs exactly those requested, the verdict computed again `stable`.
void check_stable_equilibrium(const RobotAssembly& a, const VecX& x, const VecX& inputs) {
  VecX c;
  a.problem().evaluate_residuals(x, c);
  BOOST_TEST(c.cwiseAbs().maxCoeff() <= KinematicsOptions{}.tolerance);
  BOOST_TEST((a.inputs(x) - inputs).cwiseAbs().maxCoeff() == 0.0);
  const Stability verdict = robot_stability(a, x);
  BOOST_TEST(to_string(verdict.verdict) == std::string("stable"), verdict.reason);
}

/// The complementarity of gap and contact density at every midpoint of an obstacle's contact: gap >=
/// -1e-9 L0, density >= -1e-8 F0 / L0 (the residual tolerance's scale), no density where the gap is open.
void check_complementarity(const ObstacleContact& contact, double L0, double F0) {
  for (std::size_t j = 0; j < contact.gaps.size(); ++j) {
    BOOST_TEST(contact.gaps[j] >= -1e-9 * L0);
    BOOST_TEST(contact.densities[j] >= -1e-8 * F0 / L0);
    if (contact.gaps[j] > 1e-6 * L0) BOOST_TEST(std::abs(contact.densities[j]) <= 1e-8 * F0 / L0);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(energy_fallback)

// The obstacles' gap rows (frictionless contact in the energy) against finite differences, as the
// coupling rows above: one row per obstacle shape (half-space, sphere, capsule beside its segment and past
// its end, cylinder, roller beside its side, its end face and its rim) at a centerline point of 4 control
// points off every shape's kinks, with weights of mixed signs for the Hessian.
BOOST_AUTO_TEST_CASE(obstacle_gap_rows_against_finite_differences) {
  const auto make = [](ObstacleShape shape, Vec3 position, Vec3 direction, double radius) {
    Obstacle o;
    o.shape = shape;
    o.position = position;
    o.direction = direction.normalized();
    o.end = position + Vec3(0.0, 0.04, 0.0);
    o.radius = radius;
    o.length = 0.02;
    return o;
  };
  const Vec3 y = Vec3::UnitY();
  const std::vector<Obstacle> obstacles{
      make(ObstacleShape::HalfSpace, Vec3(0.0, 0.0, -0.05), Vec3(0.1, 0.2, 1.0), 0.0),
      make(ObstacleShape::Sphere, Vec3(0.03, 0.01, 0.02), y, 0.01),
      make(ObstacleShape::Capsule, Vec3(0.02, -0.02, 0.03), y, 0.01),  // beside the segment
      make(ObstacleShape::Capsule, Vec3(0.02, -0.09, 0.03), y, 0.01),  // past its end x1
      make(ObstacleShape::Cylinder, Vec3(-0.03, 0.0, 0.01), Vec3(0.3, 1.0, 0.1), 0.005),
      make(ObstacleShape::Roller, Vec3(0.03, 0.0, 0.0), y, 0.01),      // beside the side
      make(ObstacleShape::Roller, Vec3(0.002, 0.03, 0.004), y, 0.01),  // beside an end face
      make(ObstacleShape::Roller, Vec3(0.03, 0.03, 0.0), y, 0.01)};    // from the rim
  const VecX basis = (VecX(4) << 0.1, 0.4, 0.35, 0.15).finished();
  const std::vector<VariableId> points{0, 1, 2, 3};
  const ObstacleGapRows rows(obstacles, 5e-4, basis, points, 0.3);
  std::vector<VecX> values;
  for (int a = 0; a < 4; ++a) {
    VecX v(7);
    v << 0.001 * a, 0.002 * a - 0.003, 0.004 * a + 0.001, 1.0, 0.1 * a, 0.0, 0.0;
    values.push_back(v);
  }
  const JacobianCheckResult j = check_block_jacobian(rows, values);
  BOOST_TEST(j.passed, j.to_string());
  const JacobianCheckResult h =
      check_block_hessian(rows, values, VecX::LinSpaced(rows.num_rows(), -1.0, 2.0));
  BOOST_TEST(h.passed, h.to_string());
  // Bounded below by 0 (an inequality for Ipopt), above by nothing.
  BOOST_TEST(rows.row_lower().cwiseAbs().maxCoeff() == 0.0);
  BOOST_TEST(std::isinf(rows.row_upper().minCoeff()));
}

// planar_post at 0.177198 0.184144 0.182836 m, 0.182100 0.226888 0.159735 m and 0.445277 0.366498
// 0.297536 m (17 digits below), cold inputs of the random sweep on which every other strategy fails (the
// continuations stop at 0.7-0.86 of the line from the default inputs, the fold-aware one with steps below
// 1e-8); the third is a nearly critical minimum (margin 5.5e-4, counted as positive since the rods' energy
// Hessians are exact: contact_verdict.cpp's zero tolerance is then ~3e-5). From the default equilibrium
// Ipopt minimises the energy with the gap rows at the middle rod's 24 midpoints, and Newton on the
// collocation equations (the semismooth contact rows) converges from the minimiser, its contact densities
// started from the minimiser's point forces (the gap rows' multipliers). Checked without the code
// that found it: the residual recomputed; at every midpoint the complementarity of gap and density (gap >=
// -1e-9 L0, density >= -1e-8 F0 / L0: the residual tolerance's scale, and no density where the gap is open);
// the middle rod on the post; the verdict computed again.
BOOST_AUTO_TEST_CASE(planar_post_inputs_that_all_other_strategies_fail_on) {
  const auto model = load_model("planar_post");
  Fk fk(model);
  const VecX& start = default_state(fk);
  const RobotAssembly& a = *fk.assembly;
  const double L0 = a.length_scale(), F0 = a.force_scale();
  const int middle = 1;
  for (const VecX& inputs :
       {(VecX(3) << 0.17719782674187728, 0.18414384786537918, 0.1828360524710973).finished(),
        (VecX(3) << 0.18210049270634937, 0.2268877454652834, 0.15973475140950516).finished(),
        (VecX(3) << 0.44527699973051293, 0.36649806730711199, 0.29753558740694563).finished()}) {
    const EnergyFallback r =
        minimise_energy_then_newton(fk.data, inputs, {{&start, "the default equilibrium"}});
    BOOST_TEST_REQUIRE(r.converged, r.message);
    BOOST_TEST_MESSAGE("planar_post: " << r.message);
    // Stable (counted on the energy's Ritz form with the contacts held), and an energy minimisation
    // started next to it (moved by 1e-3 L0) returns to it: the platform within 1e-5 m and the energy to
    // 1e-5 relative (the Ritz minimiser against the collocation's equilibrium, the two discretisations'
    // difference: measured 7.8e-7 m and 5e-7 relative at the first input).
    check_stable_equilibrium(a, r.x, inputs);
    BOOST_TEST(to_string(r.verdict.verdict) == std::string("stable"));
    const std::vector<ObstacleContact> contacts =
        read_rod_contact(a.rod(middle), a.rod_variables(middle), *a.rod_contact(middle), r.x);
    BOOST_TEST_REQUIRE(contacts.size() == 1u);
    const ObstacleContact& post = contacts[0];
    BOOST_TEST_REQUIRE(post.gaps.size() == a.rod_contact(middle)->midpoints.size());
    check_complementarity(post, L0, F0);
    BOOST_TEST(!post.intervals.empty());
    Vec3 platform;
    const double minimum = test::energy_minimised_from(a, r.x, 1e-3, platform);
    const double V = test::energy_at(a, r.x);
    BOOST_TEST_MESSAGE("minimised again: " << minimum << " J against " << V << " J, platform off by "
                                           << (platform - a.platform_pose(r.x, 0).position).norm() << " m");
    BOOST_TEST((platform - a.platform_pose(r.x, 0).position).norm() <= 1e-5);
    BOOST_TEST(std::abs(minimum - V) <= 1e-5 * std::abs(V));
  }
}

// planar_post at 0.455351 0.171345 0.180950 m (17 digits below), a warm input of the random sweep (after
// 0.358801 0.323430 0.369945 m) on which every other strategy fails. The energy's minimum (0.241784 J)
// lies in the robot's plane; Newton from it lands on the collocation's in-plane equilibrium, which has 1
// unstable mode (the platform leaving the plane: a pitchfork the two discretisations place on either side
// of this input), and the damped motion from the in-plane minimiser stays in the plane. Pushed along the
// unstable mode the damped motion reaches an equilibrium 0.57 mm off the plane, stable (the cold solve of
// the sweep reached its mirror image). Checked without the code that found it: the residual, the inputs,
// the verdict computed again; and on refined meshes (16 and 32 elements per rod, the same equilibrium
// carried and solved there): still off the plane by more than 0.1 mm and stable (measured 0.614 mm, margin
// 3.74e-4 at both; 0.572 mm and 3.25e-4 at 8): the off-plane equilibrium is the rods', not the mesh's.
BOOST_AUTO_TEST_CASE(planar_post_pitchfork_descended_along_the_unstable_mode) {
  const auto model = load_model("planar_post");
  Fk fk(model);
  const VecX& start = default_state(fk);
  const RobotAssembly& a = *fk.assembly;
  const VecX inputs = (VecX(3) << 0.45535090075211382, 0.17134479274337425, 0.18095039817943706).finished();
  const EnergyFallback r =
      minimise_energy_then_newton(fk.data, inputs, {{&start, "the default equilibrium"}});
  BOOST_TEST_REQUIRE(r.converged, r.message);
  BOOST_TEST_MESSAGE("planar_post: " << r.message);
  BOOST_TEST(r.message.find("damped motion along the unstable mode") != std::string::npos, r.message);
  check_stable_equilibrium(a, r.x, inputs);
  BOOST_TEST(std::abs(a.platform_pose(r.x, 0).position.y()) > 1e-4);
  for (const int elements : {16, 32}) {
    AssemblyOptions o = a.options();
    o.discretization.elements = elements;
    const RobotAssembly fine(model, o);
    const VecX off = test::carried_to(a, r.x, fine);
    const Stability v = robot_stability(fine, off);
    BOOST_TEST_MESSAGE(elements << " elements: off the plane by " << fine.platform_pose(off, 0).position.y()
                                << " m, " << to_string(v.verdict) << " (margin " << v.margin << ")");
    BOOST_TEST(std::abs(fine.platform_pose(off, 0).position.y()) > 1e-4, elements);
    BOOST_TEST(to_string(v.verdict) == std::string("stable"), elements << ": " << v.reason);
  }
}

// planar_rollers at 0.272806 0.186439 0.173524 m (17 digits below), a cold input of the random sweep on
// which every other strategy fails. From the default equilibrium Ipopt reaches a minimum of 32.28 J whose
// basin is small: the middle rod is jammed on the right roller, stretched by 5 kN, and a minimisation
// started 1e-4 L0 off it leaves it (for 0.118 J) while one started 1e-5 L0 off returns. Newton polishes
// it into an equilibrium (37.03 J on the collocation's discretisation) whose verdict is `unknown` (the gap
// row at the contact zone's edge carries no force), refused; minimised again from that equilibrium (moved
// off it by 1e-3) and polished, the robot reaches a stable equilibrium out of its plane at 0.118 J, with
// forces below 1 N. Checked without the code that found it: the residual, the inputs, the verdict computed
// again, the complementarity at every midpoint as above; an energy minimisation started next to it
// (moved by 1e-3 L0) returns to it (platform within 1e-5 m as above; measured 1.1e-7 m). (A cold FK on 64
// elements per rod reaches the same equilibrium, platform at (29.3, -13.0, 166.1) mm, also stable.)
BOOST_AUTO_TEST_CASE(planar_rollers_jammed_minimum_left_for_a_stable_equilibrium) {
  const auto model = load_model("planar_rollers");
  Fk fk(model);
  const VecX& start = default_state(fk);
  const RobotAssembly& a = *fk.assembly;
  const double L0 = a.length_scale(), F0 = a.force_scale();
  const VecX inputs = (VecX(3) << 0.27280647222514109, 0.18643866227053393, 0.17352376461923805).finished();
  const EnergyFallback r = minimise_energy_then_newton(fk.data, inputs, {{&start, "the default equilibrium"}});
  BOOST_TEST_REQUIRE(r.converged, r.message);
  BOOST_TEST_MESSAGE("planar_rollers: " << r.message);
  BOOST_TEST(r.message.find("from an equilibrium refused above") != std::string::npos, r.message);
  check_stable_equilibrium(a, r.x, inputs);
  BOOST_TEST(std::abs(a.platform_pose(r.x, 0).position.y()) > 1e-3);  // out of the plane: 13 mm measured
  const int middle = 1;
  for (const ObstacleContact& roller :
       read_rod_contact(a.rod(middle), a.rod_variables(middle), *a.rod_contact(middle), r.x))
    check_complementarity(roller, L0, F0);
  const Vec3 position = a.platform_pose(r.x, 0).position;
  Vec3 platform;
  const double minimum = test::energy_minimised_from(a, r.x, 1e-3, platform);
  BOOST_TEST_MESSAGE("minimised again: " << minimum << " J against " << test::energy_at(a, r.x)
                                         << " J, platform off by " << (platform - position).norm() << " m");
  BOOST_TEST((platform - position).norm() <= 1e-5);
}

// A model the energy does not describe (the adhesive roller's contact at one prescribed section): the
// strategy is skipped, saying why.
BOOST_AUTO_TEST_CASE(refuses_a_contact_at_one_section) {
  const auto model = load_model("adhesive_roller");
  const std::string refusal = energy_model_refusal(*model);
  BOOST_TEST(refusal.find("rod 'beam' and obstacle 'drive': a contact at one section") == 0u, refusal);
  Fk fk(model);
  const VecX x = fk.assembly->initial_guess();
  const EnergyFallback r =
      minimise_energy_then_newton(fk.data, model->default_input_values(), {{&x, "a state"}});
  BOOST_TEST(!r.converged);
  BOOST_TEST(r.message == "skipped: " + refusal);
  BOOST_TEST(r.iterations == 0);
}

BOOST_AUTO_TEST_SUITE_END()
