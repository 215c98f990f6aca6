#include "contact_output.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/io/json_writer.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/solve/solve_summary.hpp"
#include "pose_output.hpp"
#include "stability_output.hpp"

namespace pcr {
namespace {

using io_detail::write_pose_object;

const char* mode_name(LinkTarget::Mode mode) {
  switch (mode) {
    case LinkTarget::Mode::Pose: return "pose";
    case LinkTarget::Mode::Position: return "position";
    case LinkTarget::Mode::Orientation: return "orientation";
  }
  return "pose";
}

void write_wrench(JsonWriter& json, const char* name, const Vec3& force, const Vec3& moment) {
  json.key(name);
  json.begin_object();
  json.key("force");
  json.array(force);
  json.key("moment");
  json.array(moment);
  json.end_object();
}

/// A matrix as an array of its rows.
void write_matrix(JsonWriter& json, const MatX& matrix) {
  json.begin_array();
  for (int r = 0; r < matrix.rows(); ++r) json.array(VecX(matrix.row(r).transpose()));
  json.end_array();
}

/// Names of the pose components a target selects: x, y, z (world), rx, ry, rz (target frame).
std::vector<std::string> selected_component_names(const LinkTarget& target) {
  static const char* const names[6] = {"x", "y", "z", "rx", "ry", "rz"};
  std::vector<std::string> out;
  for (int i = 0; i < 6; ++i) {
    const bool position = i < 3;
    if (target.components[i] &&
        (position ? target.mode != LinkTarget::Mode::Orientation : target.mode != LinkTarget::Mode::Position))
      out.push_back(names[i]);
  }
  return out;
}

/// One target as given, its link's reached pose and the distance between them.
void write_target(JsonWriter& json, const LinkTarget& target, const Pose& reached) {
  json.begin_object();
  json.member("mode", mode_name(target.mode));
  json.key("components");
  json.begin_array();
  for (const std::string& name : selected_component_names(target)) json.value(name);
  json.end_array();
  if (target.mode != LinkTarget::Mode::Orientation) {
    json.key("position");
    json.array(target.pose.position);
  }
  if (target.mode != LinkTarget::Mode::Position) {
    json.key("quaternion_wxyz");
    json.array(VecX(target.pose.orientation));
  }
  json.key("reached_position");
  json.array(reached.position);
  json.key("reached_quaternion_wxyz");
  json.array(VecX(reached.orientation));
  json.member("position_error", (reached.position - target.pose.position).norm());
  json.member("orientation_error", rotation_angle_between(reached.rotation(), target.pose.rotation()));
  json.end_object();
}

void write_derivatives(JsonWriter& json, const RobotModel& model, const SolutionExtras& extras) {
  const size_t np = model.platforms().size();
  if (extras.input_jacobian.size() > 0 && extras.input_jacobian.rows() == 6 * static_cast<int>(np)) {
    json.key("input_jacobian");
    json.begin_object();
    for (size_t p = 0; p < np; ++p) {
      json.key(model.platforms()[p].name);
      write_matrix(json, extras.input_jacobian.middleRows(6 * static_cast<int>(p), 6));
    }
    json.end_object();
  }
  if (!extras.compliance.empty() && extras.compliance.size() == np) {
    json.key("compliance");
    json.begin_object();
    for (size_t p = 0; p < np; ++p) {
      json.key(model.platforms()[p].name);
      write_matrix(json, extras.compliance[p]);
    }
    json.end_object();
  }
}

/// "inputs" and "passive_joints": name -> value (rad or m), in the model's order; then
/// "passive_joints_outside_limits": the passive joints whose value lies outside their URDF limits (which
/// the solve does not enforce), as the table flags them.
void write_joint_values(JsonWriter& json, const RobotModel& model, const RobotSolution& solution) {
  json.key("inputs");
  json.begin_object();
  for (size_t i = 0; i < model.inputs().size() && static_cast<int>(i) < solution.inputs.size(); ++i) {
    json.member(model.inputs()[i].name, solution.inputs[static_cast<int>(i)]);
  }
  json.end_object();
  json.key("passive_joints");
  json.begin_object();
  const std::vector<int>& passive = model.passive_joints();
  for (size_t i = 0; i < passive.size() && static_cast<int>(i) < solution.passive_joints.size(); ++i) {
    json.member(model.joints()[passive[i]].name, solution.passive_joints[static_cast<int>(i)]);
  }
  json.end_object();
  json.key("passive_joints_outside_limits");
  json.begin_array();
  for (size_t i = 0; i < passive.size() && static_cast<int>(i) < solution.passive_joints.size(); ++i) {
    const Joint& joint = model.joints()[passive[i]];
    const double value = solution.passive_joints[static_cast<int>(i)];
    if (!joint.within_limits(value)) json.value(joint.name);
  }
  json.end_array();
}

/// "platforms": name -> pose (world frame).
void write_platform_poses(JsonWriter& json, const RobotModel& model, const RobotSolution& solution) {
  json.key("platforms");
  json.begin_object();
  for (size_t p = 0; p < solution.platforms.size() && p < model.platforms().size(); ++p) {
    write_pose_object(json, model.platforms()[p].name, solution.platforms[p]);
  }
  json.end_object();
}

/// "links" (only when some were asked for): name -> pose (world frame).
void write_link_poses(JsonWriter& json, const std::vector<LinkPose>& links) {
  if (links.empty()) return;
  json.key("links");
  json.begin_object();
  for (const LinkPose& link : links) {
    write_pose_object(json, link.link, link.pose);
  }
  json.end_object();
}

/// "targets" (only for IK): link -> the target, the pose reached and the distance between them.
void write_targets(JsonWriter& json, const RobotModel& model, const RobotSolution& solution,
                   const std::vector<LinkTarget>& targets) {
  if (targets.empty()) return;
  json.key("targets");
  json.begin_object();
  const VecX q = joint_values_of_solution(model, solution);
  for (const LinkTarget& target : targets) {
    json.key(target.link);
    write_target(json, target, model.link_pose(model.link_index(target.link), q, solution.platforms));
  }
  json.end_object();
}

/// "rods": name -> length, forces, end wrenches and centerline points (world frame).
void write_rods(JsonWriter& json, const std::vector<RodResult>& rods) {
  json.key("rods");
  json.begin_object();
  for (const RodResult& rod : rods) {
    json.key(rod.name);
    json.begin_object();
    json.member("length", rod.length);
    json.member("axial_force", rod.axial_force);
    json.member("min_axial_stretch", rod.min_axial_stretch);
    write_wrench(json, "base_wrench", rod.base_force, rod.base_moment);
    write_wrench(json, "tip_wrench", rod.tip_force, rod.tip_moment);
    json.key("centerline");
    json.begin_array();
    for (const Vec3& point : rod.centerline) json.array(point);
    json.end_array();
    json.end_object();
  }
  json.end_object();
}

void write_summary(JsonWriter& json, const SolveSummary& s) {
  json.begin_object();
  json.member("solver", s.solver);
  json.member("status", to_string(s.status));
  json.member("iterations", s.iterations);
  json.member("jacobian_evaluations", s.jacobian_evaluations);
  json.member("residual_max_abs", s.residual_max_abs);
  json.member("residual_round_off", s.residual_round_off);
  json.key("residual_by_kind");
  json.begin_object();
  for (const auto& kind : s.residual_by_kind) {
    json.member(kind.first, kind.second);
  }
  json.end_object();
  json.member("wall_time_seconds", s.wall_time_seconds);
  json.member("message", s.message);
  json.end_object();
}

}  // namespace

int write_solution_json(std::ostream& out, const RobotModel& model, const RobotSolution& solution,
                        const std::vector<LinkTarget>& targets) {
  return write_solution_json(out, model, solution, targets, SolutionExtras{});
}

int write_solution_json(std::ostream& out, const RobotModel& model, const RobotSolution& solution,
                        const std::vector<LinkTarget>& targets, const SolutionExtras& extras) {
  JsonWriter json(out);
  write_solution_object(json, model, solution, targets, extras);
  out << "\n";
  return json.non_finite_count();
}

void write_solution_object(JsonWriter& json, const RobotModel& model, const RobotSolution& solution,
                           const std::vector<LinkTarget>& targets, const SolutionExtras& extras) {
  const bool top_level = json.depth() == 0;
  json.begin_object();
  json.member("model", model.name());
  json.member("status", to_string(solution.summary.status));
  write_joint_values(json, model, solution);
  write_platform_poses(json, model, solution);
  write_link_poses(json, extras.links);
  write_targets(json, model, solution, targets);
  write_derivatives(json, model, extras);
  write_rods(json, solution.rods);
  write_contacts_member(json, solution.contacts, solution.contact_gaps);
  write_stability_member(json, solution.stability_verdict);
  json.key("summary");
  write_summary(json, solution.summary);
  if (top_level) {
    // Counted before this member is written: the nulls above stand for NaN or infinite values.
    json.member("non_finite_values", json.non_finite_count());
  }
  json.end_object();
}

}  // namespace pcr
