#include "pcr/robots/io/json_writer.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/solve/solve_summary.hpp"
#include "stability_output.hpp"

namespace pcr {
namespace {

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

void write_summary(JsonWriter& json, const SolveSummary& s) {
  json.begin_object();
  json.key("solver");
  json.value(s.solver);
  json.key("status");
  json.value(to_string(s.status));
  json.key("iterations");
  json.value(s.iterations);
  json.key("jacobian_evaluations");
  json.value(s.jacobian_evaluations);
  json.key("residual_max_abs");
  json.value(s.residual_max_abs);
  json.key("residual_by_kind");
  json.begin_object();
  for (const auto& kind : s.residual_by_kind) {
    json.key(kind.first);
    json.value(kind.second);
  }
  json.end_object();
  json.key("wall_time_seconds");
  json.value(s.wall_time_seconds);
  json.key("message");
  json.value(s.message);
  json.end_object();
}

}  // namespace

int write_solution_json(std::ostream& out, const RobotModel& model, const RobotSolution& solution,
                        const std::vector<LinkTarget>& targets) {
  JsonWriter json(out);
  json.begin_object();
  json.key("model");
  json.value(model.name());
  json.key("status");
  json.value(to_string(solution.summary.status));
  json.key("inputs");
  json.begin_object();
  for (size_t i = 0; i < model.inputs().size() && static_cast<int>(i) < solution.inputs.size(); ++i) {
    json.key(model.inputs()[i].name);
    json.value(solution.inputs[static_cast<int>(i)]);
  }
  json.end_object();
  json.key("platforms");
  json.begin_object();
  for (size_t p = 0; p < solution.platforms.size() && p < model.platforms().size(); ++p) {
    json.key(model.platforms()[p].name);
    json.begin_object();
    json.key("position");
    json.array(solution.platforms[p].position);
    json.key("quaternion_wxyz");
    json.array(VecX(solution.platforms[p].orientation));
    json.key("rpy");
    json.array(solution.platforms[p].rpy());
    json.end_object();
  }
  json.end_object();
  if (!targets.empty()) {
    json.key("targets");
    json.begin_object();
    for (const LinkTarget& target : targets) {
      json.key(target.link);
      json.begin_object();
      json.key("mode");
      json.value(mode_name(target.mode));
      if (target.mode != LinkTarget::Mode::Orientation) {
        json.key("position");
        json.array(target.pose.position);
      }
      if (target.mode != LinkTarget::Mode::Position) {
        json.key("quaternion_wxyz");
        json.array(VecX(target.pose.orientation));
      }
      json.end_object();
    }
    json.end_object();
  }
  json.key("rods");
  json.begin_object();
  for (const RodResult& rod : solution.rods) {
    json.key(rod.name);
    json.begin_object();
    json.key("length");
    json.value(rod.length);
    json.key("axial_force");
    json.value(rod.axial_force);
    json.key("min_axial_stretch");
    json.value(rod.min_axial_stretch);
    write_wrench(json, "base_wrench", rod.base_force, rod.base_moment);
    write_wrench(json, "tip_wrench", rod.tip_force, rod.tip_moment);
    json.key("centerline");
    json.begin_array();
    for (const Vec3& point : rod.centerline) json.array(point);
    json.end_array();
    json.end_object();
  }
  json.end_object();
  write_stability_member(json, solution.stability_verdict);
  json.key("summary");
  write_summary(json, solution.summary);
  // Counted before this member is written: the nulls above stand for NaN or infinite values.
  json.key("non_finite_values");
  json.value(json.non_finite_count());
  json.end_object();
  out << "\n";
  return json.non_finite_count();
}

}  // namespace pcr
