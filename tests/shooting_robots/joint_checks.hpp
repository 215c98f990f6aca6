#pragma once
// Checks shared by the files of the test_shooting_joints module: convergence with the solver's report,
// pose distances, and the platform balance recomputed from the rods' tip states.
#include <boost/test/unit_test.hpp>

#include <string>

#include "pcr/math/so3.hpp"
#include "pcr/robots/robot_model.hpp"
#include "pcr/robots/robot_solution.hpp"

namespace pcr::test_robots {

inline void require_converged(const RobotSolution& s, const std::string& what) {
  BOOST_REQUIRE_MESSAGE(s.summary.converged(),
                        what << ": " << s.summary.brief_report() << " " << s.summary.message);
}

inline double position_difference(const Pose& a, const Pose& b) {
  return (a.position - b.position).norm();
}
inline double angle_difference(const Pose& a, const Pose& b) {
  return rotation_angle_between(a.rotation(), b.rotation());
}

/// Platform balance computed here from the rods' tip states (docs/design.md §3): m g - sum n(L) = 0 and
/// (R c) x m g - sum (m(L) + (p(L) - x) x n(L)) = 0, relative to the weight m g and m g L_ref.
inline void check_platform_balance(const RobotModel& m, const RobotSolution& s, double tolerance) {
  const Platform& p = m.platforms()[0];
  const Pose& x = s.platforms[0];
  const Vec3 weight = p.mass * m.gravity();
  Vec3 F = weight, M = (x.rotation() * p.center_of_mass).cross(weight);
  for (const RodResult& r : s.rods) {
    F -= r.tip_force;
    M -= r.tip_moment + (r.centerline.back() - x.position).cross(r.tip_force);
  }
  BOOST_TEST(F.norm() < tolerance * weight.norm(), "force balance " << F.transpose());
  BOOST_TEST(M.norm() < tolerance * weight.norm(), "moment balance " << M.transpose());
}

}  // namespace pcr::test_robots
