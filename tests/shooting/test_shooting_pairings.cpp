// Every end pairing of a single rod by shooting (part of the test_shooting module): one equilibrium
// reproduced by every pairing RodModel::validate accepts, and the shooting Jacobian of every pairing
// against finite differences.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/shooting/joint_ends.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"
// The solver's private end conditions, to check their Jacobians against finite differences.
#include "../../rods/src/shooting/shooting_ends.hpp"
#include "shooting/shooting_fixtures.hpp"

using namespace pcr;
using namespace pcr::shooting_test;

// ---- every end pairing reproduces one equilibrium ------------------------------------------------------
// Reference: clamped base, free tip with a distributed load and tip loads. Every other pairing that
// RodModel::validate accepts is set up with the reference's own boundary values (tip pose, base
// reaction) as its prescribed data, so all must converge to the same state, and each must satisfy its
// own boundary equations. Joint ends: the end frame is the reference frame turned back by joint angles
// the solver must find, and the applied moment leaves the transmitted part of the reference moment to
// the joint (universal: along t = (R_T a) x (R b); revolute: normal to the pin).
namespace {

const RodEndKind kAllKinds[] = {RodEndKind::Clamped,   RodEndKind::Collar,   RodEndKind::Spherical,
                                RodEndKind::Universal, RodEndKind::Revolute, RodEndKind::Free};

bool accepted(RodModel rod, RodEndKind base, RodEndKind tip) {
  rod.base.kind = base;
  rod.tip.kind = tip;
  try {
    rod.validate();
  } catch (const InputError&) {
    return false;
  }
  return true;
}

// Axes of the joint ends in these tests (in the end frame, not along e3).
const Vec3 kUniversalAxis = Vec3(1.0, 0.3, 0.2).normalized();
const Vec3 kRevoluteAxis = Vec3(0.2, 1.0, 0.3).normalized();

Mat3 about(const Vec3& axis, double angle) {
  return so3_exp(angle * axis);
}

// A joint end whose rod frame is R with the internal moment m (m(L) at a tip, -m(0) at a base, i.e. the
// moment on the rod from outside): the end frame R_T = R (R_a(theta1) R_b(theta2))^T, and the applied
// moment that leaves the transmitted part of m to the joint.
void set_joint_end(RodEnd& end, const Mat3& R, const Vec3& m_outside, double theta1, double theta2) {
  const bool universal = end.kind == RodEndKind::Universal;
  end.axis = universal ? kUniversalAxis : kRevoluteAxis;
  const Vec3 a = end.axis, b = Vec3::UnitZ().cross(a).normalized();
  const Mat3 R_rel = universal ? Mat3(about(a, theta1) * about(b, theta2)) : about(a, theta1);
  const Mat3 R_T = R * R_rel.transpose();
  end.orientation = quat_from_rotation(R_T);
  const Vec3 a_world = R_T * a;
  if (universal) {
    const Vec3 t = a_world.cross(R * b);
    end.moment = m_outside - m_outside.dot(t) * t;
  } else {
    end.moment = m_outside.dot(a_world) * a_world;
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_pairing_converges_to_the_same_equilibrium) {
  RodModel ref_model = test::cantilever(1.0, Vec3(50, 50, 100), Vec3(1.0, 1.5, 0.8));
  ref_model.loads.force_per_length = Vec3(0.5, -1.0, 0.2);
  ref_model.tip.force = Vec3(0.3, 0.2, -0.1);
  ref_model.tip.moment = Vec3(0.1, -0.2, 0.05);
  ref_model.base.orientation = quat_from_rotation(rotation_from_rpy(0.1, 0.2, -0.3));
  ref_model.base.position = Vec3(0.1, -0.2, 0.3);
  const ShootingSolution ref = solve_rod_shooting(ref_model, tight_options());
  BOOST_TEST_REQUIRE(ref.summary.converged(), ref.summary.brief_report());
  // Its own boundary equations (the applied tip loads to the residual tolerance 1e-12 x F_c, M_c = 1).
  BOOST_TEST(max_abs(ref.tip.n - ref_model.tip.force) < 1e-11);
  BOOST_TEST(max_abs(ref.tip.m - ref_model.tip.moment) < 1e-11);

  const Vec3 d3_tip = ref.tip.R().col(2);
  int pairings = 0;
  for (RodEndKind base_kind : kAllKinds) {
    for (RodEndKind tip_kind : kAllKinds) {
      if (!accepted(ref_model, base_kind, tip_kind)) continue;
      ++pairings;
      RodModel rod = ref_model;
      rod.base.kind = base_kind;
      rod.tip.kind = tip_kind;
      // Prescribed tip: the reference tip pose; the tip loads stay (used by spherical, collar torsion).
      rod.tip.position = ref.tip.p;
      rod.tip.orientation = ref.tip.q;
      // Loads at the base: the reference's n(0) = -force, m(0) = -moment.
      rod.base.force = -ref.base.n;
      rod.base.moment = -ref.base.m;
      // A non-clamped base starts from a different guess than the answer: perturb the prescribed
      // orientation of a collar by a twist (the collar only fixes the axis); joint ends are turned back
      // by joint angles.
      if (base_kind == RodEndKind::Collar)
        rod.base.orientation =
            quat_multiply(rod.base.orientation, quat_from_rotation_vector(Vec3(0, 0, 0.3)));
      if (joint_end::is_joint(base_kind)) set_joint_end(rod.base, ref.base.R(), -ref.base.m, 0.3, -0.2);
      if (joint_end::is_joint(tip_kind)) set_joint_end(rod.tip, ref.tip.R(), ref.tip.m, -0.25, 0.15);
      const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
      const std::string name = std::string(to_string(base_kind)) + "-" + to_string(tip_kind);
      BOOST_TEST_REQUIRE(sol.summary.converged(), name << ": " << sol.summary.brief_report());
      // Boundary equations, checked on the returned states (tolerance: residual 1e-12 scaled by
      // L = 1, F_c = M_c = 1.5, plus the integration bound).
      const double tol = kTightIntegration;
      const ShootingState& b = sol.base;
      const ShootingState& t = sol.tip;
      const Mat3 R_base = rotation_matrix(rod.base.orientation), R_tip = rotation_matrix(rod.tip.orientation);
      const Vec3 b_u = Vec3::UnitZ().cross(kUniversalAxis).normalized();
      switch (base_kind) {
        case RodEndKind::Clamped:
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(rotation_angle_between(b.R(), R_base) < tol, name);
          break;
        case RodEndKind::Collar:
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(b.R().col(2).cross(R_base.col(2)).norm() < tol, name);
          BOOST_TEST(std::abs((b.m + rod.base.moment).dot(b.R().col(2))) < tol, name);
          break;
        case RodEndKind::Spherical:
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(max_abs(b.m + rod.base.moment) < tol, name);
          break;
        case RodEndKind::Universal:
          // Turns only about R_T a and R b; no moment about either but the applied one.
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(std::abs((R_base * kUniversalAxis).dot(b.R() * b_u)) < tol, name);
          BOOST_TEST(std::abs((b.m + rod.base.moment).dot(R_base * kUniversalAxis)) < tol, name);
          BOOST_TEST(std::abs((b.m + rod.base.moment).dot(b.R() * b_u)) < tol, name);
          break;
        case RodEndKind::Revolute:
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(max_abs(b.R() * kRevoluteAxis - R_base * kRevoluteAxis) < tol, name);
          BOOST_TEST(std::abs((b.m + rod.base.moment).dot(R_base * kRevoluteAxis)) < tol, name);
          break;
        case RodEndKind::Free:
          BOOST_TEST(max_abs(b.n + rod.base.force) < tol, name);
          BOOST_TEST(max_abs(b.m + rod.base.moment) < tol, name);
          break;
      }
      switch (tip_kind) {
        case RodEndKind::Clamped:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(rotation_angle_between(t.R(), R_tip) < tol, name);
          break;
        case RodEndKind::Collar:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(t.R().col(2).cross(d3_tip).norm() < tol, name);
          BOOST_TEST(std::abs((t.m - rod.tip.moment).dot(t.R().col(2))) < tol, name);
          break;
        case RodEndKind::Spherical:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(max_abs(t.m - rod.tip.moment) < tol, name);
          break;
        case RodEndKind::Universal:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(std::abs((R_tip * kUniversalAxis).dot(t.R() * b_u)) < tol, name);
          BOOST_TEST(std::abs((t.m - rod.tip.moment).dot(R_tip * kUniversalAxis)) < tol, name);
          BOOST_TEST(std::abs((t.m - rod.tip.moment).dot(t.R() * b_u)) < tol, name);
          break;
        case RodEndKind::Revolute:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(max_abs(t.R() * kRevoluteAxis - R_tip * kRevoluteAxis) < tol, name);
          BOOST_TEST(std::abs((t.m - rod.tip.moment).dot(R_tip * kRevoluteAxis)) < tol, name);
          break;
        case RodEndKind::Free: break;
      }
      // Same equilibrium as the reference (unique near this mildly loaded state): the whole state at
      // both ends; the integration bound scaled by the problem's sizes (forces and moments ~ 1).
      for (const auto& pair : {std::make_pair(&b, &ref.base), std::make_pair(&t, &ref.tip)}) {
        BOOST_TEST(max_abs(pair.first->p - pair.second->p) < 10 * tol, name);
        BOOST_TEST(rotation_angle_between(pair.first->R(), pair.second->R()) < 10 * tol, name);
        BOOST_TEST(max_abs(pair.first->n - pair.second->n) < 10 * tol, name);
        BOOST_TEST(max_abs(pair.first->m - pair.second->m) < 10 * tol, name);
      }
    }
  }
  // Accepted by RodModel::validate (one end holds the twist, the two ends hold the rod as a rigid body):
  // clamped x 6; collar, spherical x 3 (clamped, universal, revolute tips); universal, revolute x 5 (not
  // free); free x 1 (clamped).
  BOOST_TEST(pairings == 23);
}

// ---- the shooting Jacobian of every pairing against finite differences ------------------------------------
BOOST_AUTO_TEST_CASE(shooting_jacobian_matches_finite_differences_for_every_pairing) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto random_vec = [&]() { return Vec3(normal(rng), normal(rng), normal(rng)); };
  for (RodEndKind base_kind : kAllKinds) {
    for (RodEndKind tip_kind : kAllKinds) {
      RodModel rod = test::cantilever(1.0, Vec3(40, 50, 80), Vec3(1.0, 1.3, 0.9));
      if (!accepted(rod, base_kind, tip_kind)) continue;
      rod.base.kind = base_kind;
      rod.tip.kind = tip_kind;
      rod.base.axis = Vec3(0.9, -0.4, 0.3);  // joint axes, not unit (normalised by the solver)
      rod.tip.axis = Vec3(-0.2, 0.8, 0.5);
      rod.loads.force_per_length = 0.5 * random_vec();
      rod.base.orientation = quat_from_rotation_vector(0.5 * random_vec());
      rod.base.moment = 0.3 * random_vec();
      rod.base.force = 0.3 * random_vec();
      rod.tip.orientation = quat_from_rotation_vector(0.5 * random_vec());
      rod.tip.position = Vec3(0.2, 0.1, 0.8);
      rod.tip.moment = 0.3 * random_vec();
      rod.tip.force = 0.3 * random_vec();
      const RodOde ode(rod);
      ShootingState guess;
      guess.p = 0.1 * random_vec();
      guess.q = quat_from_rotation_vector(0.4 * random_vec());
      guess.n = random_vec();
      guess.m = random_vec();
      RodStateVector y0 = guess.to_vector();
      shooting::enforce_base(rod.base, y0);
      IntegratorOptions o;
      o.method = IntegratorMethod::RK4;  // fixed steps: the map is smooth in the unknowns
      o.rk4_steps = 40;
      RodStateWithTangents Y;
      shooting::base_tangents(rod.base, y0, Y);
      BOOST_TEST_REQUIRE(integrate_rod(ode, 0.0, 1.0, Y, o).success);
      const shooting::Mat6 J = shooting::tip_residual_jacobian(rod.tip, Y);
      for (int j = 0; j < 6; ++j) {
        const double eps = 1e-6;
        shooting::Vec6 dz = shooting::Vec6::Zero();
        dz[j] = eps;
        RodStateVector a = y0, b = y0;
        shooting::retract_base(rod.base, dz, a);
        shooting::retract_base(rod.base, -dz, b);
        integrate_rod(ode, 0.0, 1.0, a, o);
        integrate_rod(ode, 0.0, 1.0, b, o);
        const shooting::Vec6 fd =
            (shooting::tip_residual(rod.tip, a) - shooting::tip_residual(rod.tip, b)) / (2 * eps);
        // Central differences: eps^2 truncation and 1e-16 / eps roundoff on entries of size ~1-10.
        BOOST_TEST(
            (fd - J.col(j)).cwiseAbs().maxCoeff() < 1e-7 * std::max(1.0, J.col(j).cwiseAbs().maxCoeff()),
            to_string(base_kind) << "-" << to_string(tip_kind) << " column " << j << ": fd " << fd.transpose()
                                 << " vs " << J.col(j).transpose());
      }
    }
  }
}
