#include "pcr/robots/io/path_writers.hpp"

#include <string>

#include "csv_fields.hpp"
#include "path_events_output.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/io/json_writer.hpp"

namespace pcr {

using io_detail::csv_number;
using io_detail::csv_pose;
using io_detail::csv_pose_header;

bool has_stability_verdicts(const std::vector<PathPoint>& points) {
  for (const PathPoint& point : points)
    if (point.solution.stability_verdict.verdict != StabilityVerdict::NotChecked) return true;
  return false;
}

void write_path_csv(std::ostream& out, const RobotModel& model, const std::vector<PathPoint>& points) {
  write_path_csv(out, model, points, {});
}

void write_path_csv(std::ostream& out, const RobotModel& model, const std::vector<PathPoint>& points,
                    const std::vector<PathEvent>& events) {
  const std::vector<LinkPose> no_links;
  const std::vector<LinkTarget> no_targets;
  const std::vector<LinkPose>& links = points.empty() ? no_links : points.front().extras.links;
  const std::vector<LinkTarget>& targets = points.empty() ? no_targets : points.front().targets;
  out << "point";
  for (const ActuationInput& input : model.inputs()) out << ',' << input.name;
  for (const Platform& platform : model.platforms()) out << csv_pose_header(platform.name);
  for (const LinkPose& link : links) out << csv_pose_header(link.link);
  for (const LinkTarget& target : targets)
    out << ',' << target.link << ".position_error," << target.link << ".orientation_error";
  const bool verdicts = has_stability_verdicts(points);  // their columns after the message
  out << ',' << io_detail::kCsvSummaryHeader
      << (verdicts ? std::string(",") + io_detail::kCsvStabilityHeader : std::string()) << '\n';
  const auto event_row = [&](const PathEvent& event) {
    io_detail::write_event_row(out, model, event, links.size(), targets.size(), verdicts ? 4 : 0);
  };
  size_t next_event = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    // Events on the way to point k (path parameter up to k) come before its row.
    for (; next_event < events.size() && events[next_event].path_parameter <= static_cast<double>(k);
         ++next_event)
      event_row(events[next_event]);
    const RobotSolution& s = points[k].solution;
    out << k;
    for (size_t i = 0; i < model.inputs().size(); ++i)
      out << ',' << (static_cast<int>(i) < s.inputs.size() ? csv_number(s.inputs[static_cast<int>(i)]) : "");
    for (size_t p = 0; p < model.platforms().size(); ++p)
      out << (p < s.platforms.size() ? csv_pose(s.platforms[p]) : ",,,,,,");
    for (size_t l = 0; l < links.size(); ++l)
      out << (l < points[k].extras.links.size() ? csv_pose(points[k].extras.links[l].pose) : ",,,,,,");
    const VecX q = joint_values_of_solution(model, s);
    for (const LinkTarget& target : points[k].targets) {
      const Pose reached = model.link_pose(model.link_index(target.link), q, s.platforms);
      const bool position = target.mode != LinkTarget::Mode::Orientation;
      const bool orientation = target.mode != LinkTarget::Mode::Position;
      out << ',' << (position ? csv_number((reached.position - target.pose.position).norm()) : "") << ','
          << (orientation ? csv_number(rotation_angle_between(reached.rotation(), target.pose.rotation()))
                          : "");
    }
    out << ',' << io_detail::csv_summary(s.summary);
    if (verdicts) out << ',' << io_detail::csv_stability(s.stability_verdict);
    out << '\n';
  }
  for (; next_event < events.size(); ++next_event) event_row(events[next_event]);
}

int write_path_json(std::ostream& out, const RobotModel& model, const std::vector<PathPoint>& points) {
  return write_path_json(out, model, points, nullptr);
}

int write_path_json(std::ostream& out, const RobotModel& model, const std::vector<PathPoint>& points,
                    const std::vector<PathEvent>* events) {
  int failures = 0;
  for (const PathPoint& point : points) failures += point.solution.summary.converged() ? 0 : 1;
  JsonWriter json(out);
  json.begin_object();
  json.member("model", model.name());
  json.member("command", "path");
  json.member("points", static_cast<int>(points.size()));
  json.member("failures", failures);
  json.key("results");
  json.begin_array();
  for (const PathPoint& point : points)
    write_solution_object(json, model, point.solution, point.targets, point.extras);
  json.end_array();
  if (events) io_detail::write_events_json(json, model, *events);
  return json.end_document();
}

}  // namespace pcr
