// The events of a path through folds in CSV and JSON (path_events_output.hpp).
#include "path_events_output.hpp"

#include <string>

#include "csv_fields.hpp"
#include "pose_output.hpp"

namespace pcr::io_detail {

void write_event_row(std::ostream& out, const RobotModel& model, const PathEvent& event, size_t links,
                     size_t targets, size_t trailing) {
  out << to_string(event.kind);
  for (size_t i = 0; i < model.inputs().size(); ++i)
    out << ','
        << (static_cast<int>(i) < event.inputs.size() ? csv_number(event.inputs[static_cast<int>(i)]) : "");
  for (size_t p = 0; p < model.platforms().size(); ++p)
    out << (p < event.platforms.size() ? csv_pose(event.platforms[p]) : ",,,,,,");
  for (size_t l = 0; l < links; ++l) out << ",,,,,,,";
  for (size_t t = 0; t < targets; ++t) out << ",,";
  out << ',' << to_string(event.kind) << ",,,," << csv_quote(event.description) << std::string(trailing, ',')
      << '\n';
}

void write_events_json(JsonWriter& json, const RobotModel& model, const std::vector<PathEvent>& events) {
  json.key("events");
  json.begin_array();
  for (const PathEvent& e : events) {
    json.begin_object();
    json.member("kind", to_string(e.kind));
    json.member("path_parameter", e.path_parameter);
    json.key("inputs");
    json.begin_object();
    for (size_t i = 0; i < model.inputs().size() && static_cast<int>(i) < e.inputs.size(); ++i) {
      json.member(model.inputs()[i].name, e.inputs[static_cast<int>(i)]);
    }
    json.end_object();
    json.member("unstable_modes_before", e.unstable_modes_before);
    json.member("unstable_modes_after", e.unstable_modes_after);
    json.key("platforms");
    json.begin_object();
    for (size_t p = 0; p < e.platforms.size() && p < model.platforms().size(); ++p)
      write_pose_object(json, model.platforms()[p].name, e.platforms[p]);
    json.end_object();
    json.member("jump_position", e.jump_position);
    json.member("jump_rotation", e.jump_rotation);
    json.member("description", e.description);
    json.end_object();
  }
  json.end_array();
}

}  // namespace pcr::io_detail
