#include "path_files.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "cli_arguments.hpp"

namespace pcr_app {
namespace {

std::string trim(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t\r") + 1 - begin);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream stream(line);
  while (std::getline(stream, field, ',')) fields.push_back(trim(field));
  if (!line.empty() && trim(line).back() == ',') fields.push_back("");
  return fields;
}

std::string where(const NumberTable& table, size_t row) {
  return table.file + ":" + std::to_string(table.lines[row]);
}

const char* const kPoseComponents[7] = {"x", "y", "z", "qw", "qx", "qy", "qz"};

/// Column c of the target table: its target and its pose component 0..6 (x, y, z, qw, qx, qy, qz).
struct TargetColumn {
  int target = -1, component = -1;
};

}  // namespace

NumberTable read_number_table(const std::string& file) {
  std::ifstream stream(file);
  if (!stream) throw UsageError("cannot read '" + file + "'");
  NumberTable table;
  table.file = file;
  std::string line;
  for (int number = 1; std::getline(stream, line); ++number) {
    const std::string text = trim(line);
    if (text.empty() || text[0] == '#') continue;
    const std::vector<std::string> fields = split_fields(text);
    if (table.columns.empty()) {
      table.columns = fields;
      for (const std::string& name : fields)
        if (name.empty()) throw UsageError(file + ":" + std::to_string(number) + ": an empty column name");
      continue;
    }
    const std::string at = file + ":" + std::to_string(number);
    if (fields.size() != table.columns.size())
      throw UsageError(at + ": " + std::to_string(fields.size()) + " fields, the header has " +
                       std::to_string(table.columns.size()));
    std::vector<double> row;
    for (size_t c = 0; c < fields.size(); ++c)
      row.push_back(parse_number(fields[c], at + ", column " + table.columns[c]));
    table.rows.push_back(row);
    table.lines.push_back(number);
  }
  if (table.columns.empty()) throw UsageError(file + ": no header line (column names)");
  if (table.rows.empty()) throw UsageError(file + ": no row after the header");
  return table;
}

std::vector<pcr::VecX> path_inputs(const pcr::RobotModel& model, const NumberTable& table,
                                   const pcr::VecX& base) {
  std::vector<int> index;
  for (const std::string& name : table.columns) {
    int found = -1;
    for (size_t i = 0; i < model.inputs().size(); ++i)
      if (model.inputs()[i].name == name) found = static_cast<int>(i);
    if (found < 0) {
      std::string valid;
      for (const pcr::ActuationInput& input : model.inputs())
        valid += (valid.empty() ? "" : ", ") + input.name;
      throw UsageError(table.file + ": column '" + name + "' names no input of model '" + model.name() +
                       "' (inputs: " + (valid.empty() ? "none" : valid) + ")");
    }
    if (std::find(index.begin(), index.end(), found) != index.end())
      throw UsageError(table.file + ": column '" + name + "' appears twice");
    index.push_back(found);
  }
  std::vector<pcr::VecX> out;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    pcr::VecX u = base;
    for (size_t c = 0; c < index.size(); ++c) {
      const pcr::ActuationInput& input = model.inputs()[static_cast<size_t>(index[c])];
      const double value = table.rows[r][c];
      if (value < input.lower || value > input.upper) {
        std::ostringstream message;
        message << where(table, r) << ": " << input.name << " = " << value << " is outside its bounds ["
                << input.lower << ", " << input.upper << "]";
        throw UsageError(message.str());
      }
      u[index[c]] = value;
    }
    out.push_back(u);
  }
  return out;
}

TargetPath path_targets(const pcr::RobotModel& model, const NumberTable& table) {
  TargetPath path;
  std::vector<TargetColumn> columns;
  std::vector<std::array<bool, 7>> given;  // per target: which of x, y, z, qw, qx, qy, qz have a column
  for (const std::string& name : table.columns) {
    const size_t dot = name.rfind('.');
    const std::string link = dot == std::string::npos ? "" : name.substr(0, dot);
    const std::string part = dot == std::string::npos ? name : name.substr(dot + 1);
    const auto component = std::find(std::begin(kPoseComponents), std::end(kPoseComponents), part);
    if (link.empty() || component == std::end(kPoseComponents))
      throw UsageError(table.file + ": column '" + name +
                       "': expected LINK.x, LINK.y, LINK.z, LINK.qw, LINK.qx, LINK.qy or LINK.qz");
    model.link_index(link);  // InputError naming an unknown link
    auto target = std::find_if(path.targets.begin(), path.targets.end(),
                               [&](const pcr::LinkTarget& t) { return t.link == link; });
    if (target == path.targets.end()) {
      path.targets.emplace_back();
      path.targets.back().link = link;
      given.push_back({});
      target = path.targets.end() - 1;
    }
    TargetColumn column{static_cast<int>(target - path.targets.begin()),
                        static_cast<int>(component - std::begin(kPoseComponents))};
    bool& seen = given[static_cast<size_t>(column.target)][static_cast<size_t>(column.component)];
    if (seen) throw UsageError(table.file + ": column '" + name + "' appears twice");
    seen = true;
    columns.push_back(column);
  }
  for (size_t t = 0; t < path.targets.size(); ++t) {
    const std::array<bool, 7>& g = given[t];
    const int quaternion = g[3] + g[4] + g[5] + g[6];
    if (quaternion != 0 && quaternion != 4)
      throw UsageError(table.file + ": target '" + path.targets[t].link +
                       "' has part of a quaternion: give all of LINK.qw, LINK.qx, LINK.qy, LINK.qz or none");
    const bool position = g[0] || g[1] || g[2];
    path.targets[t].mode = !position         ? pcr::LinkTarget::Mode::Orientation
                           : quaternion == 4 ? pcr::LinkTarget::Mode::Pose
                                             : pcr::LinkTarget::Mode::Position;
    for (int k = 0; k < 3; ++k)
      path.targets[t].components[static_cast<size_t>(k)] = g[static_cast<size_t>(k)];
  }
  for (size_t r = 0; r < table.rows.size(); ++r) {
    std::vector<pcr::Pose> poses(path.targets.size());
    std::vector<pcr::Quat> quaternions(path.targets.size(), pcr::Quat::Zero());
    for (size_t c = 0; c < columns.size(); ++c) {
      const TargetColumn& column = columns[c];
      const double value = table.rows[r][c];
      if (column.component < 3)
        poses[static_cast<size_t>(column.target)].position[column.component] = value;
      else
        quaternions[static_cast<size_t>(column.target)][column.component - 3] = value;
    }
    for (size_t t = 0; t < path.targets.size(); ++t) {
      if (path.targets[t].mode == pcr::LinkTarget::Mode::Position) continue;
      if (!(quaternions[t].norm() > 1e-12))
        throw UsageError(where(table, r) + ": the quaternion of target '" + path.targets[t].link +
                         "' is zero");
      poses[t].orientation = quaternions[t].normalized();
    }
    path.poses.push_back(poses);
  }
  return path;
}

}  // namespace pcr_app
