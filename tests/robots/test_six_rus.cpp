// models/six_rus.urdf, the 6-RUS robot of Rodrigues et al. (ARK 2024; public code
// github.com/dfki-ric-underactuated-lab/6rus_cosserat_kinetostatics): universal joints at the crank
// tips, spherical joints at the platform, pre-curved rods. FK symmetries, FK -> IK round trips, mesh
// convergence, and the published IK / FK example of their README against ours.
#define BOOST_TEST_MODULE six_rus
#include <boost/test/unit_test.hpp>

#include <Eigen/LU>
#include <algorithm>
#include <fstream>
#include <random>
#include <sstream>

#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;

namespace {

std::shared_ptr<const RobotModel> load_six_rus() {
  return test::load_model("six_rus");
}

/// The model without the platform's 0.5 kg (their README IK example is massless).
std::shared_ptr<const RobotModel> load_massless_six_rus() {
  return test::massless_six_rus();
}

VecX inputs(std::initializer_list<double> values) {
  VecX u(static_cast<Eigen::Index>(values.size()));
  int i = 0;
  for (double v : values) u[i++] = v;
  return u;
}

KinematicsOptions with_elements(int elements) {
  KinematicsOptions o;
  o.assembly.discretization.elements = elements;
  return o;
}

Pose pose(const Vec3& position, const Mat3& rotation) {
  Pose p;
  p.position = position;
  p.orientation = quat_from_rotation(rotation);
  return p;
}

double rotation_distance(const Pose& a, const Pose& b) {
  return so3_log(a.rotation().transpose() * b.rotation()).norm();
}

// Published by them (README, "Inverse Kinetostatic (IK) model"; Inverse_forward_kinetostatic/
// IK_PCR_ROD.py): platform at (0, 0, 0.5) m, roll 10 deg, massless, motor angles [rad].
const double kPublishedIk[6] = {0.48785652, 0.48785652, 0.42037453, 0.28121425, 0.28121425, 0.42037453};

/// The state x moved by a relative 1e-3 (quaternions no longer unit), as test_kinematics does.
VecX perturbed(VecX x, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * (std::abs(x[i]) + 1e-2) * noise(rng);
  return x;
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_block_matches_finite_differences) {
  // Universal couplings on crank links moved by revolute inputs, spherical ends, pre-curved rods under
  // gravity, the platform balance (FK) and the pose target (IK), near a tilted solution. Default
  // checker tolerances (1e-6 abs + rel; central differences with relative step 1e-6).
  std::mt19937 rng(7);
  const auto model = load_six_rus();
  ForwardKinematics fk(model);
  const RobotSolution s = fk.solve(inputs({0.5, 0.3, 0.45, 0.2, 0.35, 0.6}));
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  const JacobianCheckResult r = check_problem_jacobian(fk.assembly().problem(), perturbed(fk.state(), rng));
  BOOST_TEST(r.passed, "FK: " << r.to_string());
  LinkTarget target;
  target.link = "platform";
  target.pose = s.platforms[0];
  InverseKinematics ik(model, {target});
  BOOST_REQUIRE(ik.solve({s.platforms[0]}).summary.converged());
  const JacobianCheckResult q = check_problem_jacobian(ik.problem(), perturbed(ik.state(), rng));
  BOOST_TEST(q.passed, "IK: " << q.to_string());
}

// The model is invariant under the rotation by 120 deg about z that maps motor i to motor i + 2 and
// joint C_i to C_(i+2) (indices mod 6), and under the mirror x -> -x that swaps motors and joints
// 1 <-> 2, 3 <-> 6, 4 <-> 5 (pairs have parallel, same-sense axes, so the mirror keeps every crank
// angle; the pre-curvature bends every rod towards the base centre and the section is round). Both
// map the discrete equations onto themselves (every rod has the same mesh), so their images of a
// solution are solutions to round-off. Tolerance 1e-9 m / rad: both solves stop at 1e-10 in the
// dimensionless residuals (length scale 0.53 m), well conditioned here.
BOOST_AUTO_TEST_CASE(equal_crank_angles_put_the_platform_level_on_the_axis) {
  // Equal inputs are fixed by all three mirrors (x -> -x and its 120-deg turns), whose only common
  // poses have x = y = 0 and no rotation.
  const auto model = load_six_rus();
  ForwardKinematics fk(model);
  double previous_height = 0.0;
  for (double q : {0.0, 0.2, 0.39497946, 0.6}) {
    const RobotSolution s = fk.solve(VecX::Constant(6, q));
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), "q = " << q << ": " << s.summary.brief_report());
    const Pose& p = s.platforms[0];
    BOOST_TEST_MESSAGE("q = " << q << ": " << p.position.transpose() << ", rotation "
                              << so3_log(p.rotation()).norm());
    BOOST_TEST(std::abs(p.position.x()) < 1e-9, "q = " << q << " x " << p.position.x());
    BOOST_TEST(std::abs(p.position.y()) < 1e-9, "q = " << q << " y " << p.position.y());
    BOOST_TEST(so3_log(p.rotation()).norm() < 1e-9, "q = " << q << " rotation " << so3_log(p.rotation()));
    // lifting all cranks lifts the platform (cranks 0.23164 m, nearly rigid legs)
    BOOST_TEST(p.position.z() > previous_height, "q = " << q << " z " << p.position.z());
    previous_height = p.position.z();
  }
}

