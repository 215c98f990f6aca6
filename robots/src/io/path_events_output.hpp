#pragma once
// The events of a path through folds (path_through_folds.hpp) in the path writers' CSV and JSON
// (internal header of pcr::robots; docs/results_format.md).
#include <ostream>
#include <vector>

#include "pcr/robots/io/json_writer.hpp"
#include "pcr/robots/path_through_folds.hpp"

namespace pcr::io_detail {

/// One CSV row in the columns of write_path_csv: kind, inputs, platform poses, empty link and target
/// columns (links, targets: how many), status = kind, empty iterations, residual and time, message, then
/// `trailing` empty columns (the stability columns where the path has them).
void write_event_row(std::ostream& out, const RobotModel& model, const PathEvent& event, size_t links,
                     size_t targets, size_t trailing);
/// "events": [{kind, path_parameter, inputs {NAME: value}, unstable_modes_before, unstable_modes_after,
/// platforms {NAME: {position, quaternion_wxyz, rpy}}, jump_position, jump_rotation, description}].
void write_events_json(JsonWriter& json, const RobotModel& model, const std::vector<PathEvent>& events);

}  // namespace pcr::io_detail
