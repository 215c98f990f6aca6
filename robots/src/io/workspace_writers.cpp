// CSV and JSON of a sampled workspace (workspace_writers.hpp).
#include "pcr/robots/io/workspace_writers.hpp"
#include "csv_fields.hpp"
#include "pcr/robots/io/json_writer.hpp"
#include "stability_output.hpp"

namespace pcr {

using io_detail::csv_number;

namespace {

bool has_stability_verdicts(const WorkspaceResult& result) {
  for (const WorkspaceSample& s : result.samples)
    if (s.stability.verdict != StabilityVerdict::NotChecked) return true;
  return false;
}

}  // namespace

void write_workspace_csv(std::ostream& out, const RobotModel& model, const WorkspaceResult& result) {
  const bool verdicts = has_stability_verdicts(result);  // their columns after the message
  out << "sample";
  for (const ActuationInput& input : model.inputs()) out << ',' << input.name;
  for (const Platform& platform : model.platforms()) out << io_detail::csv_pose_header(platform.name);
  out << ',' << io_detail::kCsvSummaryHeader
      << (verdicts ? std::string(",") + io_detail::kCsvStabilityHeader : std::string()) << '\n';
  for (const WorkspaceSample& s : result.samples) {
    out << s.index;
    for (int i = 0; i < s.inputs.size(); ++i) out << ',' << csv_number(s.inputs[i]);
    for (size_t p = 0; p < model.platforms().size(); ++p)
      out << (s.converged() && p < s.platforms.size() ? io_detail::csv_pose(s.platforms[p]) : ",,,,,,,");
    out << ',' << to_string(s.status) << ',' << s.iterations << ',' << csv_number(s.residual_max_abs) << ','
        << csv_number(s.wall_time_seconds) << ',' << io_detail::csv_quote(s.message);
    if (verdicts) out << ',' << io_detail::csv_stability(s.stability);
    out << '\n';
  }
}

namespace {

void write_sample(JsonWriter& json, const RobotModel& model, const WorkspaceSample& s) {
  json.begin_object();
  json.member("index", s.index);
  json.member("status", to_string(s.status));
  json.key("inputs");
  json.array(s.inputs);
  if (s.converged()) {
    json.key("platforms");
    json.begin_object();
    for (size_t p = 0; p < model.platforms().size() && p < s.platforms.size(); ++p) {
      json.key(model.platforms()[p].name);
      json.begin_object();
      json.key("position");
      json.array(s.platforms[p].position);
      json.key("quaternion_wxyz");
      json.array(VecX(s.platforms[p].orientation));
      json.end_object();
    }
    json.end_object();
  }
  json.member("iterations", s.iterations);
  json.member("residual_max_abs", s.residual_max_abs);
  json.member("message", s.message);
  write_stability_member(json, s.stability);  // the same object as fk's, when checked
  json.end_object();
}

}  // namespace

int write_workspace_json(std::ostream& out, const RobotModel& model, const WorkspaceResult& result) {
  JsonWriter json(out);
  json.begin_object();
  json.member("model", model.name());
  json.member("seed", result.seed);
  json.member("first_sample", result.first_sample);
  json.member("samples", static_cast<std::int64_t>(result.samples.size()));
  json.member("failures", result.failures);
  json.member("threads", result.threads);
  json.member("wall_time_seconds", result.wall_time_seconds);
  json.key("inputs");
  json.begin_array();
  for (const ActuationInput& input : model.inputs()) json.value(input.name);
  json.end_array();
  json.key("points");
  json.begin_array();
  for (const WorkspaceSample& s : result.samples) write_sample(json, model, s);
  json.end_array();
  return json.end_document();
}

}  // namespace pcr
