// The shooting reference on robots with joint rod ends and passive joints (joint_robots.hpp; the
// test_shooting_joints module, one executable of two files): a 6-RUS-like robot (universal rod starts on
// motor-driven cranks) by FK and IK round trips, the same robot with each universal joint built from two
// passive joints, rod bases on spring joints (hinge, slider) against rigid-body balances, the shooting
// Jacobian (joint columns, passive rows) against finite differences, and unsupported joint models.
// test_shooting_pinned_robots.cpp: rods pinned at both ends against rigid trusses.
#define BOOST_TEST_MODULE shooting_joints
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>

#include "joint_robots.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/shooting/shooting_robot_solver.hpp"
#include "robot_fixtures.hpp"
#include "shooting_robots/joint_checks.hpp"
// The solver's private shooting map, to check its Jacobian against finite differences.
#include "../../robots/src/shooting/robot_shooting_system.hpp"

using namespace pcr;
using namespace pcr::test_robots;
using test::tight_shooting;

namespace {

/// Joint values of the model at the given inputs (the six_rus_like motors are its only moving joints).
VecX joint_values_at(const RobotModel& m, const VecX& inputs) {
  VecX q = m.default_joint_values();
  for (int i = 0; i < inputs.size(); ++i) q[m.joints()[m.inputs()[i].index].value_index] = inputs[i];
  return q;
}

VecX moved_cranks(const RobotModel& m, double radians) {
  const double pattern[] = {1.0, -0.6, 0.35, -0.8, 0.5, -0.2};
  VecX u = m.default_input_values();
  for (int i = 0; i < u.size(); ++i) u[i] += pattern[i] * radians;
  return u;
}

Pose tilted_target() {
  Pose p;  // roll 10 deg about x at (0, 0.01, 0.49)
  p.position = Vec3(0.0, 0.01, 0.49);
  p.orientation = quat_from_rotation(rotation_x(10.0 * M_PI / 180.0));
  return p;
}

}  // namespace

// ---- (a) 6-RUS-like: FK at several crank angles, IK round trips -------------------------------------
BOOST_AUTO_TEST_CASE(six_rus_like_fk_and_ik_round_trips) {
  const auto model = six_rus_like(false);
  ShootingRobotSolver fk(model, tight_shooting());
  // Residual tolerance 1e-12 x (F_s ~ 5 N, F_s L_s): the balances hold to 1e-11 of the weight (4.9 N).
  const double balance = 1e-10;
  for (double move : {0.0, 0.05, -0.08}) {
    const VecX u = moved_cranks(*model, move);
    const RobotSolution s = fk.fk(u);
    require_converged(s, "FK move " + std::to_string(move));
    check_platform_balance(*model, s, balance);
    // Universal starts: no moment about the first axis (the crank's y axis), spherical ends: no moment.
    const VecX q = joint_values_at(*model, u);
    for (size_t i = 0; i < s.rods.size(); ++i) {
      const RodElement& e = model->rods()[i];
      const Vec3 a = model->attachment_pose(e.start, q, s.platforms).rotation() * e.start.axis;
      BOOST_TEST(std::abs(s.rods[i].base_moment.dot(a)) < 1e-11, e.name << " base moment about a");
      BOOST_TEST(s.rods[i].tip_moment.norm() < 1e-11, e.name << " tip moment");
      // The start follows the crank: p(0) at the crank tip.
      BOOST_TEST(
          (s.rods[i].centerline.front() - model->attachment_pose(e.start, q, s.platforms).position).norm() <
          1e-15);
    }
    // IK back to this pose returns the inputs: both solves at residual 1e-12, the input-to-pose map of
    // order 1 (rad per m): 1e-9.
    ShootingRobotSolver ik(model, tight_shooting());
    const RobotSolution back = ik.ik({s.platforms[0]});
    require_converged(back, "IK to the FK pose");
    BOOST_TEST((back.inputs - u).lpNorm<Eigen::Infinity>() < 1e-9, "inputs " << back.inputs.transpose());
  }
  // A tilted pose: IK, then FK at its inputs returns to it (1e-9 m / rad as above).
  ShootingRobotSolver ik(model, tight_shooting());
  const RobotSolution s = ik.ik({tilted_target()});
  require_converged(s, "IK tilted");
  check_platform_balance(*model, s, balance);
  const RobotSolution back = fk.fk(s.inputs);
  require_converged(back, "FK at the IK inputs");
  BOOST_TEST(position_difference(back.platforms[0], tilted_target()) < 1e-9);
  BOOST_TEST(angle_difference(back.platforms[0], tilted_target()) < 1e-9);
}