BOOST_AUTO_TEST_CASE(turned_and_mirrored_inputs_give_turned_and_mirrored_poses) {
  const auto model = load_six_rus();
  ForwardKinematics fk(model);
  const VecX u = inputs({0.5, 0.3, 0.45, 0.2, 0.35, 0.6});  // no symmetry: tilted, off-axis pose
  const RobotSolution s = fk.solve(u);
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  const Pose p = s.platforms[0];
  BOOST_TEST(rotation_distance(p, Pose{}) > 0.02);  // the case is really tilted
  // 120 deg about z: motor i + 2 takes the angle of motor i; the platform turns with its joints
  // (C_(i+2) = Rz C_i in the platform frame), so position Rz p, rotation Rz R Rz^T.
  VecX turned(6);
  for (int i = 0; i < 6; ++i) turned[(i + 2) % 6] = u[i];
  const Mat3 Rz = rotation_z(2.0 * M_PI / 3.0);
  const RobotSolution t = fk.solve(turned);
  BOOST_REQUIRE_MESSAGE(t.summary.converged(), t.summary.brief_report());
  const Pose expected_turned = pose(Rz * p.position, Rz * p.rotation() * Rz.transpose());
  BOOST_TEST_MESSAGE("turned: " << (t.platforms[0].position - expected_turned.position).norm() << " m, "
                                << rotation_distance(t.platforms[0], expected_turned) << " rad");
  BOOST_TEST((t.platforms[0].position - expected_turned.position).norm() < 1e-9);
  BOOST_TEST(rotation_distance(t.platforms[0], expected_turned) < 1e-9);
  // Mirror S = diag(-1, 1, 1) (S C_i = C_j in the platform frame too): position S p, rotation S R S.
  const VecX mirrored = inputs({u[1], u[0], u[5], u[4], u[3], u[2]});
  const Mat3 S = Vec3(-1, 1, 1).asDiagonal();
  const RobotSolution m = fk.solve(mirrored);
  BOOST_REQUIRE_MESSAGE(m.summary.converged(), m.summary.brief_report());
  const Pose expected_mirrored = pose(S * p.position, S * p.rotation() * S);
  BOOST_TEST_MESSAGE("mirrored: " << (m.platforms[0].position - expected_mirrored.position).norm() << " m, "
                                  << rotation_distance(m.platforms[0], expected_mirrored) << " rad");
  BOOST_TEST((m.platforms[0].position - expected_mirrored.position).norm() < 1e-9);
  BOOST_TEST(rotation_distance(m.platforms[0], expected_mirrored) < 1e-9);
}

BOOST_AUTO_TEST_CASE(fk_then_ik_round_trip_at_level_tilted_and_off_axis_poses) {
  // Inputs: level on the axis; their README FK inputs (roll about 10 deg); the first point of their
  // helix (0.25, 0, 0.4) m; a tilted pose without symmetry. IK (a new object, started from the
  // model's defaults) to the FK pose must give back the FK inputs. Tolerance 1e-9 rad: each solve
  // stops at 1e-10 dimensionless residual (pose errors up to ~5e-11 m, length scale 0.53 m), which
  // the inverse input Jacobian (max row sum 3.9-4.5 here, printed) turns into at most ~2e-10 rad per
  // solve, two solves.
  const auto model = load_six_rus();
  ForwardKinematics fk(model);
  const std::vector<VecX> cases = {
      VecX::Constant(6, 0.3),
      inputs({0.48785652, 0.48785652, 0.42037453, 0.28121425, 0.28121425, 0.42037453}),
      inputs({0.47946334, 0.23143240, 0.72100671, 0.82688806, -0.22061221, -0.09801356}),
      inputs({0.5, 0.3, 0.45, 0.2, 0.35, 0.6})};
  for (const VecX& u : cases) {
    const RobotSolution s = fk.solve(u);
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), "FK " << u.transpose() << ": " << s.summary.brief_report());
    LinkTarget target;
    target.link = "platform";
    InverseKinematics ik(model, {target});
    BOOST_REQUIRE(ik.square());
    const RobotSolution r = ik.solve({s.platforms[0]});
    BOOST_REQUIRE_MESSAGE(r.summary.converged(), "IK " << u.transpose() << ": " << r.summary.brief_report());
    // largest input change per unit pose change (rad per m or rad): the amplification of the pose error
    const double amplification = fk.input_jacobian().inverse().lpNorm<Eigen::Infinity>();
    BOOST_TEST_MESSAGE("round trip " << u.transpose() << ": " << (r.inputs - u).lpNorm<Eigen::Infinity>()
                                     << " rad, |d input / d pose| " << amplification << ", pose "
                                     << s.platforms[0].position.transpose() << " rpy "
                                     << s.platforms[0].rpy().transpose());
    BOOST_TEST((r.inputs - u).lpNorm<Eigen::Infinity>() < 1e-9,
               "IK inputs " << r.inputs.transpose() << " vs FK inputs " << u.transpose());
  }
}

