#include "pcr/robots/platform_hold_check.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/robot_model.hpp"
#include "pcr/rods/end_axes.hpp"

namespace pcr {
namespace {

bool has_clamped_end(const RodElement& rod) {
  return rod.start.coupling == RodEndKind::Clamped || rod.end.coupling == RodEndKind::Clamped;
}

// The columns of the constraint matrix: platforms, free passive joints, rods without a clamped end.
struct Bodies {
  int columns = 0;
  std::vector<int> joint_column;  // per model joint: its column, or -1 (not a passive joint without spring)
  std::vector<int> rod_column;    // per rod: its first column, or -1 (carried by a clamped end's link)
  std::vector<Vec3> rod_origin;   // per rod: the point its twist's v refers to
};

Bodies bodies_of(const RobotModel& m, const VecX& q, const std::vector<Pose>& poses) {
  Bodies b;
  b.columns = 6 * static_cast<int>(m.platforms().size());
  b.joint_column.assign(m.joints().size(), -1);
  for (int j : m.passive_joints())
    if (m.joints()[j].stiffness == 0.0) b.joint_column[j] = b.columns++;
  b.rod_column.assign(m.rods().size(), -1);
  b.rod_origin.assign(m.rods().size(), Vec3::Zero());
  for (std::size_t r = 0; r < m.rods().size(); ++r) {
    const RodElement& rod = m.rods()[r];
    if (has_clamped_end(rod)) continue;
    b.rod_column[r] = b.columns;
    b.columns += 6;
    b.rod_origin[r] = m.attachment_pose(rod.start.link >= 0 ? rod.start : rod.end, q, poses).position;
  }
  return b;
}

// The rows of one coupling: at `point`, position (3 rows) and the blocked rotations (`blocked` rows).
struct CouplingRows {
  int row = 0;
  Vec3 point = Vec3::Zero();
  MatX blocked;
};

// Adds coefficient * (the rows for a rigid twist [v; w] in columns col.. with v at `origin`).
void add_twist(MatX& C, const CouplingRows& c, double coefficient, int col, const Vec3& origin) {
  const int nb = static_cast<int>(c.blocked.rows());
  // Velocity of the point carried by the body: v + w x (P - origin) = v - hat(P - origin) w.
  C.block<3, 3>(c.row, col) += coefficient * Mat3::Identity();
  C.block<3, 3>(c.row, col + 3) -= coefficient * hat(c.point - origin);
  C.block(c.row + 3, col + 3, nb, 3) += coefficient * c.blocked;
}

// Adds coefficient * (the rows for the motion of `link` at the coupling): its platform's twist, or the
// rates of the free passive joints that move it (revolute: v = w x (P - o), angular velocity w;
// prismatic: v = w), w the joint axis and o its origin in the world.
void add_link(MatX& C, const CouplingRows& c, double coefficient, int link, const RobotModel& m,
              const Bodies& b, const VecX& q, const std::vector<Pose>& poses) {
  const int platform = m.carrying_platform(link);
  if (platform >= 0) {
    add_twist(C, c, coefficient, 6 * platform, poses[platform].position);
    return;
  }
  for (std::size_t j = 0; j < m.joints().size(); ++j) {
    if (b.joint_column[j] < 0 || !m.joint_moves_link(static_cast<int>(j), link)) continue;
    const Joint& joint = m.joints()[j];
    const Pose frame = m.link_pose(joint.parent_link, q, poses) * joint.origin;
    const Vec3 w = frame.rotation() * joint.axis;
    const bool prismatic = joint.type == JointType::Prismatic;
    const int col = b.joint_column[j];
    C.block<3, 1>(c.row, col) += coefficient * (prismatic ? w : Vec3(w.cross(c.point - frame.position)));
    if (!prismatic) C.block(c.row + 3, col, c.blocked.rows(), 1) += coefficient * c.blocked * w;
  }
}

CouplingRows rows_at(const RodAttachment& end, int row, const RobotModel& m, const VecX& q,
                     const std::vector<Pose>& poses) {
  const Pose frame = m.attachment_pose(end, q, poses);
  return {row, frame.position, blocked_rotations(end.coupling, frame.rotation(), end.axis)};
}

// "pcr_rod 'a' (end spherical), ..." for the rod ends on links selected by `on`.
template <typename Selected>
std::string describe_rods(const RobotModel& model, Selected on) {
  std::ostringstream out;
  bool first = true;
  for (const RodElement& rod : model.rods()) {
    for (const RodAttachment* end : {&rod.start, &rod.end}) {
      if (end->link < 0 || !on(end->link)) continue;
      out << (first ? "" : ", ") << "pcr_rod '" << rod.name << "' (" << (end == &rod.start ? "start" : "end")
          << " " << to_string(end->coupling) << ")";
      first = false;
    }
  }
  return first ? std::string("(none)") : out.str();
}

std::string on_platform(const RobotModel& model, int platform) {
  return describe_rods(model, [&](int link) { return model.carrying_platform(link) == platform; });
}

// Kinematic constraints a rod puts between the bodies of its two ends: its non-clamped end's (a clamped
// end carries the rod), or, with no clamped end, those of both ends less the rod's own 6 degrees of
// freedom (exact when the rod alone is held, RodModel::validate).
int rod_constraint_count(const RodElement& rod) {
  const int start = kinematic_constraint_count(rod.start.coupling),
            end = kinematic_constraint_count(rod.end.coupling);
  if (rod.start.coupling == RodEndKind::Clamped) return end;
  if (rod.end.coupling == RodEndKind::Clamped) return start;
  return std::max(0, start + end - 6);
}

void check_constraint_counts(const RobotModel& model) {
  const int n = static_cast<int>(model.platforms().size());
  std::vector<int> attached(n, 0), constraints(n, 0);
  for (const RodElement& rod : model.rods()) {
    const int a = rod.start.link >= 0 ? model.carrying_platform(rod.start.link) : -2;
    const int b = rod.end.link >= 0 ? model.carrying_platform(rod.end.link) : -2;
    if (a >= 0) ++attached[a];
    if (b >= 0) ++attached[b];
    if (a == -2 || b == -2 || a == b) continue;
    // An upper bound where passive joints carry the rod's other end (they take constraints away).
    if (a >= 0) constraints[a] += rod_constraint_count(rod);
    if (b >= 0) constraints[b] += rod_constraint_count(rod);
  }
  for (int p = 0; p < n; ++p) {
    const std::string& name = model.platforms()[p].name;
    require(attached[p] > 0, "platform '", name, "' has no rods attached: its pose would be undetermined");
    require(constraints[p] >= 6, "platform '", name, "' is under-constrained: its rods ",
            on_platform(model, p), " put ", constraints[p],
            " kinematic constraints on it (clamped 6, collar 5, revolute 5, universal 4, spherical 3, free 0 "
            "per ",
            "rod joining it to another body; a rod without a clamped end: both ends' less 6), it needs at "
            "least 6");
  }
}

}  // namespace

MatX coupling_constraint_matrix(const RobotModel& model, const VecX& joint_values,
                                const std::vector<Pose>& platform_poses) {
  const Bodies bodies = bodies_of(model, joint_values, platform_poses);
  int rows = 0;
  for (const RodElement& rod : model.rods())
    rows += has_clamped_end(rod) ? rod_constraint_count(rod)
                                 : kinematic_constraint_count(rod.start.coupling) +
                                       kinematic_constraint_count(rod.end.coupling);
  MatX C = MatX::Zero(rows, bodies.columns);
  int row = 0;
  for (std::size_t r = 0; r < model.rods().size(); ++r) {
    const RodElement& rod = model.rods()[r];
    if (has_clamped_end(rod)) {
      // The rod moves with its clamped end's link; the other end's coupling constrains the relative
      // motion of the two links at its frame (clamped-clamped: the end at s = L).
      const bool start_carries = rod.start.coupling == RodEndKind::Clamped;
      const RodAttachment& carrier = start_carries ? rod.start : rod.end;
      const RodAttachment& held = start_carries ? rod.end : rod.start;
      if (held.coupling == RodEndKind::Free) continue;
      const CouplingRows c = rows_at(held, row, model, joint_values, platform_poses);
      add_link(C, c, 1.0, held.link, model, bodies, joint_values, platform_poses);
      add_link(C, c, -1.0, carrier.link, model, bodies, joint_values, platform_poses);
      row += kinematic_constraint_count(held.coupling);
      continue;
    }
    for (const RodAttachment* end : {&rod.start, &rod.end}) {
      if (end->coupling == RodEndKind::Free) continue;
      const CouplingRows c = rows_at(*end, row, model, joint_values, platform_poses);
      add_link(C, c, 1.0, end->link, model, bodies, joint_values, platform_poses);
      add_twist(C, c, -1.0, bodies.rod_column[r], bodies.rod_origin[r]);
      row += kinematic_constraint_count(end->coupling);
    }
  }
  return C;
}

namespace {

// Unit twist with round-off residue shown as 0 and the largest component made positive.
VecX tidy(VecX v) {
  v /= v.norm();
  Eigen::Index largest = 0;
  v.cwiseAbs().maxCoeff(&largest);
  if (v[largest] < 0.0) v = -v;
  for (Eigen::Index k = 0; k < v.size(); ++k) v[k] = std::abs(v[k]) < 1e-12 ? 0.0 : v[k];
  return v;
}

// Throws for the null motion `motion` (a unit vector of coupling_constraint_matrix's columns), naming the
// body that moves most in it and the others that move with it.
[[noreturn]] void reject_free_motion(const RobotModel& model, const Bodies& b, const VecX& motion) {
  struct Part {
    std::string name;
    double size;
    int column, width;
  };
  std::vector<Part> parts;
  for (std::size_t p = 0; p < model.platforms().size(); ++p)
    parts.push_back({"platform '" + model.platforms()[p].name + "'", 0.0, 6 * static_cast<int>(p), 6});
  for (std::size_t j = 0; j < b.joint_column.size(); ++j)
    if (b.joint_column[j] >= 0)
      parts.push_back({"passive joint '" + model.joints()[j].name + "'", 0.0, b.joint_column[j], 1});
  for (std::size_t r = 0; r < b.rod_column.size(); ++r)
    if (b.rod_column[r] >= 0)
      parts.push_back({"pcr_rod '" + model.rods()[r].name + "'", 0.0, b.rod_column[r], 6});
  std::size_t worst = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    parts[k].size = motion.segment(parts[k].column, parts[k].width).norm();
    if (parts[k].size > parts[worst].size) worst = k;
  }
  std::ostringstream others;
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (k != worst && parts[k].size > 1e-6 * parts[worst].size)
      others << (others.tellp() > 0 ? ", " : " (moving with ") << parts[k].name;
  if (others.tellp() > 0) others << ")";
  const Part& part = parts[worst];
  const int index = part.column;
  if (part.width == 1) {
    int j = 0;
    while (b.joint_column[j] != index) ++j;
    throw_input_error(part.name, " is not held at its default value: the rod ends it carries, ",
                      describe_rods(model, [&](int link) { return model.joint_moves_link(j, link); }),
                      ", leave it free to move", others.str(),
                      "; hold it by rods, or give it a spring (pcr_joint stiffness > 0)");
  }
  const VecX twist = tidy(motion.segment<6>(index));
  if (index < 6 * static_cast<int>(model.platforms().size())) {
    throw_input_error(part.name, " is not held at its initial pose: its rods ", on_platform(model, index / 6),
                      " leave the motion v = [", twist.head<3>().transpose(), "], w = [",
                      twist.tail<3>().transpose(), "] unconstrained", others.str());
  }
  throw_input_error(part.name, " is not held: its couplings leave it free to move as a rigid body, v = [",
                    twist.head<3>().transpose(), "] (at its first attached end), w = [",
                    twist.tail<3>().transpose(), "]", others.str());
}

}  // namespace

void check_platforms_held(const RobotModel& model) {
  check_constraint_counts(model);
  const VecX q = model.default_joint_values();
  const std::vector<Pose> poses = model.initial_platform_poses();
  const Bodies bodies = bodies_of(model, q, poses);
  if (bodies.columns == 0) return;
  // Rank at the initial configuration: every motion of the bodies must violate some coupling.
  const MatX C = coupling_constraint_matrix(model, q, poses);
  const RightSingularVectors svd = right_singular_vectors(C);
  const VecX& sigma = svd.sigma;
  // Relative threshold: exact dependencies give sigma ~ 1e-16 sigma_max; held bodies give
  // sigma_min ~ (smallest lever arm / largest) sigma_max, far above 1e-9 for any sensible geometry.
  const double tolerance = 1e-9 * (sigma.size() > 0 ? sigma[0] : 1.0);
  for (int i = 0; i < bodies.columns; ++i) {
    if (i < sigma.size() && sigma[i] > tolerance) continue;
    reject_free_motion(model, bodies, svd.V.col(i));
  }
}

}  // namespace pcr