// ---- (b) a universal joint = two passive revolute joints with a massless link ------------------------
BOOST_AUTO_TEST_CASE(universal_joints_equal_two_passive_joints) {
  const auto with_universal = six_rus_like(false), with_passive = six_rus_like(true);
  BOOST_REQUIRE(with_passive->passive_joints().size() == 12u);
  ShootingRobotSolver u(with_universal, tight_shooting()), p(with_passive, tight_shooting());
  // The same mechanics solved with different unknowns: poses to 1e-9 m / rad (residuals 1e-12 on both
  // sides, integration 1e-12 per step), rod wrenches to 1e-8 relative to the largest.
  auto compare = [](const RobotSolution& a, const RobotSolution& b, const std::string& what) {
    BOOST_TEST(position_difference(a.platforms[0], b.platforms[0]) < 1e-9, what);
    BOOST_TEST(angle_difference(a.platforms[0], b.platforms[0]) < 1e-9, what);
    double size = 0.0, diff = 0.0;
    for (size_t i = 0; i < a.rods.size(); ++i) {
      size = std::max({size, a.rods[i].base_force.norm(), a.rods[i].base_moment.norm()});
      diff = std::max({diff, (a.rods[i].base_force - b.rods[i].base_force).norm(),
                       (a.rods[i].base_moment - b.rods[i].base_moment).norm(),
                       (a.rods[i].tip_force - b.rods[i].tip_force).norm()});
    }
    BOOST_TEST(diff < 1e-8 * size, what << ": wrenches differ by " << diff << " of " << size);
  };
  for (double move : {0.0, 0.05}) {
    const VecX inputs = moved_cranks(*with_universal, move);
    const RobotSolution a = u.fk(inputs), b = p.fk(inputs);
    require_converged(a, "universal FK");
    require_converged(b, "passive FK");
    BOOST_REQUIRE(b.passive_joints.size() == 12);
    compare(a, b, "FK move " + std::to_string(move));
    // The passive joints balance: no moment about either axis at the rods' starts (their origins).
    for (int i = 0; i < 6; ++i) {
      const RodElement& e = with_passive->rods()[i];
      const Vec3 moment = b.rods[i].base_moment;
      VecX q = with_passive->default_joint_values();
      for (int j = 0; j < inputs.size(); ++j)
        q[with_passive->joints()[with_passive->inputs()[j].index].value_index] = inputs[j];
      for (int k = 0; k < 12; ++k)
        q[with_passive->joints()[with_passive->passive_joints()[k]].value_index] = b.passive_joints[k];
      const Pose start = with_passive->attachment_pose(e.start, q, b.platforms);
      BOOST_TEST(std::abs(moment.dot(start.rotation() * Vec3::UnitX())) < 1e-11);  // second axis -x
      const int first = with_passive->joint_index("u_a" + std::to_string(i + 1));
      const Joint& ja = with_passive->joints()[first];
      const Vec3 a = with_passive->link_pose(ja.parent_link, q, b.platforms).rotation() *
                     ja.origin.rotation() * Vec3::UnitY();
      BOOST_TEST(std::abs(moment.dot(a)) < 1e-11);
    }
  }
  const RobotSolution a = u.ik({tilted_target()}), b = p.ik({tilted_target()});
  require_converged(a, "universal IK");
  require_converged(b, "passive IK");
  BOOST_TEST((a.inputs - b.inputs).lpNorm<Eigen::Infinity>() < 1e-9);
  compare(a, b, "IK tilted");
}