BOOST_AUTO_TEST_CASE(default_mesh_is_close_to_a_fine_mesh) {
  // FK at their README FK inputs (0.5 kg) and the README IK (massless): default mesh (degree 6,
  // 8 elements per rod) against 32 elements. Bound 1e-7 m / rad: the accuracy docs/cli.md states for
  // the default mesh on the shipped robots (2e-7 m), halved.
  const VecX u = inputs({0.48785652, 0.48785652, 0.42037453, 0.28121425, 0.28121425, 0.42037453});
  const auto model = load_six_rus();
  ForwardKinematics coarse(model), fine(model, with_elements(32));
  const RobotSolution a = coarse.solve(u), b = fine.solve(u);
  BOOST_REQUIRE(a.summary.converged() && b.summary.converged());
  const double dx = (a.platforms[0].position - b.platforms[0].position).norm();
  const double dr = rotation_distance(a.platforms[0], b.platforms[0]);
  BOOST_TEST_MESSAGE("FK default vs 32 elements: " << dx << " m, " << dr << " rad");
  BOOST_TEST(dx < 1e-7);
  BOOST_TEST(dr < 1e-7);
  BOOST_TEST(dx > 0.0);  // two different meshes: a zero would mean the option was not applied
}

BOOST_AUTO_TEST_CASE(readme_ik_against_their_published_angles_and_an_independent_true_u_solution) {
  // Ours against two references for p = (0, 0, 0.5) m, roll 10 deg, massless:
  //  - a tight shooting solution of the same model (frictionless universal joint, first axis turning
  //    with the crank; DOP853 rtol 1e-10, printed to 8 digits, independent Python code):
  //    tolerance 2e-8 rad = rounding of the print 5e-9 + our mesh error (4.4e-9 rad against 32
  //    elements) + margin;
  //  - their published angles: their joint (first axis fixed in the motor housing, base moment
  //    with zero world x, y components) moves the angles by 5.5e-5 rad at this pose (the tight
  //    solution of their equations, 0.48785636 0.42037417 0.28121390, minus the true-U one), plus
  //    1.6e-7 rad from their RK45 / LM tolerances 1e-5: bound 6e-5 rad. The difference must also be
  //    larger than 1e-5 rad: we do not model their joint.
  const double true_u[6] = {0.48780158, 0.48780158, 0.42035594, 0.28118242, 0.28118242, 0.42035594};
  const auto model = load_massless_six_rus();
  LinkTarget target;
  target.link = "platform";
  InverseKinematics ik(model, {target});
  const RobotSolution r = ik.solve({pose(Vec3(0, 0, 0.5), rotation_x(10.0 * M_PI / 180.0))});
  BOOST_REQUIRE_MESSAGE(r.summary.converged(), r.summary.brief_report());
  double to_published = 0.0;
  for (int i = 0; i < 6; ++i) {
    BOOST_TEST(std::abs(r.inputs[i] - true_u[i]) < 2e-8, "motor" << i + 1 << " " << r.inputs[i]);
    to_published = std::max(to_published, std::abs(r.inputs[i] - kPublishedIk[i]));
  }
  BOOST_TEST_MESSAGE("max |ours - published| = " << to_published << " rad");
  BOOST_TEST(to_published < 6e-5);
  BOOST_TEST(to_published > 1e-5);
}

BOOST_AUTO_TEST_CASE(readme_fk_against_an_independent_true_u_solution) {
  // Their README FK case (inputs = their published IK angles, platform 0.5 kg). Reference: the same
  // independent tight shooting solution of the true-U model with the platform weight's moment
  // p x F in the balance (which their code omits): p = (0, 6.73177e-4, 0.497409060) m, roll
  // 0.176831800 rad, pitch = yaw = 0. Tolerance 2e-8 (m, rad): our mesh error (below 1e-8 against
  // 32 elements) + the print's rounding 5e-10 + margin.
  const auto model = load_six_rus();
  ForwardKinematics fk(model);
  const RobotSolution s =
      fk.solve(inputs({0.48785652, 0.48785652, 0.42037453, 0.28121425, 0.28121425, 0.42037453}));
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  const Pose& p = s.platforms[0];
  BOOST_TEST((p.position - Vec3(0, 6.73177e-4, 0.497409060)).norm() < 2e-8, p.position.transpose());
  BOOST_TEST(rotation_distance(p, pose(Vec3::Zero(), rotation_x(0.176831800))) < 2e-8, p.rpy().transpose());
}
