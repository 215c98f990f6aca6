#include "pcr/robots/platform_hold_check.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr {
namespace {

// The coupling that holds the two links a rod joins: with one end clamped, the rod is carried rigidly by
// that end's link, and the other end's coupling constrains the relative motion at its frame.
struct Holding {
  const RodAttachment* carrier = nullptr;  // clamped end
  const RodAttachment* held = nullptr;     // the other end (clamped-clamped: the end at s = L)
};

Holding holding_of(const RodElement& rod) {
  if (rod.start.coupling == RodEndKind::Clamped) return {&rod.start, &rod.end};
  return {&rod.end, &rod.start};
}

// Adds coefficient * (rows of the constraints at `frame` for the twist of platform `body`) to C.
void add_body_rows(MatX& C, int row, int body, double coefficient, RodEndKind coupling, const Pose& frame,
                   const Pose& body_pose) {
  if (body < 0) return;  // the world does not move
  const int col = 6 * body;
  // Velocity of the point P carried by the body: v + w x (P - x) = v - hat(P - x) w.
  C.block<3, 3>(row, col) += coefficient * Mat3::Identity();
  C.block<3, 3>(row, col + 3) -= coefficient * hat(frame.position - body_pose.position);
  if (coupling == RodEndKind::Clamped) {
    C.block<3, 3>(row + 3, col + 3) += coefficient * Mat3::Identity();
  } else if (coupling == RodEndKind::Collar) {
    // Only rotations about axes normal to the tangent d3 = frame z: rows d1^T, d2^T.
    const Mat3 R = frame.rotation();
    C.block<1, 3>(row + 3, col + 3) += coefficient * R.col(0).transpose();
    C.block<1, 3>(row + 4, col + 3) += coefficient * R.col(1).transpose();
  }
}

std::string describe_rods(const RobotModel& model, int platform) {
  std::ostringstream out;
  bool first = true;
  for (const RodElement& rod : model.rods()) {
    const RodAttachment* ends[] = {&rod.start, &rod.end};
    for (const RodAttachment* end : ends) {
      if (end->link < 0 || model.carrying_platform(end->link) != platform) continue;
      out << (first ? "" : ", ") << "pcr_rod '" << rod.name << "' (" << (end == &rod.start ? "start" : "end")
          << " " << to_string(end->coupling) << ")";
      first = false;
    }
  }
  return out.str();
}

}  // namespace

MatX coupling_constraint_matrix(const RobotModel& model, const VecX& joint_values,
                                const std::vector<Pose>& platform_poses) {
  int rows = 0;
  for (const RodElement& rod : model.rods())
    rows += kinematic_constraint_count(holding_of(rod).held->coupling);
  MatX C = MatX::Zero(rows, 6 * static_cast<int>(model.platforms().size()));
  int row = 0;
  for (const RodElement& rod : model.rods()) {
    const Holding h = holding_of(rod);
    const int k = kinematic_constraint_count(h.held->coupling);
    if (k == 0) continue;
    const Pose frame = model.attachment_pose(*h.held, joint_values, platform_poses);
    const int carrier = model.carrying_platform(h.carrier->link);
    const int held = model.carrying_platform(h.held->link);
    if (carrier != held) {
      // Relative motion: held body minus the rod carried by the clamped end's body.
      if (held >= 0) add_body_rows(C, row, held, 1.0, h.held->coupling, frame, platform_poses[held]);
      if (carrier >= 0)
        add_body_rows(C, row, carrier, -1.0, h.held->coupling, frame, platform_poses[carrier]);
    }
    row += k;
  }
  return C;
}

void check_platforms_held(const RobotModel& model) {
  const int n = static_cast<int>(model.platforms().size());
  if (n == 0) return;
  // Count the kinematic constraints each platform receives from rods joining it to another body.
  std::vector<int> attached(n, 0), constraints(n, 0);
  for (const RodElement& rod : model.rods()) {
    const Holding h = holding_of(rod);
    const int carrier = model.carrying_platform(h.carrier->link);
    const int held = h.held->link >= 0 ? model.carrying_platform(h.held->link) : -2;
    const int k = kinematic_constraint_count(h.held->coupling);
    if (carrier >= 0) ++attached[carrier];
    if (held >= 0) ++attached[held];
    if (held == -2 || held == carrier) continue;
    if (carrier >= 0) constraints[carrier] += k;
    if (held >= 0) constraints[held] += k;
  }
  for (int p = 0; p < n; ++p) {
    const std::string& name = model.platforms()[p].name;
    require(attached[p] > 0, "platform '", name, "' has no rods attached: its pose would be undetermined");
    require(constraints[p] >= 6, "platform '", name, "' is under-constrained: its rods ",
            describe_rods(model, p), " put ", constraints[p],
            " kinematic constraints on it (clamped 6, collar 5, spherical 3, free 0 per ",
            "rod joining it to another body), it needs at least 6");
  }

  // Rank at the initial configuration: every platform twist must violate some coupling.
  const MatX C =
      coupling_constraint_matrix(model, model.default_joint_values(), model.initial_platform_poses());
  Eigen::JacobiSVD<MatX> svd(C, Eigen::ComputeFullV);
  const VecX& sigma = svd.singularValues();
  // Relative threshold: exact dependencies give sigma ~ 1e-16 sigma_max; held platforms give
  // sigma_min ~ (smallest lever arm / largest) sigma_max, far above 1e-9 for any sensible geometry.
  const double tolerance = 1e-9 * (sigma.size() > 0 ? sigma[0] : 1.0);
  for (int i = 0; i < 6 * n; ++i) {
    if (i < sigma.size() && sigma[i] > tolerance) continue;
    const VecX free_motion = svd.matrixV().col(i);
    int worst = 0;
    for (int p = 1; p < n; ++p) {
      if (free_motion.segment<6>(6 * p).norm() > free_motion.segment<6>(6 * worst).norm()) worst = p;
    }
    // Unit twist, with round-off residue shown as 0 and the largest component made positive.
    VecX twist = free_motion.segment<6>(6 * worst) / free_motion.segment<6>(6 * worst).norm();
    Eigen::Index largest = 0;
    twist.cwiseAbs().maxCoeff(&largest);
    if (twist[largest] < 0.0) twist = -twist;
    for (Eigen::Index k = 0; k < 6; ++k) twist[k] = std::abs(twist[k]) < 1e-12 ? 0.0 : twist[k];
    throw_input_error("platform '", model.platforms()[worst].name,
                      "' is not held at its initial pose: its rods ", describe_rods(model, worst),
                      " leave the motion v = [", twist.head<3>().transpose(), "], w = [",
                      twist.tail<3>().transpose(), "] unconstrained");
  }
}

}  // namespace pcr