// ---- (d) a rod base on a spring joint ----------------------------------------------------------------
BOOST_AUTO_TEST_CASE(spring_hinge_balances_the_weights_it_carries) {
  // Revolute about x at the origin carrying the arm, a stiff rod along the arm's y axis and the platform
  // at its end, under gravity -g e3. As a rigid body (the hinge turned by q: the rod along
  // (0, cos q, sin q)) the moment of the weights about x balances the spring:
  //   k (q - rest) = -g cos(q) (m_a 0.05 + m_r L / 2 + m_p (L + 0.03)),
  // solved here by bisection.
  const auto model = spring_hinge(JointType::Revolute);
  ShootingRobotSolver shooting(model, tight_shooting());
  const RobotSolution s = shooting.fk(VecX(0));
  require_converged(s, "spring hinge");
  BOOST_REQUIRE(s.passive_joints.size() == 1);
  const Joint& spring = model->joints()[model->passive_joints()[0]];
  const double q = s.passive_joints[0];
  const double g = 9.81, k = spring.stiffness;
  const RodModel& rod = model->rods()[0].rod;
  const double L = rod.length, EI = rod.bending_torsion_stiffness[0], m_r = rod.mass_per_length * L;
  const double m_p = model->platforms()[0].mass, m_a = model->links()[model->link_index("arm")].mass;
  const double lever = m_a * 0.05 + m_r * L / 2 + m_p * (L + 0.03);
  double lo = -1.0, hi = 1.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (k * (mid - spring.rest) + g * lever * std::cos(mid) < 0 ? lo : hi) = mid;
  }
  // The rod's bending moves the weights off the rigid positions (cantilever formulas, Roark): the tip
  // by at most delta = P L^3 / (3 EI) + M0 L^2 / (2 EI) + w L^4 / (8 EI) and turns it by at most
  // psi = P L^2 / (2 EI) + M0 L / EI + w L^3 / (6 EI), with P = m_p g, M0 = 0.03 P, w = m_r g / L; axial
  // and shear strains (~1e-7) are below that. The moment of the weights changes by at most
  // g (m_p (delta + 0.03 psi) + m_r delta), the angle by that over d/dq of the balance,
  // k - g lever sin(q) >= k - g lever; a factor 2 covers the nonlinear terms (O(psi^2)).
  const double P = m_p * g, M0 = 0.03 * P, w = m_r * g / L;
  const double delta = P * std::pow(L, 3) / (3 * EI) + M0 * L * L / (2 * EI) + w * std::pow(L, 4) / (8 * EI);
  const double psi = P * L * L / (2 * EI) + M0 * L / EI + w * std::pow(L, 3) / (6 * EI);
  const double bound = 2.0 * g * (m_p * (delta + 0.03 * psi) + m_r * delta) / (k - g * lever);
  BOOST_TEST_MESSAGE("hinge angle " << q << " rad, rigid body " << lo << " rad, bound " << bound << " rad");
  BOOST_TEST(std::abs(q - lo) < bound, "hinge " << q << " rad, rigid body " << lo << " rad, bound " << bound);
  // The hinge really turns against the spring (the closed form is not trivially met at the rest angle).
  BOOST_TEST(std::abs(q - spring.rest) > 100 * bound);

  // Prismatic along z with the rod's weight: the force balance along z alone gives the closed form
  // k (q - rest) = -(m_p + m_a + rho A L) g, whatever the rod's shape.
  const auto slider = spring_hinge(JointType::Prismatic);
  ShootingRobotSolver slide(slider, tight_shooting());
  const RobotSolution t = slide.fk(VecX(0));
  require_converged(t, "spring slider");
  const Joint& spring_z = slider->joints()[slider->passive_joints()[0]];
  const double mass = slider->platforms()[0].mass + slider->links()[slider->link_index("arm")].mass +
                      slider->rods()[0].rod.mass_per_length * slider->rods()[0].rod.length;
  const double closed_form = spring_z.rest - mass * 9.81 / spring_z.stiffness;
  // The balance row at 1e-12 x F_s (~7 N) over k = 2000 N/m: 1e-14 m; 1e-13 with margin.
  BOOST_TEST(std::abs(t.passive_joints[0] - closed_form) < 1e-13,
             "slider " << t.passive_joints[0] << " m, closed form " << closed_form << " m");
}

// ---- the shooting Jacobian against finite differences ---------------------------------------------------
BOOST_AUTO_TEST_CASE(shooting_jacobian_matches_finite_differences) {
  // At a generic point (cold state with random joint angles, transmitted moments and passive values),
  // RK4 with fixed steps (the map is then smooth in every unknown): every column of J against central
  // differences of the residual, FK and IK layouts (IK with fewer inputs than 6 per platform is not
  // square, which the check does not need).
  using shooting_robot::RobotShootingModel;
  using shooting_robot::RobotShootingSystem;
  ShootingRobotOptions o;
  o.integrator = IntegratorMethod::RK4;
  o.rk4_steps = 20;
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  struct Case {
    std::string name;
    std::shared_ptr<const RobotModel> model;
  };
  const Case cases[] = {{"six_rus_like", six_rus_like(false)},
                        {"six_rus_like_passive", six_rus_like(true)},
                        {"planar_pinned", planar_pinned(false)},
                        {"tripod_pinned", tripod_pinned(false)},
                        {"tripod_passive_pins", tripod_pinned(true)},
                        {"spring_hinge", spring_hinge(JointType::Revolute)},
                        {"spring_slider", spring_hinge(JointType::Prismatic)}};
  for (const Case& c : cases) {
    for (bool ik : {false, true}) {
      RobotShootingModel m(c.model);
      RobotShootingSystem system(m, o);
      system.set_mode(ik);
      shooting_robot::State s =
          m.cold_state(c.model->default_input_values(), c.model->initial_platform_poses());
      for (int i = 0; i < m.num_rods(); ++i)
        for (int k = 0; k < 6; ++k) s.base[i][k] += 0.1 * normal(rng) * m.rods[i].unknown_scale[k];
      for (int p = 0; p < s.passive.size(); ++p)
        s.passive[p] += 0.1 * normal(rng) * m.passive[p].unknown_scale;
      system.start(s);
      VecX r;
      BOOST_REQUIRE(system.evaluate_start(true, r));
      MatX J;
      system.dense_jacobian(J);
      const int n = system.layout().num_unknowns();
      BOOST_REQUIRE(J.cols() == n);
      double worst = 0.0;
      int worst_column = -1;
      for (int j = 0; j < n; ++j) {
        const double h = 1e-6;
        VecX dz = VecX::Zero(n), rp, rm;
        dz[j] = h;
        BOOST_REQUIRE(system.evaluate_trial(dz, false, rp));
        BOOST_REQUIRE(system.evaluate_trial(-dz, false, rm));
        const VecX fd = (rp - rm) / (2 * h);
        // Central differences of the scaled map: truncation h^2 |r'''| ~ 1e-12 x O(10-100), round-off
        // 1e-16 / h = 1e-10; the algebraic rows' own central differences inside J are as accurate.
        const double error =
            (fd - J.col(j)).cwiseAbs().maxCoeff() / std::max(1.0, J.col(j).cwiseAbs().maxCoeff());
        if (error > worst) {
          worst = error;
          worst_column = j;
        }
      }
      BOOST_TEST(worst < 1e-7, c.name << (ik ? " IK" : " FK") << ": worst column " << worst_column
                                      << " relative error " << worst);
    }
  }
}

BOOST_AUTO_TEST_CASE(unsupported_joint_models_are_rejected_by_name) {
  auto message_of = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // A universal axis along the rod tangent has no second axis.
  std::shared_ptr<RobotModel> model = std::make_shared<RobotModel>(*six_rus_like(false));
  std::vector<RodElement> rods = model->rods();
  rods[2].start.axis = Vec3::UnitZ();
  // (Rejected by the RobotModel or by the solver: the model is built inside.)
  const std::string axis = message_of([&] {
    ShootingRobotSolver s(std::make_shared<const RobotModel>(model->name(), model->links(), model->joints(),
                                                             model->platforms(), rods, model->loads(),
                                                             model->gravity()));
  });
  BOOST_TEST(axis.find("rod3") != std::string::npos, axis);
  BOOST_TEST(axis.find("universal axis") != std::string::npos, axis);
  // A passive joint that carries nothing and has no spring is undetermined.
  std::vector<Link> links = model->links();
  std::vector<Joint> joints = model->joints();
  Link idle;
  idle.name = "idle";
  links.push_back(idle);
  Joint hinge;
  hinge.name = "idle_hinge";
  hinge.type = JointType::Continuous;
  hinge.parent_link = 0;
  hinge.child_link = static_cast<int>(links.size()) - 1;
  hinge.passive = true;
  joints.push_back(hinge);
  const std::string idle_message = message_of([&] {
    ShootingRobotSolver s(std::make_shared<const RobotModel>(
        model->name(), links, joints, model->platforms(), model->rods(), model->loads(), model->gravity()));
  });
  BOOST_TEST(idle_message.find("idle_hinge") != std::string::npos, idle_message);
}